//! VTU entries: an ASCII file written by hand (two quadrangles, two edges, a node group),
//! and the binary forms (appended raw, inline base64, zlib) of our writer.

use super::{Entry, Set};
use std::io::Write;

const BASE: &str = r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">
<UnstructuredGrid>
<Piece NumberOfPoints="6" NumberOfCells="4">
<Points>
<DataArray type="Float64" NumberOfComponents="3" format="ascii">
0 0 0  1 0 0  2 0 0  0 1 0  1 1 0  2 1 0
</DataArray>
</Points>
<Cells>
<DataArray type="Int64" Name="connectivity" format="ascii">0 1 4 3  1 2 5 4  0 1  3 0</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">4 8 10 12</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">9 9 3 3</DataArray>
</Cells>
<CellData>
<DataArray type="Int32" Name="group_Body" format="ascii">1 1 0 0</DataArray>
<DataArray type="Int32" Name="group_Bottom" format="ascii">0 0 1 0</DataArray>
</CellData>
<PointData>
<DataArray type="Float64" Name="nodes_P" format="ascii">1 0 0 0 0 0</DataArray>
</PointData>
</Piece>
</UnstructuredGrid>
</VTKFile>
"#;

const POINTS: &str = "0 0 0  1 0 0  2 0 0  0 1 0  1 1 0  2 1 0";
const CONN: &str = "0 1 4 3  1 2 5 4  0 1  3 0";

/// The file of our writer for the two quadrangles of the MSH base.
fn written() -> Vec<u8> {
    let mesh = tribo::mesh::gmsh::parse(super::msh22::BASE.as_bytes(), "base").unwrap();
    let p = std::env::temp_dir().join(format!("mesh-corpus-{}.vtu", std::process::id()));
    tribo::post::vtu::write_mesh(&p, &mesh).unwrap();
    let b = std::fs::read(&p).unwrap();
    let _ = std::fs::remove_file(&p);
    b
}

fn zlib(data: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    e.write_all(data).unwrap();
    e.finish().unwrap()
}

/// Points as one zlib block in appended data whose header announces `announced` bytes
/// and holds `data` compressed.
fn zlib_points(announced: u64, data: &[u8]) -> Vec<u8> {
    let z = zlib(data);
    let mut raw = vec![];
    for w in [1u64, announced, announced, z.len() as u64] {
        raw.extend(w.to_le_bytes());
    }
    raw.extend(&z);
    let mut f = BASE
        .replace(
            "header_type=\"UInt64\"",
            "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\"",
        )
        .replace(
            &format!("format=\"ascii\">\n{POINTS}\n</DataArray>"),
            "format=\"appended\" offset=\"0\"/>",
        )
        .replace("</VTKFile>\n", "")
        .into_bytes();
    f.extend(b"<AppendedData encoding=\"raw\">\n_");
    f.extend(raw);
    f.extend(b"\n</AppendedData>\n</VTKFile>\n");
    f
}

