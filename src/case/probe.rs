//! Probes: the nodes a probe reads (its group, or the node nearest to its point) and its
//! value in a state.

use super::schema;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::post::stress::{nodal_stresses, CellNodeStresses};
use crate::solver::problem::SolidProblem;

/// How far from the mesh a probe point may be, in mesh sizes (the bounding box's
/// diagonal): farther, every node is about as near as any other in floating point.
const MAX_PROBE_DISTANCE: f64 = 1e6;

/// Stress component of a probe field (4 = von Mises), None for displacements.
fn probe_component(spec: &schema::ProbeSpec) -> Result<Option<usize>> {
    Ok(match spec.field.as_str() {
        "dx" | "dy" => None,
        "sixx" => Some(0),
        "siyy" => Some(1),
        "sizz" => Some(2),
        "sixy" => Some(3),
        "vmis" => Some(4),
        other => {
            return Err(Error::model(format!(
                "probe '{}': field '{other}' is not one of dx, dy, sixx, siyy, sizz, sixy, vmis",
                spec.name
            )))
        }
    })
}

/// The nodes a probe averages over: its group's, or the node nearest to its point.
pub fn probe_nodes(mesh: &Mesh, spec: &schema::ProbeSpec) -> Result<Vec<usize>> {
    let what = format!("probe '{}'", spec.name);
    match (&spec.group, spec.at) {
        (Some(g), None) => mesh
            .node_group(g)
            .map_err(|e| Error::model(format!("{what}: {e}"))),
        (None, Some(p)) => {
            let (lo, hi) = crate::mesh::quality::bounding_box(mesh);
            let size = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
            let out = |k: usize| (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0);
            if out(0).hypot(out(1)) > MAX_PROBE_DISTANCE * size {
                return Err(Error::model(format!(
                    "{what}: at = [{:e}, {:e}] is more than {MAX_PROBE_DISTANCE:e} times the mesh \
                     size ({size:.3e}) away from the mesh: no node is nearer than another there",
                    p[0], p[1]
                )));
            }
            let cells: Vec<usize> = match &spec.stress_group {
                Some(g) => mesh
                    .cell_group(g)
                    .map_err(|e| Error::model(format!("{what}: {e}")))?
                    .to_vec(),
                None => mesh.cells_of_dim(2).collect(),
            };
            let nearest = cells
                .iter()
                .flat_map(|&c| mesh.cell_nodes(c).iter().copied())
                .min_by(|&a, &b| {
                    let d = |n: usize| (mesh.coords[n][0] - p[0]).hypot(mesh.coords[n][1] - p[1]);
                    d(a).total_cmp(&d(b))
                })
                .ok_or_else(|| Error::model(format!("{what}: no node to probe")))?;
            Ok(vec![nearest])
        }
        _ => Err(Error::model(format!(
            "{what}: give either group = \"NAME\" or at = [x, y]"
        ))),
    }
}

/// Value of a probe: mean of the field over the nodes of its group (or at its node).
/// `elno` are the cell-node stresses of the state, `all` their average over every cell.
pub fn probe(
    problem: &SolidProblem,
    spec: &schema::ProbeSpec,
    elno: &CellNodeStresses,
    all: &[[f64; 4]],
) -> Result<f64> {
    let mesh = problem.mesh;
    let what = format!("probe '{}'", spec.name);
    let nodes = probe_nodes(mesh, spec)?;
    let comp = probe_component(spec)?;
    let values: Vec<f64> = match comp {
        None => {
            let c = if spec.field == "dx" { 0 } else { 1 };
            nodes.iter().map(|&n| problem.u[2 * n + c]).collect()
        }
        Some(k) => {
            let local;
            let s = match &spec.stress_group {
                Some(g) => {
                    local = nodal_stresses(mesh, &problem.asm, elno, Some(g))
                        .map_err(|e| Error::model(format!("{what}: {e}")))?;
                    &local
                }
                None => all,
            };
            nodes
                .iter()
                .map(|&n| {
                    if k == 4 {
                        crate::fem::material::von_mises(&s[n])
                    } else {
                        s[n][k]
                    }
                })
                .collect()
        }
    };
    if values.iter().any(|v| v.is_nan()) {
        return Err(Error::model(format!(
            "{what}: some nodes of group '{}' are in no cell of the stress group",
            spec.group.as_deref().unwrap_or("")
        )));
    }
    Ok(values.iter().sum::<f64>() / values.len() as f64)
}
