//! Stresses: at Gauss points, extrapolated to the nodes of each cell (ELNO), and nodal
//! values as the unweighted mean of the ELNO values of the cells sharing a node
//! (contact.md §3.4–3.5; this defines SIYY at B).

use crate::assembly::Assembler;
use crate::error::{Error, Result};
use crate::fem::extrapolate;
use crate::fem::material::von_mises;
use crate::fem::solid::{gauss_stresses_as, StressMeasure};
use crate::mesh::Mesh;

/// Extrapolated stresses of every assembled cell: for assembled cell i,
/// `elno[offsets[i] + a]` is the stress [xx, yy, zz, xy] at its local node a.
pub struct CellNodeStresses {
    pub offsets: Vec<usize>,
    pub values: Vec<[f64; 4]>,
}

pub fn cell_node_stresses(mesh: &Mesh, asm: &Assembler, u: &[f64]) -> Result<CellNodeStresses> {
    cell_node_stresses_as(mesh, asm, u, StressMeasure::Cauchy)
}

/// `cell_node_stresses` in the given measure (Cauchy or second Piola–Kirchhoff).
pub fn cell_node_stresses_as(
    mesh: &Mesh,
    asm: &Assembler,
    u: &[f64],
    measure: StressMeasure,
) -> Result<CellNodeStresses> {
    let mut offsets = vec![0];
    let mut values = vec![];
    let mut gauss = [[0.0; 4]; 9];
    for (i, &c) in asm.cells.iter().enumerate() {
        let kind = mesh.kind(c);
        let (x, nn) = mesh.cell_coords(c);
        let mut ue = [[0.0; 2]; 8];
        for (a, &n) in mesh.cell_nodes(c).iter().enumerate() {
            ue[a] = [u[2 * n], u[2 * n + 1]];
        }
        let sm = &asm.cell_model[i];
        gauss_stresses_as(kind, &x[..nn], &ue[..nn], sm, measure, &mut gauss).map_err(|_| {
            Error::solve(format!(
                "cell {} ({kind}) has a non-positive Jacobian",
                c + 1
            ))
        })?;
        let e = extrapolate::matrix(kind);
        for row in e.iter().take(nn) {
            let mut s = [0.0; 4];
            for (g, w) in row.iter().enumerate() {
                for k in 0..4 {
                    s[k] += w * gauss[g][k];
                }
            }
            values.push(s);
        }
        offsets.push(values.len());
    }
    Ok(CellNodeStresses { offsets, values })
}

/// Nodal stresses: mean over the assembled cells that contain the node and, if `group` is
/// given, belong to that cell group. Nodes in no such cell get NaN.
pub fn nodal_stresses(
    mesh: &Mesh,
    asm: &Assembler,
    elno: &CellNodeStresses,
    group: Option<&str>,
) -> Result<Vec<[f64; 4]>> {
    let member: Option<Vec<bool>> = match group {
        Some(g) => {
            let mut m = vec![false; mesh.num_cells()];
            for &c in mesh.cell_group(g)? {
                m[c] = true;
            }
            Some(m)
        }
        None => None,
    };
    let mut sum = vec![[0.0; 4]; mesh.num_nodes()];
    let mut count = vec![0usize; mesh.num_nodes()];
    for (i, &c) in asm.cells.iter().enumerate() {
        if member.as_ref().is_some_and(|m| !m[c]) {
            continue;
        }
        for (a, &n) in mesh.cell_nodes(c).iter().enumerate() {
            let s = elno.values[elno.offsets[i] + a];
            for k in 0..4 {
                sum[n][k] += s[k];
            }
            count[n] += 1;
        }
    }
    Ok(sum
        .iter()
        .zip(&count)
        .map(|(s, &c)| {
            if c == 0 {
                [f64::NAN; 4]
            } else {
                s.map(|v| v / c as f64)
            }
        })
        .collect())
}

pub fn nodal_von_mises(stresses: &[[f64; 4]]) -> Vec<f64> {
    stresses.iter().map(von_mises).collect()
}
