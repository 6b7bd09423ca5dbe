//! The mesh: 2D node coordinates, cells of mixed kinds, named groups.
//!
//! | file | what |
//! |---|---|
//! | `cell.rs` | `CellKind`: node counts, local edges, orientation permutations |
//! | `builder.rs` | `MeshBuilder`: readers and generators push nodes, cells and groups; `finish` checks and orients, and puts 2D cells in no group into `ungrouped` |
//! | `topology.rs` | edge → parent cell adjacency, outward orientation |
//! | `quality.rs` | min angle, max aspect ratio, bounding box |
//! | `gmsh/` | Gmsh MSH 4.1 (ASCII, binary) and 2.2 (ASCII) reader |
//! | `med.rs` | MED (HDF5) mesh reader |
//! | `gmsh_write.rs`, `med_write.rs` | MSH 4.1/2.2 and MED writers (`tribo mesh convert`) |
//! | `families.rs` | entities partitioned by their set of groups (for the writers) |
//! | `vtu_read.rs` | VTU mesh reader (uncompressed ASCII / raw appended) |
//! | `compare.rs` | are two meshes the same (nodes, cells, groups)? |
//! | `refine.rs` | uniform refinement: every cell split n × n, groups kept (`tribo mesh refine`) |
//! | `quadtree.rs` | balanced quadtree → conforming graded quad/triangle cells |
//! | `fasthash.rs` | a fast hasher for the generators' integer-keyed maps |
//! | `generate.rs` | built-in meshes: SSNP154 geometry, rectangles, rings |
//!
//! Invariants of a finished `Mesh`: every node index is in range, every 2D cell is
//! counter-clockwise with a positive Jacobian at its corners and centre.

mod builder;
pub mod cell;
pub mod compare;
mod families;
pub(crate) mod fasthash;
pub mod generate;
pub mod gmsh;
pub mod gmsh_write;
pub mod med;
pub mod med_write;
pub mod quadtree;
pub mod quality;
pub mod refine;
pub mod topology;
pub mod vtu_read;

pub use builder::MeshBuilder;
pub use cell::CellKind;

use crate::error::{Error, Result};
use std::collections::BTreeMap;

/// The group of the 2D cells that a mesh file puts in no group (every reader makes it; a
/// mesh group of that name beside such cells is an error).
pub const DEFAULT_GROUP: &str = "ungrouped";

#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Node coordinates (x, y); in axisymmetry x is the radius.
    pub coords: Vec<[f64; 2]>,
    kinds: Vec<CellKind>,
    offsets: Vec<usize>,
    conn: Vec<usize>,
    /// Named cell groups (cell indices, sorted). Point cells make 0D groups.
    pub cell_groups: BTreeMap<String, Vec<usize>>,
    /// Named node groups given explicitly (e.g. by a MED node family).
    pub node_groups: BTreeMap<String, Vec<usize>>,
    /// Number of 2D cells that were given clockwise and were reordered.
    pub reoriented: usize,
}

