//! External loads at load factor 1, as a full dof vector: nodal forces on node groups,
//! pressures and tractions on edge groups (dead loads on the reference geometry).

use crate::error::{Error, Result};
use crate::fem::element::{shape, shape_grad, MAX_NODES};
use crate::fem::material::Modelisation;
use crate::fem::quadrature::line;
use crate::mesh::topology::{edge_parent, edge_parents};
use crate::mesh::Mesh;

#[derive(Clone, Copy, Debug)]
pub enum EdgeLoad {
    /// Normal pressure, positive pushing into the body.
    Pressure(f64),
    /// Traction vector per unit area.
    Traction([f64; 2]),
}

/// Adds `force` at each node of `nodes`.
pub fn add_nodal_force(f: &mut [f64], nodes: &[usize], force: [f64; 2]) {
    for &n in nodes {
        f[2 * n] += force[0];
        f[2 * n + 1] += force[1];
    }
}

/// Integrates an edge load over the 1D cells of `group` and adds it to `f`.
pub fn add_edge_load(
    mesh: &Mesh,
    group: &str,
    load: EdgeLoad,
    model: Modelisation,
    thickness: f64,
    f: &mut [f64],
) -> Result<()> {
    let cells = mesh.cell_group(group)?;
    let parents = edge_parents(mesh);
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
            let mut n = [0.0; MAX_NODES];
            let mut dn = [[0.0; 2]; MAX_NODES];
            shape(kind, xi, &mut n);
            shape_grad(kind, xi, &mut dn);
            let mut t = [0.0; 2];
            let mut r = 0.0;
            for a in 0..nn {
                let x = mesh.coords[nodes[a]];
                t[0] += dn[a][0] * x[0];
                t[1] += dn[a][0] * x[1];
                r += n[a] * x[0];
            }
            // Right-hand normal of the tangent (|t| = ds/dξ), outward if same_dir.
            let sign = if same_dir { 1.0 } else { -1.0 };
            let normal = [sign * t[1], -sign * t[0]];
            let measure = match model {
                Modelisation::Axisymmetric => 2.0 * std::f64::consts::PI * r,
                _ => thickness,
            };
            let jac = (t[0] * t[0] + t[1] * t[1]).sqrt();
            let w = rule.weights[q] * measure;
            let traction_ds = match load {
                // -p n ds: normal has length ds/dξ already
                EdgeLoad::Pressure(p) => [-p * normal[0] * w, -p * normal[1] * w],
                EdgeLoad::Traction(tr) => [tr[0] * jac * w, tr[1] * jac * w],
            };
            for a in 0..nn {
                f[2 * nodes[a]] += n[a] * traction_ds[0];
                f[2 * nodes[a] + 1] += n[a] * traction_ds[1];
            }
        }
    }
    Ok(())
}
