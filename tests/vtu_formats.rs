//! VTU files as other tools write them (issue 22): group names with XML's special
//! characters round-trip, inline base64 `binary` arrays (meshio's default) and
//! zlib-compressed blocks are read, and node indices are integers checked as such.

use base64::engine::general_purpose::STANDARD;
use base64::Engine;
use std::io::Write;
use std::path::PathBuf;
use std::process::Command;
use tribo::mesh::generate::rectangle;
use tribo::mesh::{vtu_read, CellKind, Mesh, MeshBuilder};

const ODD: &str = "a<b&\"c'";

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tribo-vtu-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A 2 × 1 Quad4 rectangle whose body group is named `ODD`.
fn odd_mesh() -> Mesh {
    let r = rectangle([0.0, 0.0], 2.0, 1.0, 2, 1, CellKind::Quad4, 0.0).unwrap();
    let mut b = MeshBuilder::new("odd");
    b.append(&r, |g| if g == "Body" { ODD.into() } else { g.into() });
    b.finish().unwrap()
}

#[test]
fn odd_group_names_round_trip_through_convert_and_run() {
    let d = temp_dir("odd");
    let mesh = odd_mesh();
    let msh = d.join("x.msh");
    tribo::mesh::gmsh_write::write(&msh, &mesh, tribo::mesh::gmsh_write::MshVersion::V41).unwrap();
    let vtu = d.join("y.vtu");
    let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(["mesh", "convert"])
        .arg(&msh)
        .arg(&vtu)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&std::fs::read(&vtu).unwrap()).into_owned();
    assert!(
        text.contains("Name=\"group_a&lt;b&amp;&quot;c&apos;\""),
        "not escaped"
    );
    let back = tribo::mesh::read(&vtu).unwrap();
    assert_eq!(back.group_names(), mesh.group_names());
    assert_eq!(back.cell_groups[ODD].len(), 2);
    // same nodes, cells and groups (cells in another order)
    let same = tribo::mesh::compare::compare(&mesh, &back, 1e-12);
    assert!(same.differences.is_empty(), "{:?}", same.differences);
    // result.vtu of a run on that mesh: the material group keeps its name
    let case = d.join("c.toml");
    std::fs::write(
        &case,
        r#"[mesh]
file = "x.msh"
[[material]]
group = "a<b&\"c'"
E = 1000.0
nu = 0.3
[[displacement]]
group = "Left"
dx = 0.0
dy = 0.0
[[force]]
group = "Right"
fx = 1.0
"#,
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .arg("run")
        .arg(&case)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let result = tribo::mesh::read(&d.join("c/result.vtu")).unwrap();
    assert_eq!(result.cell_groups[ODD].len(), 2);
    // the 2D cells, then the edges with their groups
    assert_eq!(
        result.cells_of_dim(2).count(),
        2,
        "result.vtu holds the 2D cells"
    );
    assert_eq!(result.cells_of_dim(1).count(), mesh.cells_of_dim(1).count());
    for g in mesh.group_names() {
        if mesh.group_dim(&g) == Some(1) {
            assert_eq!(
                result.cell_groups[&g].len(),
                mesh.cell_groups[&g].len(),
                "{g}"
            );
        }
    }
}

/// The arrays of a unit square (one Quad4) and its bottom edge (one Seg2, group
/// `Bottom`): (section, name, VTK type, components, little-endian bytes).
fn square_arrays() -> Vec<(&'static str, &'static str, &'static str, usize, Vec<u8>)> {
    let pts: Vec<u8> = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.]
        .iter()
        .flat_map(|v: &f64| v.to_le_bytes())
        .collect();
    let i64s = |v: &[i64]| -> Vec<u8> { v.iter().flat_map(|x| x.to_le_bytes()).collect() };
    let group: Vec<u8> = [0i32, 1].iter().flat_map(|x| x.to_le_bytes()).collect();
    vec![
        ("Points", "", "Float64", 3, pts),
        (
            "Cells",
            "connectivity",
            "Int64",
            1,
            i64s(&[0, 1, 2, 3, 0, 1]),
        ),
        ("Cells", "offsets", "Int64", 1, i64s(&[4, 6])),
        ("Cells", "types", "UInt8", 1, vec![9, 3]),
        ("CellData", "group_Bottom", "Int32", 1, group),
    ]
}

