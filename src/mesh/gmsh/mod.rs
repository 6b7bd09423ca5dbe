//! Gmsh MSH reader: format 4.1 (ASCII, and binary written on a little-endian machine with
//! 8-byte `size_t`) and format 2.2 (ASCII).
//!
//! Sections read: `$MeshFormat`, `$PhysicalNames`, `$Entities` (4.1), `$Nodes`,
//! `$Elements`; any other section (`$Periodic`, `$NodeData`, `$Comments`, ...) is skipped.
//!
//! - Element types: 15 (Point1), 1 (Seg2), 8 (Seg3), 2 (Tri3), 9 (Tri6), 3 (Quad4),
//!   16 (Quad8); Gmsh's node order is ours. Any other type is an error.
//! - Node tags may be sparse and in any order; nodes get dense indices in file order.
//! - z is dropped, but a node with |z| > 1e-12 × (bounding-box diagonal) is an error.
//! - Groups: each physical group of an element (4.1: the physical tags of its entity in
//!   `$Entities`; 2.2: its first tag) puts the cell in the cell group named in
//!   `$PhysicalNames`; a physical group without a name is an error. A 2.2 element
//!   repeated with the same number (Gmsh's way to put it in several groups) is one cell.
//!   When the file defines physical groups, elements outside all of them are dropped (as
//!   Gmsh does); their nodes stay. A file without any physical group keeps all its
//!   elements, in no group.
//! - Errors name the place: `file:line` in ASCII files, `file (byte N)` in binary ones,
//!   just `file` for problems of the whole file. Malformed input never panics; counts
//!   read from the file never size an allocation beyond what the remaining bytes can hold.
//!
//! | file | what |
//! |---|---|
//! | `mod.rs` | `read`, `parse`; element type tables, node map, the parser's state |
//! | `tokens.rs` | ASCII tokens and numbers, error places, section end markers |
//! | `binary.rs` | binary fields and the 4.1 numbers (`size_t`, `int`, `double`) in either encoding |
//! | `sections.rs` | the section loop, `$MeshFormat`, `$PhysicalNames`, what `$Nodes` and `$Elements` share |
//! | `msh41.rs` | MSH 4.1 `$Entities`, `$Nodes` and `$Elements` blocks |
//! | `msh22.rs` | MSH 2.2 `$Nodes` and `$Elements` |
//! | `finish.rs` | whole-file checks and the mesh: physical groups to cell groups |
//! | `tests/` | unit tests: reading, error messages, truncations and mutations |

mod binary;
mod finish;
mod msh22;
mod msh41;
mod sections;
#[cfg(test)]
mod tests;
mod tokens;

use super::{CellKind, Mesh, MeshBuilder};
use crate::error::{Error, Result};
use std::collections::HashMap;
use std::path::Path;

/// Reads a Gmsh MSH file; errors name the file.
pub fn read(path: &Path) -> Result<Mesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse(&bytes, &path.display().to_string())
}

/// Parses the bytes of a Gmsh MSH file; `source` names it in error messages.
pub fn parse(bytes: &[u8], source: &str) -> Result<Mesh> {
    Parser::new(bytes, source).run()
}

const SUPPORTED_VERSIONS: &str = "supported versions are 4.1 (ASCII or binary) and 2.2 (ASCII)";
const SUPPORTED_TYPES: &str =
    "15 (Point1), 1 (Seg2), 8 (Seg3), 2 (Tri3), 9 (Tri6), 3 (Quad4), 16 (Quad8)";

/// Our cell kind for a Gmsh element type number.
fn cell_kind(gmsh_type: i64) -> Option<CellKind> {
    Some(match gmsh_type {
        15 => CellKind::Point1,
        1 => CellKind::Seg2,
        8 => CellKind::Seg3,
        2 => CellKind::Tri3,
        9 => CellKind::Tri6,
        3 => CellKind::Quad4,
        16 => CellKind::Quad8,
        _ => return None,
    })
}