impl Mesh {
    pub fn num_nodes(&self) -> usize {
        self.coords.len()
    }
    pub fn num_cells(&self) -> usize {
        self.kinds.len()
    }
    pub fn kind(&self, cell: usize) -> CellKind {
        self.kinds[cell]
    }
    pub fn cell_nodes(&self, cell: usize) -> &[usize] {
        &self.conn[self.offsets[cell]..self.offsets[cell + 1]]
    }
    /// Indices of all cells of topological dimension `dim`.
    pub fn cells_of_dim(&self, dim: usize) -> impl Iterator<Item = usize> + '_ {
        (0..self.num_cells()).filter(move |&c| self.kinds[c].dim() == dim)
    }
    /// Count of cells per kind.
    pub fn kind_counts(&self) -> BTreeMap<CellKind, usize> {
        let mut m = BTreeMap::new();
        for &k in &self.kinds {
            *m.entry(k).or_insert(0) += 1;
        }
        m
    }

    /// Names of all groups (cell groups and explicit node groups), for error messages.
    pub fn group_names(&self) -> Vec<String> {
        let mut names: Vec<String> = self.cell_groups.keys().cloned().collect();
        for k in self.node_groups.keys() {
            if !self.cell_groups.contains_key(k) {
                names.push(k.clone());
            }
        }
        names.sort();
        names
    }

    fn unknown_group(&self, name: &str) -> Error {
        Error::model(format!(
            "group '{}' is not in the mesh; groups are: {}",
            name,
            self.group_names().join(", ")
        ))
    }

    /// Cells of a named cell group.
    pub fn cell_group(&self, name: &str) -> Result<&[usize]> {
        self.cell_groups
            .get(name)
            .map(|v| v.as_slice())
            .ok_or_else(|| self.unknown_group(name))
    }

    /// Topological dimension of a cell group (the largest cell dimension in it).
    pub fn group_dim(&self, name: &str) -> Option<usize> {
        if let Some(cells) = self.cell_groups.get(name) {
            return cells.iter().map(|&c| self.kinds[c].dim()).max();
        }
        self.node_groups.get(name).map(|_| 0)
    }

    /// Nodes of a group, sorted and unique: the explicit node group if there is one,
    /// otherwise the nodes of the cells of the cell group of that name.
    pub fn node_group(&self, name: &str) -> Result<Vec<usize>> {
        if let Some(nodes) = self.node_groups.get(name) {
            return Ok(nodes.clone());
        }
        Ok(self.nodes_of_cells(self.cell_group(name)?))
    }

    /// The nodes of these cells, sorted and unique.
    pub fn nodes_of_cells(&self, cells: &[usize]) -> Vec<usize> {
        let listed: usize = cells.iter().map(|&c| self.cell_nodes(c).len()).sum();
        if listed < self.num_nodes() / 16 {
            let mut nodes: Vec<usize> = cells
                .iter()
                .flat_map(|&c| self.cell_nodes(c).iter().copied())
                .collect();
            nodes.sort_unstable();
            nodes.dedup();
            return nodes;
        }
        // a large group: marking is linear where sorting its node list is not
        let mut member = vec![false; self.num_nodes()];
        for &c in cells {
            for &n in self.cell_nodes(c) {
                member[n] = true;
            }
        }
        (0..member.len()).filter(|&n| member[n]).collect()
    }

    /// The single node of a group that must hold exactly one node (e.g. B, C, Force).
    pub fn single_node(&self, name: &str) -> Result<usize> {
        let nodes = self.node_group(name)?;
        match nodes.as_slice() {
            [n] => Ok(*n),
            _ => Err(Error::model(format!(
                "group '{}' must hold exactly one node, it holds {}",
                name,
                nodes.len()
            ))),
        }
    }

    /// Coordinates of the nodes of a cell, in a fixed-size buffer.
    pub fn cell_coords(&self, cell: usize) -> ([[f64; 2]; crate::fem::element::MAX_NODES], usize) {
        let mut x = [[0.0; 2]; crate::fem::element::MAX_NODES];
        let nodes = self.cell_nodes(cell);
        for (a, &n) in nodes.iter().enumerate() {
            x[a] = self.coords[n];
        }
        (x, nodes.len())
    }

    /// node → list of 2D cells that contain it (CSR layout: offsets, cells).
    pub fn node_to_cells(&self, dim: usize) -> (Vec<usize>, Vec<usize>) {
        let mut count = vec![0usize; self.num_nodes() + 1];
        for c in self.cells_of_dim(dim) {
            for &n in self.cell_nodes(c) {
                count[n + 1] += 1;
            }
        }
        for i in 0..self.num_nodes() {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        let mut cells = vec![0usize; count[self.num_nodes()]];
        for c in self.cells_of_dim(dim) {
            for &n in self.cell_nodes(c) {
                cells[fill[n]] = c;
                fill[n] += 1;
            }
        }
        (count, cells)
    }
}

/// Reads a mesh file: Gmsh `.msh`, MED `.med`/`.mmed` or `.vtu`, by extension, or by
/// content when the extension is none of these (HDF5 signature: MED, `$MeshFormat`: Gmsh,
/// XML: VTU).
pub fn read(path: &std::path::Path) -> Result<Mesh> {
    match MeshFormat::of_path(path)? {
        MeshFormat::Gmsh => gmsh::read(path),
        MeshFormat::Med => med::read(path),
        MeshFormat::Vtu => vtu_read::read(path),
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    Gmsh,
    Med,
    Vtu,
}

impl MeshFormat {
    fn of_path(path: &std::path::Path) -> Result<MeshFormat> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase());
        match ext.as_deref() {
            Some("msh") => return Ok(MeshFormat::Gmsh),
            Some("med" | "mmed" | "rmed") => return Ok(MeshFormat::Med),
            Some("vtu") => return Ok(MeshFormat::Vtu),
            _ => {}
        }
        let mut head = [0u8; 64];
        let n = {
            use std::io::Read;
            let mut f = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
            f.read(&mut head).map_err(|e| Error::io(path, e))?
        };
        let head = &head[..n];
        if head.starts_with(b"\x89HDF\r\n\x1a\n") {
            Ok(MeshFormat::Med)
        } else if String::from_utf8_lossy(head)
            .trim_start()
            .starts_with("$MeshFormat")
        {
            Ok(MeshFormat::Gmsh)
        } else {
            Err(Error::model(format!(
                "{}: unknown mesh format (not a Gmsh .msh, MED/HDF5 or VTU file); \
                 supported: Gmsh MSH 4.1 (ASCII/binary) and 2.2 (ASCII), MED 3.x/4.x, VTU",
                path.display()
            )))
        }
    }
}
