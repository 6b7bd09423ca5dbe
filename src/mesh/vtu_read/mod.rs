//! VTK XML unstructured-grid (.vtu) mesh reader, for `tribo mesh convert`: data arrays
//! inline as ASCII or base64 `binary`, or appended raw, with UInt32 or UInt64 block
//! headers, optionally zlib-compressed (`data.rs`). Connectivity, offsets and types are
//! read as integers; a negative or out-of-range node index is an error naming the cell.
//!
//! Cells: VTK types 1, 3, 21, 5, 22, 9, 23 (vertex, line, quadratic edge, triangle,
//! quadratic triangle, quad, quadratic quad), whose node orders are ours. Groups: cell
//! data arrays `group_NAME` (non-zero = member) and point data arrays `nodes_NAME`, as
//! `post::vtu::write_mesh` writes them (names XML-escaped). z must be zero.

mod data;

use super::{CellKind, Mesh, MeshBuilder};
use crate::error::{Error, Result};
use data::{floats, ints, Array, Layout};
use std::collections::HashMap;
use std::path::Path;

pub fn read(path: &Path) -> Result<Mesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse(&bytes, &path.display().to_string())
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

/// Attributes of the tag starting at `s` (text after the tag name, up to `>`), values in
/// either quotes with their entities decoded.
fn attributes(s: &str) -> HashMap<String, String> {
    let mut out = HashMap::new();
    let mut rest = s;
    while let Some(eq) = rest.find('=') {
        let key = rest[..eq].trim().to_string();
        let after = rest[eq + 1..].trim_start();
        let Some(q) = after.chars().next().filter(|c| *c == '"' || *c == '\'') else {
            break;
        };
        let Some(end) = after[1..].find(q) else {
            break;
        };
        out.insert(key, unescape(&after[1..1 + end]));
        rest = &after[end + 2..];
    }
    out
}

/// XML text with its entities (&lt; &gt; &amp; &quot; &apos; &#N; &#xN;) decoded; an
/// unknown one is kept as written.
fn unescape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut rest = s;
    while let Some(amp) = rest.find('&') {
        out.push_str(&rest[..amp]);
        rest = &rest[amp..];
        let decoded = rest.find(';').and_then(|semi| {
            let c = match &rest[1..semi] {
                "lt" => '<',
                "gt" => '>',
                "amp" => '&',
                "quot" => '"',
                "apos" => '\'',
                e => {
                    let n = match e.strip_prefix("#x").or_else(|| e.strip_prefix("#X")) {
                        Some(h) => u32::from_str_radix(h, 16).ok()?,
                        None => e.strip_prefix('#')?.parse().ok()?,
                    };
                    char::from_u32(n)?
                }
            };
            Some((c, semi + 1))
        });
        match decoded {
            Some((c, len)) => {
                out.push(c);
                rest = &rest[len..];
            }
            None => {
                out.push('&');
                rest = &rest[1..];
            }
        }
    }
    out.push_str(rest);
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
    let zlib = match head.get("compressor").map(String::as_str) {
        None | Some("") => false,
        Some("vtkZLibDataCompressor") => true,
        Some(other) => {
            return Err(err(format!(
                "compressor '{other}' is not supported (only vtkZLibDataCompressor)"
            )))
        }
    };
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
    let layout = Layout {
        header64,
        zlib,
        appended: raw,
    };
    let values = |a: &Array, n: usize| floats(a, &layout, n).map_err(&err);
    let integers = |a: &Array, n: usize| ints(a, &layout, n).map_err(&err);
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
    let n_values = np
        .checked_mul(ncomp)
        .ok_or_else(|| err(format!("NumberOfPoints {np} is too large")))?;
    let xyz = values(pts, n_values)?;
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
    let cells = |name: &str| {
        find_array("Cells", Some(name)).ok_or_else(|| err(format!("no '{name}' array in <Cells>")))
    };
    let types = integers(cells("types")?, nc)?;
    let offsets = integers(cells("offsets")?, nc)?;
    let total = offsets.last().copied().unwrap_or(0);
    let total = usize::try_from(total)
        .map_err(|_| err(format!("cell {nc}: offset {total} is negative")))?;
    let conn = integers(cells("connectivity")?, total)?;
    let mut start = 0usize;
    for c in 0..nc {
        let kind = kind_of(types[c]).ok_or_else(|| {
            err(format!(
                "cell {}: VTK cell type {} is not supported (1, 3, 21, 5, 22, 9, 23)",
                c + 1,
                types[c]
            ))
        })?;
        let end = usize::try_from(offsets[c])
            .ok()
            .filter(|&e| e >= start && e <= conn.len() && e - start == kind.num_nodes())
            .ok_or_else(|| {
                err(format!(
                    "cell {}: offsets give {} nodes for a {kind} (offset {} after {start})",
                    c + 1,
                    offsets[c].saturating_sub(start as i64),
                    offsets[c]
                ))
            })?;
        let mut nodes = Vec::with_capacity(end - start);
        for &v in &conn[start..end] {
            let n = usize::try_from(v).ok().filter(|&n| n < np).ok_or_else(|| {
                err(format!(
                    "cell {}: node index {v} is not one of the {np} points (0 to {})",
                    c + 1,
                    np as i64 - 1
                ))
            })?;
            if nodes.contains(&n) {
                return Err(err(format!("cell {}: node index {n} appears twice", c + 1)));
            }
            nodes.push(n);
        }
        b.add_cell(kind, &nodes, c as u64 + 1);
        start = end;
    }
    for a in &arrays {
        let Some(name) = a.attrs.get("Name") else {
            continue;
        };
        if let (Some(g), "CellData") = (name.strip_prefix("group_"), a.section) {
            for c in members(&values(a, nc)?, name, "cell").map_err(&err)? {
                b.add_to_cell_group(g, c);
            }
        } else if let (Some(g), "PointData") = (name.strip_prefix("nodes_"), a.section) {
            for n in members(&values(a, np)?, name, "point").map_err(&err)? {
                b.add_to_node_group(g, n);
            }
        }
    }
    b.finish()
}

/// The entities flagged 1 in a group's flags; any value but 0 and 1 is an error (a NaN
/// or 0.5 would otherwise count as a member).
fn members(flags: &[f64], name: &str, what: &str) -> std::result::Result<Vec<usize>, String> {
    let mut out = vec![];
    for (i, &v) in flags.iter().enumerate() {
        if v == 1.0 {
            out.push(i);
        } else if v != 0.0 {
            return Err(format!(
                "array '{name}': value {v} of {what} {} is not a 0/1 flag",
                i + 1
            ));
        }
    }
    Ok(out)
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}
