//! VTK unstructured-grid (.vtu) writer for ParaView: XML header with raw appended binary
//! data (little-endian, UInt64 block headers). The file is built in memory and written
//! through a temporary file and a rename, so it is never seen half-written.

use crate::error::Result;
use crate::mesh::Mesh;
use std::path::Path;

pub enum Field<'a> {
    /// Point data with `ncomp` components per node, with optional component names.
    Point {
        name: &'a str,
        ncomp: usize,
        values: &'a [f64],
        components: &'a [&'a str],
    },
    /// Cell data over the written cells.
    Cell {
        name: &'a str,
        ncomp: usize,
        values: &'a [f64],
    },
    CellInt {
        name: &'a str,
        values: &'a [i32],
    },
}

/// Writes the cells `cells` of `mesh` (all nodes are written) with the given fields.
pub fn write(path: &Path, mesh: &Mesh, cells: &[usize], fields: &[Field]) -> Result<()> {
    crate::error::write_atomic(path, &to_bytes(mesh, cells, fields))
}

/// `text` as an XML attribute value (group names are the user's: `a<b&"c'` stays that).
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // (a parser would turn them into spaces)
            '\n' | '\r' | '\t' => out.push_str(&format!("&#{};", c as u32)),
            c => out.push(c),
        }
    }
    out
}

pub fn to_bytes(mesh: &Mesh, cells: &[usize], fields: &[Field]) -> Vec<u8> {
    let mut xml = String::new();
    let mut data: Vec<u8> = vec![];
    let mut append = |bytes: Vec<u8>| -> usize {
        let off = data.len();
        data.extend_from_slice(&(bytes.len() as u64).to_le_bytes());
        data.extend_from_slice(&bytes);
        off
    };
    let f64s =
        |v: &mut dyn Iterator<Item = f64>| -> Vec<u8> { v.flat_map(|x| x.to_le_bytes()).collect() };
    xml.push_str("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n");
    xml.push_str(&format!(
        "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
        mesh.num_nodes(),
        cells.len()
    ));
    let pts = append(f64s(
        &mut mesh.coords.iter().flat_map(|p| [p[0], p[1], 0.0]),
    ));
    xml.push_str(&format!(
        "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"{pts}\"/></Points>\n"
    ));
    let conn: Vec<u8> = cells
        .iter()
        .flat_map(|&c| mesh.cell_nodes(c).iter().map(|&n| n as i64))
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let mut acc = 0i64;
    let offs: Vec<u8> = cells
        .iter()
        .flat_map(|&c| {
            acc += mesh.cell_nodes(c).len() as i64;
            acc.to_le_bytes()
        })
        .collect();
    let types: Vec<u8> = cells.iter().map(|&c| mesh.kind(c).vtk_type()).collect();
    let (o1, o2, o3) = (append(conn), append(offs), append(types));
    xml.push_str(&format!(
        "<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"{o1}\"/>\n\
         <DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"{o2}\"/>\n\
         <DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"{o3}\"/>\n</Cells>\n"
    ));
    let mut point_xml = String::new();
    let mut cell_xml = String::new();
    for f in fields {
        match f {
            Field::Point {
                name,
                ncomp,
                values,
                components,
            } => {
                let off = append(f64s(&mut values.iter().copied()));
                let name = escape(name);
                let names: String = components
                    .iter()
                    .enumerate()
                    .map(|(i, c)| format!(" ComponentName{i}=\"{}\"", escape(c)))
                    .collect();
                point_xml.push_str(&format!(
                    "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"{ncomp}\"{names} format=\"appended\" offset=\"{off}\"/>\n"
                ));
            }
            Field::Cell {
                name,
                ncomp,
                values,
            } => {
                let off = append(f64s(&mut values.iter().copied()));
                let name = escape(name);
                cell_xml.push_str(&format!(
                    "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"{ncomp}\" format=\"appended\" offset=\"{off}\"/>\n"
                ));
            }
            Field::CellInt { name, values } => {
                let off = append(values.iter().flat_map(|v| v.to_le_bytes()).collect());
                let name = escape(name);
                cell_xml.push_str(&format!(
                    "<DataArray type=\"Int32\" Name=\"{name}\" format=\"appended\" offset=\"{off}\"/>\n"
                ));
            }
        }
    }
    xml.push_str(&format!(
        "<PointData>\n{point_xml}</PointData>\n<CellData>\n{cell_xml}</CellData>\n"
    ));
    xml.push_str("</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_");
    let mut out = xml.into_bytes();
    out.extend_from_slice(&data);
    out.extend_from_slice(b"\n</AppendedData>\n</VTKFile>\n");
    out
}

/// Membership flags of the written `cells` in each cell group ("group_NAME", 1 or 0),
/// for groups that hold at least one of them.
pub fn cell_group_flags(mesh: &Mesh, cells: &[usize]) -> Vec<(String, Vec<i32>)> {
    let mut out = vec![];
    for (name, members) in &mesh.cell_groups {
        let mut flag = vec![0i32; mesh.num_cells()];
        for &c in members {
            flag[c] = 1;
        }
        let vals: Vec<i32> = cells.iter().map(|&c| flag[c]).collect();
        if vals.contains(&1) {
            out.push((format!("group_{name}"), vals));
        }
    }
    out
}

/// Membership flags of the nodes in each explicit node group ("nodes_NAME", 1.0 or 0.0).
pub fn node_group_flags(mesh: &Mesh) -> Vec<(String, Vec<f64>)> {
    mesh.node_groups
        .iter()
        .map(|(name, nodes)| {
            let mut flag = vec![0.0; mesh.num_nodes()];
            for &n in nodes {
                flag[n] = 1.0;
            }
            (format!("nodes_{name}"), flag)
        })
        .collect()
}

/// The mesh alone, every cell (0D to 2D), with its groups as cell and point flags.
pub fn write_mesh(path: &Path, mesh: &Mesh) -> Result<()> {
    let cells: Vec<usize> = (0..mesh.num_cells()).collect();
    let cell_flags = cell_group_flags(mesh, &cells);
    let node_flags = node_group_flags(mesh);
    let dims: Vec<i32> = cells.iter().map(|&c| mesh.kind(c).dim() as i32).collect();
    let mut fields = vec![Field::CellInt {
        name: "cell_dim",
        values: &dims,
    }];
    for (name, vals) in &cell_flags {
        fields.push(Field::CellInt { name, values: vals });
    }
    for (name, vals) in &node_flags {
        fields.push(Field::Point {
            name,
            ncomp: 1,
            values: vals,
            components: &[],
        });
    }
    write(path, mesh, &cells, &fields)
}

/// A ParaView collection (.pvd): one dataset per (time, file name relative to the .pvd).
pub fn write_pvd(path: &Path, entries: &[(f64, String)]) -> Result<()> {
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n<Collection>\n",
    );
    for (t, file) in entries {
        let file = escape(file);
        xml.push_str(&format!(
            "<DataSet timestep=\"{t:e}\" group=\"\" part=\"0\" file=\"{file}\"/>\n"
        ));
    }
    xml.push_str("</Collection>\n</VTKFile>\n");
    crate::error::write_atomic(path, xml.as_bytes())
}
