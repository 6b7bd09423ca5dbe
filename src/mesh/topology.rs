//! Edge ↔ cell adjacency: which 2D cell an edge (Seg2/Seg3 cell or cell side) belongs to.

use super::Mesh;
use crate::union_find::UnionFind;
use std::collections::HashMap;

/// Map from an edge's sorted corner pair to (2D cell, local edge index) for every side of
/// every 2D cell; an interior side appears with one of its two cells.
pub fn edge_parents(mesh: &Mesh) -> HashMap<(usize, usize), (usize, usize)> {
    let mut map = HashMap::new();
    for c in mesh.cells_of_dim(2) {
        let nodes = mesh.cell_nodes(c);
        for (e, local) in mesh.kind(c).edges().iter().enumerate() {
            let (a, b) = (nodes[local[0]], nodes[local[1]]);
            map.insert((a.min(b), a.max(b)), (c, e));
        }
    }
    map
}

/// For a 1D cell, its parent 2D cell and whether the 1D cell runs in the same direction as
/// the parent's counter-clockwise side (then its right-hand normal points outward).
pub fn edge_parent(
    mesh: &Mesh,
    parents: &HashMap<(usize, usize), (usize, usize)>,
    edge_cell: usize,
) -> Option<(usize, bool)> {
    let nodes = mesh.cell_nodes(edge_cell);
    let (a, b) = (nodes[0], nodes[1]);
    let &(c, e) = parents.get(&(a.min(b), a.max(b)))?;
    let start = mesh.cell_nodes(c)[mesh.kind(c).edges()[e][0]];
    Some((c, start == a))
}

/// The body (connected set of 2D cells sharing nodes) of each node, numbered from 0;
/// usize::MAX for nodes of no 2D cell.
pub fn node_bodies(mesh: &Mesh) -> Vec<usize> {
    // union-find over nodes, joined through the corners of each 2D cell
    let mut sets = UnionFind::new(mesh.num_nodes());
    let mut used = vec![false; mesh.num_nodes()];
    for c in mesh.cells_of_dim(2) {
        let nodes = mesh.cell_nodes(c);
        for &n in nodes {
            used[n] = true;
            sets.join(nodes[0], n);
        }
    }
    let mut id: HashMap<usize, usize> = HashMap::new();
    (0..mesh.num_nodes())
        .map(|n| {
            if !used[n] {
                return usize::MAX;
            }
            let r = sets.root(n);
            let next = id.len();
            *id.entry(r).or_insert(next)
        })
        .collect()
}