/// A VTU file of `square_arrays`, each array's element text made by `element`.
fn vtu(head: &str, element: impl Fn(&str, &str, usize, &[u8]) -> String) -> String {
    let mut sections = String::new();
    for section in ["Points", "Cells", "CellData"] {
        sections.push_str(&format!("<{section}>\n"));
        for (s, name, ty, ncomp, bytes) in square_arrays() {
            if s == section {
                sections.push_str(&element(name, ty, ncomp, &bytes));
            }
        }
        sections.push_str(&format!("</{section}>\n"));
    }
    format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" \
         byte_order=\"LittleEndian\" {head}>\n<UnstructuredGrid>\n\
         <Piece NumberOfPoints=\"4\" NumberOfCells=\"2\">\n{sections}</Piece>\n\
         </UnstructuredGrid>\n</VTKFile>\n"
    )
}

fn check_square(m: &Mesh) {
    assert_eq!(m.num_nodes(), 4);
    assert_eq!(m.coords[2], [1.0, 1.0]);
    assert_eq!(m.kind(0), CellKind::Quad4);
    assert_eq!(m.cell_nodes(0), &[0, 1, 2, 3]);
    assert_eq!(m.kind(1), CellKind::Seg2);
    assert_eq!(m.cell_groups["Bottom"], vec![1]);
}

fn open_tag(name: &str, ty: &str, ncomp: usize, format: &str) -> String {
    let name = if name.is_empty() {
        String::new()
    } else {
        format!(" Name=\"{name}\"")
    };
    format!("<DataArray type=\"{ty}\"{name} NumberOfComponents=\"{ncomp}\" format=\"{format}\"")
}

/// meshio's uncompressed binary: the UInt64 size and the data base64-encoded together.
#[test]
fn inline_base64_binary_is_read() {
    let text = vtu("header_type=\"UInt64\"", |name, ty, ncomp, bytes| {
        let mut block = (bytes.len() as u64).to_le_bytes().to_vec();
        block.extend_from_slice(bytes);
        format!(
            "{}>\n  {}\n</DataArray>\n",
            open_tag(name, ty, ncomp, "binary"),
            STANDARD.encode(&block)
        )
    });
    check_square(&vtu_read::parse(text.as_bytes(), "b64.vtu").unwrap());
}

/// zlib blocks of `size` bytes (the last one shorter): the UInt32 header
/// [blocks, size, last size, compressed sizes...] and the compressed blocks.
fn zlib_blocks(bytes: &[u8], size: usize) -> (Vec<u8>, Vec<u8>) {
    let chunks: Vec<&[u8]> = bytes.chunks(size).collect();
    let compressed: Vec<Vec<u8>> = chunks
        .iter()
        .map(|c| {
            let mut z = flate2::write::ZlibEncoder::new(vec![], flate2::Compression::default());
            z.write_all(c).unwrap();
            z.finish().unwrap()
        })
        .collect();
    let last = bytes.len() % size;
    let mut header = vec![chunks.len() as u32, size as u32, last as u32];
    header.extend(compressed.iter().map(|c| c.len() as u32));
    let header = header.iter().flat_map(|v| v.to_le_bytes()).collect();
    (header, compressed.concat())
}

