//! VTK XML unstructured-grid (.vtu) mesh reader, for `tribo mesh convert` from the files
//! tribo (and most tools) write uncompressed: data arrays inline as ASCII or appended raw
//! (UInt32 or UInt64 block headers). Base64 and compressed data are clear errors.
//!
//! Cells: VTK types 1, 3, 21, 5, 22, 9, 23 (vertex, line, quadratic edge, triangle,
//! quadratic triangle, quad, quadratic quad), whose node orders are ours. Groups: cell
//! data arrays `group_NAME` (non-zero = member) and point data arrays `nodes_NAME`, as
//! `post::vtu::write_mesh` writes them. z must be zero.

use super::{CellKind, Mesh, MeshBuilder};
use crate::error::{Error, Result};
use std::collections::HashMap;
use std::path::Path;

pub fn read(path: &Path) -> Result<Mesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse(&bytes, &path.display().to_string())
}

/// One `<DataArray .../>` element: its attributes and, for inline ASCII, its text.
struct Array {
    attrs: HashMap<String, String>,
    text: String,
    section: &'static str,
}

fn kind_of(vtk: i64) -> Option<CellKind> {
    Some(match vtk {
        1 => CellKind::Point1,
        3 => CellKind::Seg2,
        21 => CellKind::Seg3,
        5 => CellKind::Tri3,
        22 => CellKind::Tri6,
        9 => CellKind::Quad4,
        23 => CellKind::Quad8,
        _ => return None,
    })
}

/// Attributes of the tag starting at `s` (text after the tag name, up to `>`).
fn attributes(s: &str) -> HashMap<String, String> {
    let mut out = HashMap::new();
    let mut rest = s;
    while let Some(eq) = rest.find('=') {
        let key = rest[..eq].trim().to_string();
        let after = &rest[eq + 1..];
        let Some(q0) = after.find('"') else { break };
        let Some(q1) = after[q0 + 1..].find('"') else {
            break;
        };
        out.insert(key, after[q0 + 1..q0 + 1 + q1].to_string());
        rest = &after[q0 + q1 + 2..];
    }
    out
}