pub fn entries() -> Vec<Entry> {
    let mut s = Set {
        base: BASE,
        ext: "vtu",
        prefix: "vtu",
        out: vec![],
    };
    s.ok("base", BASE.into(), 6, 4);
    // connectivity
    s.sub(
        "conn_negative",
        CONN,
        "-1 1 4 3  1 2 5 4  0 1  3 0",
        "cell 1: node index -1 is not one of the 6 points (0 to 5)",
    );
    s.sub(
        "conn_out_of_range",
        CONN,
        "0 1 4 3  1 2 6 4  0 1  3 0",
        "cell 2: node index 6 is not one of the 6 points (0 to 5)",
    );
    s.sub(
        "conn_float",
        CONN,
        "0 1 4 3  1 2 5 4  0 1.0  3 0",
        "array 'connectivity': '1.0' is not an integer",
    );
    s.sub(
        "conn_huge",
        CONN,
        "0 1 4 3  1 2 5 4  0 1  3 99999999999999999999",
        "array 'connectivity': '99999999999999999999' is not an integer",
    );
    s.sub(
        "conn_short",
        CONN,
        "0 1 4 3  1 2 5 4  0 1  3",
        "array 'connectivity': 11 values, expected 12",
    );
    s.sub(
        "quad_repeated_node",
        CONN,
        "0 1 4 4  1 2 5 4  0 1  3 0",
        "cell 1: node index 4 appears twice",
    );
    s.sub(
        "seg_repeated_node",
        CONN,
        "0 1 4 3  1 2 5 4  0 1  3 3",
        "cell 4: node index 3 appears twice",
    );
    s.sub(
        "quad_bowtie",
        CONN,
        "0 4 1 3  1 2 5 4  0 1  3 0",
        "cell 1 (Quad4) is inverted or tangled",
    );
    s.sub_ok("quad_clockwise", CONN, "3 4 1 0  1 2 5 4  0 1  3 0", 6, 4);
    // offsets and types
    s.sub(
        "offsets_decreasing",
        "4 8 10 12",
        "4 2 10 12",
        "cell 2: offsets give -2 nodes for a Quad4 (offset 2 after 4)",
    );
    s.sub(
        "offsets_negative",
        "4 8 10 12",
        "4 8 10 -12",
        "cell 4: offset -12 is negative",
    );
    s.sub(
        "offsets_huge",
        "4 8 10 12",
        "4 8 10 1000000000000000",
        "array 'connectivity': 12 values, expected 1000000000000000",
    );
    s.sub(
        "offsets_short",
        "4 8 10 12",
        "4 8 10",
        "array 'offsets': 3 values, expected 4",
    );
    s.sub(
        "type_unknown",
        "9 9 3 3",
        "9 12 3 3",
        "cell 2: VTK cell type 12 is not supported",
    );
    s.sub(
        "type_negative",
        "9 9 3 3",
        "9 9 -3 3",
        "cell 3: VTK cell type -3 is not supported",
    );
    s.sub(
        "type_tri_for_quad",
        "9 9 3 3",
        "5 9 3 3",
        "cell 1: offsets give 4 nodes for a Tri3",
    );
    s.sub(
        "type_float",
        "9 9 3 3",
        "9 9 3 3.5",
        "array 'types': '3.5' is not an integer",
    );
    // points
    s.sub(
        "points_nan",
        POINTS,
        "0 0 0  nan 0 0  2 0 0  0 1 0  1 1 0  2 1 0",
        "node 2 has a non-finite coordinate",
    );
    s.sub(
        "points_inf",
        POINTS,
        "0 0 0  1 0 0  2 0 0  0 1 0  1 inf 0  2 1 0",
        "node 5 has a non-finite coordinate",
    );
    s.sub(
        "points_z",
        POINTS,
        "0 0 0  1 0 0  2 0 0.5  0 1 0  1 1 0  2 1 0",
        "point 3 has z = 0.5: 3D meshes are not supported",
    );
    s.sub(
        "points_short",
        POINTS,
        "0 0 0  1 0 0  2 0 0  0 1 0  1 1 0  2 1",
        "array 'Points': 17 values, expected 18",
    );
    s.sub(
        "points_word",
        POINTS,
        "0 0 0  1 0 0  2 0 0  0 1 0  1 one 0  2 1 0",
        "array 'Points': 'one' is not a number",
    );
    s.sub(
        "points_components_4",
        "NumberOfComponents=\"3\"",
        "NumberOfComponents=\"4\"",
        "points with 4 components",
    );
    s.sub("no_points", "<Points>", "<Pointz>", "no <Points> array");
    // counts
    s.sub(
        "npoints_more",
        "NumberOfPoints=\"6\"",
        "NumberOfPoints=\"7\"",
        "array 'Points': 18 values, expected 21",
    );
    s.sub(
        "npoints_huge",
        "NumberOfPoints=\"6\"",
        "NumberOfPoints=\"1000000000000\"",
        "array 'Points': 18 values, expected 3000000000000",
    );
    s.sub(
        "npoints_overflow",
        "NumberOfPoints=\"6\"",
        "NumberOfPoints=\"9223372036854775807\"",
        "NumberOfPoints 9223372036854775807 is too large",
    );
    s.sub(
        "npoints_negative",
        "NumberOfPoints=\"6\"",
        "NumberOfPoints=\"-6\"",
        "<Piece> without a valid NumberOfPoints",
    );
    s.sub(
        "ncells_more",
        "NumberOfCells=\"4\"",
        "NumberOfCells=\"5\"",
        "array 'types': 4 values, expected 5",
    );
    s.sub(
        "ncells_huge",
        "NumberOfCells=\"4\"",
        "NumberOfCells=\"18446744073709551615\"",
        "array 'types': 4 values, expected 18446744073709551615",
    );
    s.sub(
        "ncells_zero",
        "NumberOfCells=\"4\"",
        "NumberOfCells=\"0\"",
        "array 'types': 4 values, expected 0",
    );
    // groups
    s.sub(
        "group_short",
        "\"ascii\">1 1 0 0</DataArray>",
        "\"ascii\">1 1 0</DataArray>",
        "array 'group_Body': 3 values, expected 4",
    );
    s.sub(
        "group_nan",
        "\"ascii\">1 1 0 0</DataArray>",
        "\"ascii\">1 nan 0 0</DataArray>",
        "array 'group_Body': value NaN of cell 2 is not a 0/1 flag",
    );
    s.sub(
        "group_half",
        "\"ascii\">0 0 1 0</DataArray>",
        "\"ascii\">0 0 0.5 0</DataArray>",
        "array 'group_Bottom': value 0.5 of cell 3 is not a 0/1 flag",
    );
    s.sub(
        "nodes_flag_two",
        "1 0 0 0 0 0",
        "1 0 0 0 0 2",
        "array 'nodes_P': value 2 of point 6 is not a 0/1 flag",
    );
    s.sub_ok(
        "group_empty",
        "\"ascii\">0 0 1 0</DataArray>",
        "\"ascii\">0 0 0 0</DataArray>",
        6,
        4,
    );
    // structure
    s.text("empty", "", "not a VTK XML file (no <VTKFile>)");
    s.text("not_xml", "hello\n", "not a VTK XML file (no <VTKFile>)");
    s.sub(
        "polydata",
        "type=\"UnstructuredGrid\"",
        "type=\"PolyData\"",
        "VTK file of type 'PolyData', expected UnstructuredGrid",
    );
    s.sub(
        "big_endian",
        "LittleEndian",
        "BigEndian",
        "big-endian VTU files are not supported",
    );
    s.sub(
        "compressor_lz4",
        "header_type=\"UInt64\"",
        "header_type=\"UInt64\" compressor=\"vtkLZ4DataCompressor\"",
        "compressor 'vtkLZ4DataCompressor' is not supported",
    );
    s.sub(
        "two_pieces",
        "</UnstructuredGrid>",
        "<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\"></Piece>\n</UnstructuredGrid>",
        "tribo reads VTU files with exactly one <Piece>",
    );
    s.sub(
        "format_hex",
        "Name=\"offsets\" format=\"ascii\"",
        "Name=\"offsets\" format=\"hex\"",
        "array 'offsets': format 'hex' is not one of ascii, binary, appended",
    );
    s.sub(
        "unterminated_array",
        "4 8 10 12</DataArray>",
        "4 8 10 12",
        "array 'offsets': '<DataArray' is not an integer",
    );
    s.sub(
        "no_connectivity",
        "Name=\"connectivity\"",
        "Name=\"connexions\"",
        "no 'connectivity' array in <Cells>",
    );
    s.cut("cut_half", "<Cells>", "no 'types' array in <Cells>");
    s.cut(
        "cut_in_array",
        "0 0 0  1 0",
        "<DataArray> without </DataArray>",
    );
    s.bytes(
        "not_utf8",
        BASE.replacen("<Cells>", "<Cells>\u{1}", 1)
            .bytes()
            .map(|b| if b == 1 { 0xff } else { b })
            .collect(),
        "the XML part is not UTF-8",
    );
    // binary forms of our writer
    let w = written();
    let text = String::from_utf8_lossy(&w).to_string();
    let data_at = w.windows(2).position(|x| x == b"\n_").unwrap() + 2;
    s.ok("appended", w.clone(), 6, 9);
    s.bytes(
        "appended_cut",
        w[..data_at + 100].to_vec(),
        "array 'Points' (appended at 0): 144 bytes announced, 92 present",
    );
    s.bytes(
        "appended_no_data",
        w[..data_at - 2].to_vec(),
        "appended data without its '_' marker",
    );
    let mut big = w.clone();
    big[data_at..data_at + 8].copy_from_slice(&u64::MAX.to_le_bytes());
    s.bytes(
        "appended_size_huge",
        big,
        "array 'Points' (appended at 0): 18446744073709551615 bytes announced",
    );
    let mut off = w.clone();
    let at = text.find("offset=\"152\"").unwrap();
    off.splice(at..at + 12, b"offset=\"9999\"".iter().copied());
    s.bytes(
        "appended_offset_beyond",
        off,
        "array 'connectivity': offset 9999 beyond the data",
    );
    let mut neg = w.clone();
    let c = data_at + 152 + 8; // the first connectivity value
    neg[c..c + 8].copy_from_slice(&(-1i64).to_le_bytes());
    s.bytes(
        "appended_conn_negative",
        neg,
        "cell 1: node index -1 is not one of the 6 points",
    );
    let mut far = w.clone();
    far[c..c + 8].copy_from_slice(&(1i64 << 40).to_le_bytes());
    s.bytes(
        "appended_conn_huge",
        far,
        "cell 1: node index 1099511627776 is not one of the 6 points",
    );
    let mut nan = w.clone();
    nan[data_at + 8..data_at + 16].copy_from_slice(&f64::NAN.to_le_bytes());
    s.bytes(
        "appended_points_nan",
        nan,
        "node 1 has a non-finite coordinate",
    );
    let mut enc = w.clone();
    let at = text.find("encoding=\"raw\"").unwrap();
    enc.splice(at..at + 14, b"encoding=\"base64\"".iter().copied());
    s.bytes(
        "appended_base64",
        enc,
        "appended data encoding 'base64' is not supported (only raw)",
    );
    // inline base64
    let pts: Vec<u8> = [
        0.0f64, 0., 0., 1., 0., 0., 2., 0., 0., 0., 1., 0., 1., 1., 0., 2., 1., 0.,
    ]
    .iter()
    .flat_map(|v| v.to_le_bytes())
    .collect();
    let b64 = |b: &[u8]| {
        use base64::Engine;
        base64::engine::general_purpose::STANDARD.encode(b)
    };
    let mut framed = (pts.len() as u64).to_le_bytes().to_vec();
    framed.extend(&pts);
    let inline = |payload: &str| {
        BASE.replace(
            &format!("format=\"ascii\">\n{POINTS}\n</DataArray>"),
            &format!("format=\"binary\">\n{payload}\n</DataArray>"),
        )
    };
    s.ok("base64", inline(&b64(&framed)).into_bytes(), 6, 4);
    s.text(
        "base64_invalid",
        &inline("AAAAAAAAAAAAAAAA$$$$"),
        "array 'Points' (binary): invalid base64",
    );
    s.text(
        "base64_short",
        &inline(&b64(&framed[..100])),
        "array 'Points' (binary):",
    );
    // zlib: a valid one, a lying header, a bomb (10 MB of zeros announced for 18 values)
    s.ok("zlib", zlib_points(144, &pts), 6, 4);
    s.bytes(
        "zlib_wrong_size",
        zlib_points(140, &pts),
        "array 'Points' (appended at 0): block 1: 141 bytes after decompression, expected 140",
    );
    s.bytes(
        "zlib_bomb",
        zlib_points(10_000_000, &vec![0u8; 10_000_000]),
        "array 'Points' (appended at 0): 10000000 bytes announced for 18 values",
    );
    s.bytes(
        "zlib_garbage",
        {
            let mut f = zlib_points(144, &pts);
            let n = f.len();
            for b in &mut f[n - 60..n - 40] {
                *b ^= 0x5a;
            }
            f
        },
        "array 'Points' (appended at 0): block 1: zlib:",
    );
    s.out
}
