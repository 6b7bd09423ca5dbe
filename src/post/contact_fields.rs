//! The contact outputs of a contact problem's current state, per pair: the pressures,
//! shear and multipliers the formulation reports, and the nodal values with their sums
//! (`contact_summary`), open nodes exactly 0 in both.

use super::contact_state::{Multipliers, OPEN};
use super::contact_summary::{pair_result, PairInput, PairResult};
use crate::assembly::coupled::Triplets;
use crate::contact::problem::ContactProblem;
use crate::error::{Error, Result};
use crate::fem::solid::Kinematics;

/// The contact outputs of a state, per pair: pressures, (μ, shear), multipliers, and the
/// nodal values with their sums.
pub struct ContactFields {
    pub pressure: Vec<Vec<(usize, f64)>>,
    pub shear: Vec<(f64, Vec<(usize, f64)>)>,
    pub multipliers: Vec<Multipliers>,
    pub pairs: Vec<PairResult>,
}

impl ContactFields {
    pub fn none() -> Self {
        ContactFields {
            pressure: vec![],
            shear: vec![],
            multipliers: vec![],
            pairs: vec![],
        }
    }
}

/// Per pair: nodal pressures, (μ, nodal shear) from the multipliers (open nodes exactly
/// 0), the raw multipliers, and the nodal values with their sums.
pub fn contact_fields(cp: &ContactProblem, axisymmetric: bool) -> Result<ContactFields> {
    let (mut pressures, mut shear, mut multipliers) = (vec![], vec![], vec![]);
    for (p, &b) in cp.pairs.iter().zip(&cp.mult_base) {
        let lam = &cp.lam[b..b + p.num_multipliers()];
        pressures.push(p.nodal_pressures(lam));
        shear.push((p.friction(), p.nodal_shear(lam)));
        multipliers.push(p.nodal_multipliers(lam));
    }
    // never a non-finite value in an output
    for (i, (p, s)) in pressures.iter().zip(&shear).enumerate() {
        if let Some(&(n, v)) = p.iter().chain(&s.1).find(|(_, v)| !v.is_finite()) {
            return Err(Error::Solve(format!(
                "[[contact]] {}: the contact traction at node {} is {v} (a degenerate \
                 contact there: a node with no share of the surface?)",
                i + 1,
                n + 1
            )));
        }
    }
    // the forces each pair applies: its contact terms of the residual, alone
    let mesh = cp.solid.mesh;
    let mut pairs = vec![];
    for (i, (p, &b)) in cp.pairs.iter().zip(&cp.mult_base).enumerate() {
        let n = p.num_multipliers();
        let mut ru = vec![0.0; cp.solid.u.len()];
        let mut rl = vec![0.0; n];
        let lam = &cp.lam[b..b + n];
        p.contribute(
            mesh,
            &cp.solid.u,
            lam,
            &mut ru,
            &mut rl,
            &mut Triplets::default(),
            b,
        );
        let (slave, master) = p.surfaces();
        pairs.push(pair_result(&PairInput {
            mesh,
            u: &cp.solid.u,
            slave,
            master,
            pressure: &pressures[i],
            shear: &shear[i].1,
            mu: shear[i].0,
            residual: &ru,
            axisymmetric,
            large: cp
                .solid
                .asm
                .cell_model
                .iter()
                .any(|m| m.kinematics == Kinematics::Large),
            reference_normals: p.reference_normals(),
            gap_allowance: p.overlap_allowance(),
        }));
    }
    // the outputs from the multipliers too: open nodes exactly 0
    for ((r, pr), sh) in pairs.iter().zip(&mut pressures).zip(&mut shear) {
        let open: std::collections::HashSet<usize> = r
            .nodes
            .iter()
            .filter(|c| c.status == OPEN)
            .map(|c| c.node)
            .collect();
        for (n, v) in pr.iter_mut().chain(sh.1.iter_mut()) {
            if open.contains(n) {
                *v = 0.0;
            }
        }
    }
    Ok(ContactFields {
        pressure: pressures,
        shear,
        multipliers,
        pairs,
    })
}
