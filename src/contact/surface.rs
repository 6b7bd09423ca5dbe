//! Contact surfaces: the Seg2/Seg3 cells of an edge group, checked to form one connected
//! chain, each with the 2D cell it bounds (so that the outward normal is known).

use crate::error::{Error, Result};
use crate::mesh::topology::{edge_parent, edge_parents};
use crate::mesh::Mesh;
use std::collections::HashMap;

#[derive(Clone, Debug)]
pub struct Surface {
    pub group: String,
    /// The 1D cells of the group.
    pub cells: Vec<usize>,
    /// For each cell, whether its node order runs counter-clockwise around its parent 2D
    /// cell (then the right-hand normal of dx/dξ points out of the body).
    pub ccw: Vec<bool>,
    /// The parent 2D cell of each edge cell.
    pub parent: Vec<usize>,
    /// All nodes of the surface, sorted.
    pub nodes: Vec<usize>,
}

impl Surface {
    pub fn from_group(mesh: &Mesh, group: &str, role: &str) -> Result<Surface> {
        let cells = mesh
            .cell_group(group)
            .map_err(|e| Error::model(format!("{role} surface: {e}")))?
            .to_vec();
        if cells.is_empty() {
            return Err(Error::model(format!("{role} surface '{group}' is empty")));
        }
        let parents = edge_parents(mesh);
        let mut ccw = vec![];
        let mut parent = vec![];
        let mut degree: HashMap<usize, usize> = HashMap::new();
        for &c in &cells {
            let kind = mesh.kind(c);
            if kind.dim() != 1 {
                return Err(Error::model(format!(
                    "{role} surface '{group}' holds a {kind} cell; contact surfaces are groups of Seg2/Seg3 edges"
                )));
            }
            let (p, same) = edge_parent(mesh, &parents, c).ok_or_else(|| {
                Error::model(format!(
                    "{role} surface '{group}': edge cell {} is not a side of any 2D cell",
                    c + 1
                ))
            })?;
            ccw.push(same);
            parent.push(p);
            let nodes = mesh.cell_nodes(c);
            for &n in &nodes[..2] {
                *degree.entry(n).or_insert(0) += 1;
            }
        }
        // One connected chain, open (2 ends) or closed (a hole, a full ring: no end).
        let ends = degree.values().filter(|&&d| d == 1).count();
        if degree.values().any(|&d| d > 2) || (ends != 2 && ends != 0) || !connected(mesh, &cells) {
            return Err(Error::model(format!(
                "{role} surface '{group}' is not a single connected chain of edges (check the group: \
                 it must be one open or closed curve)"
            )));
        }
        let mut nodes: Vec<usize> = cells
            .iter()
            .flat_map(|&c| mesh.cell_nodes(c).iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        Ok(Surface {
            group: group.to_string(),
            cells,
            ccw,
            parent,
            nodes,
        })
    }
}

fn connected(mesh: &Mesh, cells: &[usize]) -> bool {
    let mut comp: HashMap<usize, usize> = HashMap::new();
    fn find(comp: &mut HashMap<usize, usize>, x: usize) -> usize {
        let p = *comp.entry(x).or_insert(x);
        if p == x {
            x
        } else {
            let r = find(comp, p);
            comp.insert(x, r);
            r
        }
    }
    for &c in cells {
        let n = mesh.cell_nodes(c);
        let (a, b) = (find(&mut comp, n[0]), find(&mut comp, n[1]));
        comp.insert(a, b);
    }
    let keys: Vec<usize> = comp.keys().copied().collect();
    let roots: std::collections::HashSet<usize> =
        keys.into_iter().map(|k| find(&mut comp, k)).collect();
    roots.len() == 1
}
