//! External loads: the integration points of edge loads (pressures and tractions on edge
//! groups, dead loads on the reference geometry). The case's loading multiplies each
//! point's weights by the load's value there (a number or an expression of x, y, t).

use crate::error::{Error, Result};
use crate::fem::element::{shape, shape_grad, MAX_NODES};
use crate::fem::material::Modelisation;
use crate::fem::quadrature::line;
use crate::mesh::topology::{edge_parent, edge_parents};
use crate::mesh::Mesh;

/// One integration point of an edge cell.
#[derive(Clone, Copy, Debug)]
pub struct EdgePoint {
    /// Position (reference geometry).
    pub x: [f64; 2],
    /// The edge cell.
    pub cell: usize,
    pub nodes: [usize; MAX_NODES],
    pub shape: [f64; MAX_NODES],
    pub num_nodes: usize,
    /// Outward normal times the weight (ds · thickness or ds · 2πr): a pressure p gives
    /// the force −p · normal_w.
    pub normal_w: [f64; 2],
    /// The weight: a traction t gives the force t · ds_w.
    pub ds_w: f64,
}

impl EdgePoint {
    /// (dof, coefficient) pairs of the force `dir` · value spread on the cell's nodes.
    pub fn terms(&self, dir: [f64; 2]) -> impl Iterator<Item = (usize, f64)> + '_ {
        (0..self.num_nodes).flat_map(move |a| {
            let n = self.nodes[a];
            [
                (2 * n, self.shape[a] * dir[0]),
                (2 * n + 1, self.shape[a] * dir[1]),
            ]
        })
    }
}

/// The integration points of the 1D cells of `group`, which must be sides of 2D cells
/// (the normal points out of them).
pub fn edge_points(
    mesh: &Mesh,
    group: &str,
    model: Modelisation,
    thickness: f64,
) -> Result<Vec<EdgePoint>> {
    let cells = mesh.cell_group(group)?;
    let parents = edge_parents(mesh);
    let mut out = vec![];
    for &c in cells {
        let kind = mesh.kind(c);
        if kind.dim() != 1 {
            return Err(Error::model(format!(
                "group '{group}' holds a {kind} cell; edge loads need a group of Seg2/Seg3 edges"
            )));
        }
        let Some((_, same_dir)) = edge_parent(mesh, &parents, c) else {
            return Err(Error::model(format!(
                "group '{group}': edge cell {} is not a side of any 2D cell",
                c + 1
            )));
        };
        let nodes = mesh.cell_nodes(c);
        let nn = nodes.len();
        let rule = line(nn);
        for (q, &xi) in rule.points.iter().enumerate() {
            let mut p = EdgePoint {
                x: [0.0; 2],
                cell: c,
                nodes: [0; MAX_NODES],
                shape: [0.0; MAX_NODES],
                num_nodes: nn,
                normal_w: [0.0; 2],
                ds_w: 0.0,
            };
            p.nodes[..nn].copy_from_slice(nodes);
            let mut dn = [[0.0; 2]; MAX_NODES];
            shape(kind, xi, &mut p.shape);
            shape_grad(kind, xi, &mut dn);
            let mut t = [0.0; 2];
            for a in 0..nn {
                let x = mesh.coords[nodes[a]];
                t[0] += dn[a][0] * x[0];
                t[1] += dn[a][0] * x[1];
                p.x[0] += p.shape[a] * x[0];
                p.x[1] += p.shape[a] * x[1];
            }
            // Right-hand normal of the tangent (|t| = ds/dξ), outward if same_dir.
            let sign = if same_dir { 1.0 } else { -1.0 };
            let measure = match model {
                Modelisation::Axisymmetric => 2.0 * std::f64::consts::PI * p.x[0],
                _ => thickness,
            };
            let w = rule.weights[q] * measure;
            p.normal_w = [sign * t[1] * w, -sign * t[0] * w];
            p.ds_w = (t[0] * t[0] + t[1] * t[1]).sqrt() * w;
            out.push(p);
        }
    }
    Ok(out)
}
