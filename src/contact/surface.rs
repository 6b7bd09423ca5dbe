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
    /// The parent 2D cell of each edge cell (none on a rigid surface).
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
                    "{role} surface '{group}': edge cell {} is not a side of any 2D cell (an \
                     edge group of no 2D cell is a rigid surface: give it a [[rigid]] entry \
                     with its reference point, and make it the master)",
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
        Ok(Surface::of_cells(mesh, group, cells, ccw, parent))
    }
}

impl Surface {
    /// A rigid surface (edges of no 2D cell, see `case::rigid`): `parent` is empty, and
    /// each cell's `ccw` says whether its right-hand normal points out of the rigid body.
    /// `made`: the cells were made with it so; else the chain is oriented consistently and
    /// its side is the one facing `toward` (the slave's nodes) at the cell nearest to them.
    pub fn rigid(mesh: &Mesh, group: &str, made: bool, toward: &[usize]) -> Result<Surface> {
        let cells = mesh
            .cell_group(group)
            .map_err(|e| Error::model(format!("master surface: {e}")))?
            .to_vec();
        if cells.is_empty() {
            return Err(Error::model(format!("master surface '{group}' is empty")));
        }
        let mut degree: HashMap<usize, Vec<usize>> = HashMap::new();
        for (k, &c) in cells.iter().enumerate() {
            for &n in &mesh.cell_nodes(c)[..2] {
                degree.entry(n).or_default().push(k);
            }
        }
        let ends: Vec<usize> = degree
            .iter()
            .filter(|(_, v)| v.len() == 1)
            .map(|(&n, _)| n)
            .collect();
        if degree.values().any(|v| v.len() > 2)
            || (ends.len() != 2 && !ends.is_empty())
            || !connected(mesh, &cells)
        {
            return Err(Error::model(format!(
                "rigid surface '{group}' is not a single connected chain of edges (check the \
                 group: it must be one open or closed curve)"
            )));
        }
        let mut ccw = vec![true; cells.len()];
        if !made {
            // walk the chain from an end (any node if closed): forward cells run along it
            let mut at = ends
                .iter()
                .copied()
                .min()
                .unwrap_or(mesh.cell_nodes(cells[0])[0]);
            let mut seen = vec![false; cells.len()];
            while let Some(&k) = degree[&at].iter().find(|&&k| !seen[k]) {
                seen[k] = true;
                let n = mesh.cell_nodes(cells[k]);
                ccw[k] = n[0] == at;
                at = if n[0] == at { n[1] } else { n[0] };
            }
            // the side facing the slave at the chord nearest to it
            let mid = |k: usize| {
                let n = mesh.cell_nodes(cells[k]);
                let (a, b) = (mesh.coords[n[0]], mesh.coords[n[1]]);
                (
                    [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])],
                    [b[0] - a[0], b[1] - a[1]],
                )
            };
            let mut best = (f64::INFINITY, 0, [0.0; 2]);
            for k in 0..cells.len() {
                let (m, _) = mid(k);
                for &s in toward {
                    let x = mesh.coords[s];
                    let d = (x[0] - m[0]).hypot(x[1] - m[1]);
                    if d < best.0 {
                        best = (d, k, x);
                    }
                }
            }
            let (_, k, x) = best;
            let (m, t) = mid(k);
            let right = [t[1], -t[0]];
            let facing = right[0] * (x[0] - m[0]) + right[1] * (x[1] - m[1]) > 0.0;
            if facing != ccw[k] {
                ccw.iter_mut().for_each(|c| *c = !*c);
            }
        }
        Ok(Surface::of_cells(mesh, group, cells, ccw, vec![]))
    }

    /// The surface of these edge cells (their orientations and parent 2D cells given),
    /// with its sorted nodes.
    fn of_cells(
        mesh: &Mesh,
        group: &str,
        cells: Vec<usize>,
        ccw: Vec<bool>,
        parent: Vec<usize>,
    ) -> Surface {
        let nodes = mesh.nodes_of_cells(&cells);
        Surface {
            group: group.to_string(),
            cells,
            ccw,
            parent,
            nodes,
        }
    }

    /// Whether this is a rigid surface (no parent 2D cells).
    pub fn is_rigid(&self) -> bool {
        self.parent.is_empty()
    }

    /// The shortest cell's length (the chord between its end nodes, on the initial
    /// geometry): the surface's finest scale.
    pub fn shortest_cell(&self, mesh: &Mesh) -> f64 {
        self.cells
            .iter()
            .map(|&c| {
                let n = mesh.cell_nodes(c);
                let (a, b) = (mesh.coords[n[0]], mesh.coords[n[1]]);
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
            .fold(f64::INFINITY, f64::min)
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