/// VTK's compressed layout: inline arrays with the header and the blocks base64-encoded
/// apart, the cell types appended raw; the points in 3 blocks of 40 bytes (40, 40, 16).
#[test]
fn zlib_compressed_blocks_are_read_inline_and_appended() {
    let mut appended: Vec<u8> = vec![];
    let offsets = std::cell::RefCell::new(vec![]);
    let text = vtu(
        "header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\"",
        |name, ty, ncomp, bytes| {
            let (header, data) = zlib_blocks(bytes, 40);
            if name == "types" {
                let off = offsets.borrow().len();
                offsets.borrow_mut().push((header, data));
                return format!(
                    "{} offset=\"@{off}\"/>\n",
                    open_tag(name, ty, ncomp, "appended")
                );
            }
            format!(
                "{}>\n{}{}\n</DataArray>\n",
                open_tag(name, ty, ncomp, "binary"),
                STANDARD.encode(&header),
                STANDARD.encode(&data)
            )
        },
    );
    // the appended arrays at their byte offsets
    let mut text = text;
    for (k, (header, data)) in offsets.into_inner().into_iter().enumerate() {
        text = text.replace(
            &format!("offset=\"@{k}\""),
            &format!("offset=\"{}\"", appended.len()),
        );
        appended.extend(header);
        appended.extend(data);
    }
    let mut file = text
        .replace("</UnstructuredGrid>\n</VTKFile>\n", "</UnstructuredGrid>\n")
        .into_bytes();
    file.extend_from_slice(b"<AppendedData encoding=\"raw\">\n_");
    file.extend_from_slice(&appended);
    file.extend_from_slice(b"\n</AppendedData>\n</VTKFile>\n");
    check_square(&vtu_read::parse(&file, "z.vtu").unwrap());
    // a block that inflates to more than its header announces is refused: the types'
    // header [1 block, 40, last 2, ...] made [1, 40, 1, ...]
    let header: Vec<u8> = [1u32, 40, 2].iter().flat_map(|v| v.to_le_bytes()).collect();
    let at = file.windows(12).position(|w| w == header).unwrap();
    file[at + 8] = 1;
    assert_eq!(
        vtu_read::parse(&file, "z.vtu").unwrap_err().to_string(),
        "z.vtu: array 'types' (appended at 0): block 1: 2 bytes after decompression, expected 1"
    );
}

const ASCII: &str = r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">
<UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="2">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">
0 0 0  1 0 0  1 1 0  0 1 0</DataArray></Points>
<Cells>
<DataArray type="Int64" Name="connectivity" format="ascii">0 1 2 3 0 1</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">4 6</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">9 3</DataArray>
</Cells>
</Piece></UnstructuredGrid></VTKFile>
"#;

fn error(text: &str) -> String {
    vtu_read::parse(text.as_bytes(), "n.vtu")
        .unwrap_err()
        .to_string()
}

#[test]
fn node_indices_are_integers_in_range() {
    assert_eq!(
        error(&ASCII.replace("0 1 2 3 0 1", "0 1 2 -3 0 1")),
        "n.vtu: cell 1: node index -3 is not one of the 4 points (0 to 3)"
    );
    assert_eq!(
        error(&ASCII.replace("0 1 2 3 0 1", "0 1 2 3 0 4")),
        "n.vtu: cell 2: node index 4 is not one of the 4 points (0 to 3)"
    );
    assert_eq!(
        error(&ASCII.replace("0 1 2 3 0 1", "0 1 2 3 0 1.5")),
        "n.vtu: array 'connectivity': '1.5' is not an integer"
    );
    assert_eq!(
        error(&ASCII.replace("4 6", "4 -6")),
        "n.vtu: cell 2: offset -6 is negative"
    );
    // 2^53 + 1 is exact as an integer (through f64 it would read 2^53)
    let big = ASCII.replace("0 1 2 3 0 1", "0 1 2 3 0 9007199254740993");
    assert_eq!(
        error(&big),
        "n.vtu: cell 2: node index 9007199254740993 is not one of the 4 points (0 to 3)"
    );
    // binary: a Float64 connectivity is refused, not rounded
    let floats: Vec<u8> = [0.0f64, 1.0, 2.0, 3.0, 0.0, 1.0]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let mut block = (floats.len() as u64).to_le_bytes().to_vec();
    block.extend(floats);
    let text = ASCII.replace(
        "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3 0 1",
        &format!(
            "<DataArray type=\"Float64\" Name=\"connectivity\" format=\"binary\">{}",
            STANDARD.encode(&block)
        ),
    );
    assert_eq!(
        error(&text),
        "n.vtu: array 'connectivity': type Float64, expected an integer type"
    );
}