/// What a few unsupported Gmsh element types are, for error messages.
fn unsupported_type_name(gmsh_type: i64) -> Option<&'static str> {
    Some(match gmsh_type {
        4 => "4-node tetrahedron",
        5 => "8-node hexahedron",
        6 => "6-node prism",
        7 => "5-node pyramid",
        10 => "9-node quadrangle",
        11 => "10-node tetrahedron",
        12 => "27-node hexahedron",
        13 => "18-node prism",
        14 => "14-node pyramid",
        17 => "20-node hexahedron",
        18 => "15-node prism",
        19 => "13-node pyramid",
        20 => "9-node triangle",
        21 => "10-node triangle",
        26 => "4-node line",
        _ => return None,
    })
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Version {
    V22,
    V41,
}

/// Where a token or binary field starts: 1-based line and byte offset.
#[derive(Clone, Copy, Debug)]
struct Pos {
    line: usize,
    offset: usize,
}

/// A run of elements of one kind: a 4.1 entity block (`key` = entity tag, `dim` = entity
/// dimension) or consecutive 2.2 elements (`key` = physical tag, `dim` = cell dimension).
struct Block {
    kind: CellKind,
    dim: i64,
    key: i64,
    conn_start: usize,
    label_start: usize,
    count: usize,
}

const NO_NODE: usize = usize::MAX;

/// Node tag → dense index: a vector for small tags, a hash map for the others.
#[derive(Default)]
struct NodeMap {
    dense: Vec<usize>,
    dense_limit: u64,
    sparse: HashMap<u64, usize>,
}

impl NodeMap {
    /// Lets the dense part grow up to about twice the expected node count.
    fn expect(&mut self, nodes: usize) {
        let limit = (nodes as u64).saturating_mul(2).saturating_add(1024);
        self.dense_limit = self.dense_limit.max(limit);
    }

    /// Returns false if the tag is already there.
    fn insert(&mut self, tag: u64, index: usize) -> bool {
        if tag < self.dense_limit {
            let t = tag as usize;
            if t >= self.dense.len() {
                self.dense.resize(t + 1, NO_NODE);
            }
            if self.dense[t] != NO_NODE {
                return false;
            }
            self.dense[t] = index;
            true
        } else {
            self.sparse.insert(tag, index).is_none()
        }
    }

    fn get(&self, tag: u64) -> Option<usize> {
        if tag < self.dense_limit {
            match self.dense.get(tag as usize) {
                Some(&i) if i != NO_NODE => Some(i),
                _ => None,
            }
        } else {
            self.sparse.get(&tag).copied()
        }
    }
}

/// A token for an error message: at most 40 bytes, control characters escaped.
fn show(tok: &[u8]) -> String {
    let cut = &tok[..tok.len().min(40)];
    let mut s: String = String::from_utf8_lossy(cut).escape_debug().collect();
    if tok.len() > 40 {
        s.push_str("...");
    }
    s
}

struct Parser<'a> {
    data: &'a [u8],
    pos: usize,
    /// 1-based line number at `pos`.
    line: usize,
    source: &'a str,
    /// Binary file: places are byte offsets, and 4.1 sections hold binary numbers.
    binary: bool,
    /// The section being read, for end-of-file messages.
    section: &'static str,
    version: Version,
    builder: MeshBuilder,
    nodes: NodeMap,
    /// (dim, physical tag) → name.
    names: HashMap<(i64, i64), String>,
    /// (dim, entity tag) → physical tags (4.1).
    entities: Option<HashMap<(i64, i64), Vec<i64>>>,
    conn: Vec<usize>,
    labels: Vec<u64>,
    blocks: Vec<Block>,
    lo: [f64; 3],
    hi: [f64; 3],
    /// The node with the largest |z|: (z, tag, where).
    zmax: Option<(f64, u64, Pos)>,
    has_names: bool,
    has_nodes: bool,
    has_elements: bool,
}

impl<'a> Parser<'a> {
    fn new(data: &'a [u8], source: &'a str) -> Self {
        Parser {
            data,
            pos: 0,
            line: 1,
            source,
            binary: false,
            section: "",
            version: Version::V41,
            builder: MeshBuilder::new(source),
            nodes: NodeMap::default(),
            names: HashMap::new(),
            entities: None,
            conn: Vec::new(),
            labels: Vec::new(),
            blocks: Vec::new(),
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
            zmax: None,
            has_names: false,
            has_nodes: false,
            has_elements: false,
        }
    }
}