pub fn parse(bytes: &[u8], source: &str) -> Result<Mesh> {
    let err = |msg: String| Error::parse(source, msg);
    // The XML part ends where the raw appended data starts.
    let (xml_end, raw) = match find(bytes, b"<AppendedData") {
        Some(at) => {
            let tag_end = find(&bytes[at..], b">")
                .ok_or_else(|| err("unterminated <AppendedData> tag".into()))?
                + at;
            let tag = String::from_utf8_lossy(&bytes[at..tag_end]);
            let enc = attributes(&tag["<AppendedData".len()..])
                .get("encoding")
                .cloned()
                .unwrap_or_default();
            if enc != "raw" {
                return Err(err(format!(
                    "appended data encoding '{enc}' is not supported (only raw)"
                )));
            }
            let us = find(&bytes[tag_end..], b"_")
                .ok_or_else(|| err("appended data without its '_' marker".into()))?
                + tag_end;
            (at, &bytes[us + 1..])
        }
        None => (bytes.len(), &bytes[..0]),
    };
    let xml = std::str::from_utf8(&bytes[..xml_end])
        .map_err(|_| err("the XML part is not UTF-8".into()))?;
    let head = attributes(
        xml.split_once("<VTKFile")
            .ok_or_else(|| err("not a VTK XML file (no <VTKFile>)".into()))?
            .1
            .split('>')
            .next()
            .unwrap_or(""),
    );
    if head.get("type").map(String::as_str) != Some("UnstructuredGrid") {
        return Err(err(format!(
            "VTK file of type '{}', expected UnstructuredGrid",
            head.get("type").cloned().unwrap_or_default()
        )));
    }
    if head.contains_key("compressor") {
        return Err(err("compressed VTU files are not supported".into()));
    }
    if head.get("byte_order").is_some_and(|b| b != "LittleEndian") {
        return Err(err("big-endian VTU files are not supported".into()));
    }
    let header64 = head.get("header_type").is_some_and(|h| h == "UInt64");
    if xml.matches("<Piece").count() != 1 {
        return Err(err("tribo reads VTU files with exactly one <Piece>".into()));
    }
    let piece = attributes(
        xml.split_once("<Piece")
            .unwrap()
            .1
            .split('>')
            .next()
            .unwrap_or(""),
    );
    let count = |k: &str| -> Result<usize> {
        piece
            .get(k)
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| err(format!("<Piece> without a valid {k}")))
    };
    let (np, nc) = (count("NumberOfPoints")?, count("NumberOfCells")?);

    // Collect the data arrays with the section they are in.
    let mut arrays = vec![];
    let mut section = "";
    let mut rest = xml;
    while let Some(lt) = rest.find('<') {
        rest = &rest[lt + 1..];
        let name_end = rest.find([' ', '>', '/']).unwrap_or(rest.len());
        let tag = &rest[..name_end];
        match tag {
            "Points" => section = "Points",
            "Cells" => section = "Cells",
            "PointData" => section = "PointData",
            "CellData" => section = "CellData",
            "DataArray" => {
                let end = rest
                    .find('>')
                    .ok_or_else(|| err("unterminated <DataArray>".into()))?;
                let attrs = attributes(&rest[name_end..end]);
                let self_closing = rest[..end].ends_with('/');
                let mut text = String::new();
                if !self_closing {
                    let close = rest[end..]
                        .find("</DataArray>")
                        .ok_or_else(|| err("<DataArray> without </DataArray>".into()))?;
                    text = rest[end + 1..end + close].to_string();
                }
                arrays.push(Array {
                    attrs,
                    text,
                    section,
                });
            }
            _ => {}
        }
    }
    let values = |a: &Array, expected: usize| -> Result<Vec<f64>> {
        let name = a
            .attrs
            .get("Name")
            .cloned()
            .unwrap_or_else(|| a.section.to_string());
        let ty = a.attrs.get("type").cloned().unwrap_or_default();
        let v = match a.attrs.get("format").map(String::as_str) {
            Some("ascii") => a
                .text
                .split_ascii_whitespace()
                .map(|t| t.parse::<f64>())
                .collect::<std::result::Result<Vec<f64>, _>>()
                .map_err(|_| err(format!("array '{name}': a value is not a number")))?,
            Some("appended") => {
                let off: usize = a
                    .attrs
                    .get("offset")
                    .and_then(|o| o.parse().ok())
                    .ok_or_else(|| err(format!("array '{name}': no valid offset")))?;
                let hl = if header64 { 8 } else { 4 };
                let block = raw
                    .get(off..off + hl)
                    .ok_or_else(|| err(format!("array '{name}': offset {off} beyond the data")))?;
                let len = if header64 {
                    u64::from_le_bytes(block.try_into().unwrap()) as usize
                } else {
                    u32::from_le_bytes(block.try_into().unwrap()) as usize
                };
                let data = raw
                    .get(off + hl..(off + hl).saturating_add(len))
                    .ok_or_else(|| err(format!("array '{name}': truncated data")))?;
                decode(data, &ty).ok_or_else(|| {
                    err(format!(
                        "array '{name}': type '{ty}' with {len} bytes is not readable"
                    ))
                })?
            }
            other => {
                return Err(err(format!(
                    "array '{name}': format '{}' is not supported (ascii or appended raw)",
                    other.unwrap_or("binary")
                )))
            }
        };
        if v.len() != expected {
            return Err(err(format!(
                "array '{name}': {} values, expected {expected}",
                v.len()
            )));
        }
        Ok(v)
    };
    let find_array = |section: &str, name: Option<&str>| {
        arrays.iter().find(|a| {
            a.section == section && name.is_none_or(|n| a.attrs.get("Name").is_some_and(|x| x == n))
        })
    };
    let pts = find_array("Points", None).ok_or_else(|| err("no <Points> array".into()))?;
    let ncomp: usize = pts
        .attrs
        .get("NumberOfComponents")
        .and_then(|c| c.parse().ok())
        .unwrap_or(1);
    if ncomp != 3 && ncomp != 2 {
        return Err(err(format!("points with {ncomp} components")));
    }
    let xyz = values(pts, np * ncomp)?;
    let mut b = MeshBuilder::new(source);
    for (i, p) in xyz.chunks(ncomp).enumerate() {
        if ncomp == 3 && p[2] != 0.0 {
            return Err(err(format!(
                "point {} has z = {}: 3D meshes are not supported",
                i + 1,
                p[2]
            )));
        }
        b.add_node([p[0], p[1]]);
    }
    let get = |name: &str, n: usize| -> Result<Vec<f64>> {
        let a = find_array("Cells", Some(name))
            .ok_or_else(|| err(format!("no '{name}' array in <Cells>")))?;
        values(a, n)
    };
    let types = get("types", nc)?;
    let offsets = get("offsets", nc)?;
    let total = offsets.last().copied().unwrap_or(0.0) as usize;
    let conn = get("connectivity", total)?;
    let mut start = 0usize;
    for c in 0..nc {
        let end = offsets[c] as usize;
        let kind = kind_of(types[c] as i64).ok_or_else(|| {
            err(format!(
                "cell {}: VTK cell type {} is not supported (1, 3, 21, 5, 22, 9, 23)",
                c + 1,
                types[c]
            ))
        })?;
        if end < start || end > conn.len() || end - start != kind.num_nodes() {
            return Err(err(format!(
                "cell {}: offsets give {} nodes for a {kind}",
                c + 1,
                end.saturating_sub(start)
            )));
        }
        let nodes: Vec<usize> = conn[start..end].iter().map(|&v| v as usize).collect();
        if nodes.iter().any(|&n| n >= np) {
            return Err(err(format!(
                "cell {}: node index beyond the {np} points",
                c + 1
            )));
        }
        b.add_cell(kind, &nodes, c as u64 + 1);
        start = end;
    }
    for a in &arrays {
        let Some(name) = a.attrs.get("Name") else {
            continue;
        };
        if let (Some(g), "CellData") = (name.strip_prefix("group_"), a.section) {
            for (c, v) in values(a, nc)?.iter().enumerate() {
                if *v != 0.0 {
                    b.add_to_cell_group(g, c);
                }
            }
        } else if let (Some(g), "PointData") = (name.strip_prefix("nodes_"), a.section) {
            for (n, v) in values(a, np)?.iter().enumerate() {
                if *v != 0.0 {
                    b.add_to_node_group(g, n);
                }
            }
        }
    }
    b.finish()
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

/// Little-endian values of a VTK scalar type, as f64 (exact for the integer sizes used).
fn decode(data: &[u8], ty: &str) -> Option<Vec<f64>> {
    macro_rules! read {
        ($t:ty) => {{
            let n = std::mem::size_of::<$t>();
            if data.len() % n != 0 {
                return None;
            }
            data.chunks(n)
                .map(|c| <$t>::from_le_bytes(c.try_into().unwrap()) as f64)
                .collect()
        }};
    }
    Some(match ty {
        "Float64" => read!(f64),
        "Float32" => read!(f32),
        "Int64" => read!(i64),
        "UInt64" => read!(u64),
        "Int32" => read!(i32),
        "UInt32" => read!(u32),
        "Int16" => read!(i16),
        "UInt16" => read!(u16),
        "Int8" => read!(i8),
        "UInt8" => read!(u8),
        _ => return None,
    })
}
