//! Cell kinds, named by node count (Seg2, Tri6, Quad8, ...), and their local topology.
//! Node order is Gmsh's (= VTK's): corners counter-clockwise, then mid-side nodes, the
//! mid-side node of edge (i, i+1) first.

use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CellKind {
    Point1,
    Seg2,
    Seg3,
    Tri3,
    Tri6,
    Quad4,
    Quad8,
}

impl CellKind {
    pub const ALL: [CellKind; 7] = [
        CellKind::Point1,
        CellKind::Seg2,
        CellKind::Seg3,
        CellKind::Tri3,
        CellKind::Tri6,
        CellKind::Quad4,
        CellKind::Quad8,
    ];

    pub fn name(self) -> &'static str {
        match self {
            CellKind::Point1 => "Point1",
            CellKind::Seg2 => "Seg2",
            CellKind::Seg3 => "Seg3",
            CellKind::Tri3 => "Tri3",
            CellKind::Tri6 => "Tri6",
            CellKind::Quad4 => "Quad4",
            CellKind::Quad8 => "Quad8",
        }
    }

    pub fn num_nodes(self) -> usize {
        match self {
            CellKind::Point1 => 1,
            CellKind::Seg2 => 2,
            CellKind::Seg3 => 3,
            CellKind::Tri3 => 3,
            CellKind::Tri6 => 6,
            CellKind::Quad4 => 4,
            CellKind::Quad8 => 8,
        }
    }

    pub fn num_corners(self) -> usize {
        match self {
            CellKind::Point1 => 1,
            CellKind::Seg2 | CellKind::Seg3 => 2,
            CellKind::Tri3 | CellKind::Tri6 => 3,
            CellKind::Quad4 | CellKind::Quad8 => 4,
        }
    }

    /// Topological dimension: 0 for points, 1 for segments, 2 for surface cells.
    pub fn dim(self) -> usize {
        match self {
            CellKind::Point1 => 0,
            CellKind::Seg2 | CellKind::Seg3 => 1,
            _ => 2,
        }
    }

    pub fn is_quadratic(self) -> bool {
        matches!(self, CellKind::Seg3 | CellKind::Tri6 | CellKind::Quad8)
    }

    /// Local nodes of each edge of a 2D cell, in counter-clockwise order (corner, corner,
    /// mid-side); empty for points and segments.
    pub fn edges(self) -> &'static [&'static [usize]] {
        match self {
            CellKind::Tri3 => &[&[0, 1], &[1, 2], &[2, 0]],
            CellKind::Tri6 => &[&[0, 1, 3], &[1, 2, 4], &[2, 0, 5]],
            CellKind::Quad4 => &[&[0, 1], &[1, 2], &[2, 3], &[3, 0]],
            CellKind::Quad8 => &[&[0, 1, 4], &[1, 2, 5], &[2, 3, 6], &[3, 0, 7]],
            _ => &[],
        }
    }

    /// Kind of the edges of a 2D cell.
    pub fn edge_kind(self) -> Option<CellKind> {
        match self {
            CellKind::Tri3 | CellKind::Quad4 => Some(CellKind::Seg2),
            CellKind::Tri6 | CellKind::Quad8 => Some(CellKind::Seg3),
            _ => None,
        }
    }

    /// The permutation that turns a clockwise cell into a counter-clockwise one
    /// (`new[i] = old[perm[i]]`), the identity for points and segments.
    pub fn reverse_permutation(self) -> &'static [usize] {
        match self {
            CellKind::Point1 => &[0],
            CellKind::Seg2 => &[0, 1],
            CellKind::Seg3 => &[0, 1, 2],
            CellKind::Tri3 => &[0, 2, 1],
            CellKind::Tri6 => &[0, 2, 1, 5, 4, 3],
            CellKind::Quad4 => &[0, 3, 2, 1],
            CellKind::Quad8 => &[0, 3, 2, 1, 7, 6, 5, 4],
        }
    }

    /// For each mid-side node (index >= num_corners) the two corners it sits between.
    pub fn midside_corners(self) -> &'static [[usize; 2]] {
        match self {
            CellKind::Seg3 => &[[0, 1]],
            CellKind::Tri6 => &[[0, 1], [1, 2], [2, 0]],
            CellKind::Quad8 => &[[0, 1], [1, 2], [2, 3], [3, 0]],
            _ => &[],
        }
    }

    /// VTK cell type code.
    pub fn vtk_type(self) -> u8 {
        match self {
            CellKind::Point1 => 1,
            CellKind::Seg2 => 3,
            CellKind::Seg3 => 21,
            CellKind::Tri3 => 5,
            CellKind::Tri6 => 22,
            CellKind::Quad4 => 9,
            CellKind::Quad8 => 23,
        }
    }

    pub fn from_name(name: &str) -> Option<CellKind> {
        CellKind::ALL
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(name))
    }
}

impl fmt::Display for CellKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
