//! A cut load step starts again from the contact state its step started from. A failed
//! attempt may end far away (a diverging iterate slid a body several cells along the
//! other); restoring must bring back the statuses and the contact's candidate pairs of the
//! step start, whatever the attempt visited. (Mortar restored the candidates of the last
//! iterate: at 1.38M unknowns every retry of SSNP154 A's second load step then met an
//! active slave node with no master cell in front of it, a singular system, 8 cuts.)

mod common;

use tribo::case::{build_pairs, build_problem, schema::CaseFile};
use tribo::contact::problem::ContactProblem;
use tribo::mesh::generate::rectangle;
use tribo::mesh::CellKind;
use tribo::solver::newton::Nonlinear;

/// `swap`: the lower block's top is the slave; `model`: the modelisation (the blocks lie at
/// x ≥ 0, so axisymmetry is meaningful).
fn restored_residual_is_the_committed_one(formulation: &str, swap: bool, model: &str) {
    let lower = rectangle([0.0, -1.0], 2.0, 1.0, 6, 2, CellKind::Quad4, 0.0).unwrap();
    let upper = rectangle([0.15, 0.0], 1.7, 0.8, 5, 2, CellKind::Quad4, 0.0).unwrap();
    let mesh = common::bodies(&[("Lower", &lower), ("Upper", &upper)]);
    let (slave, master) = if swap {
        ("LowerTop", "UpperBottom")
    } else {
        ("UpperBottom", "LowerTop")
    };
    let pair = common::HELD_BELOW_CONTACT_ABOVE.replace(
        "slave = \"UpperBottom\"\nmaster = \"LowerTop\"",
        &format!("slave = \"{slave}\"\nmaster = \"{master}\"\nformulation = \"{formulation}\""),
    );
    assert!(pair.contains(formulation));
    let text = common::case_head(&[("LowerBody", 1000.0, 0.3), ("UpperBody", 3000.0, 0.25)])
        + &format!("[model]\nkinematics = \"large\"\nmodelisation = \"{model}\"\n")
        + &pair;
    let case: CaseFile = toml::from_str(&text).unwrap();
    let solid = build_problem(&case, &mesh).unwrap();
    let pairs = build_pairs(&case, &mesh).unwrap();
    let mut p = ContactProblem::new(solid, pairs);
    let nf = p.num_primal();
    let n = p.num_unknowns();
    // the upper block pressed 0.01 into the lower one; then moved 0.6 (about two of the
    // lower block's cells) along it and 0.05 deeper
    let at = |dx: f64, dy: f64| {
        let mut u = vec![0.0; 2 * mesh.num_nodes()];
        for i in lower.num_nodes()..mesh.num_nodes() {
            u[2 * i] = dx;
            u[2 * i + 1] = dy;
        }
        let mut x = p.unknowns();
        let mut xf = vec![0.0; nf];
        p.solid.asm.dofs.restrict(&u, &mut xf);
        x[..nf].copy_from_slice(&xf);
        x
    };
    let start = at(0.0, -0.01);
    let far = at(0.6, -0.05);
    assert_eq!(start.len(), n);
    let mut r = vec![0.0; n];
    p.evaluate(&start, 1.0, &mut r, false).unwrap();
    p.update_status(&start, 1.0).unwrap();
    p.commit_step();
    let mut committed = vec![0.0; n];
    p.evaluate(&start, 1.0, &mut committed, false).unwrap();
    // a failed attempt: far away, its statuses (and candidates) updated there
    p.evaluate(&far, 1.0, &mut r, false).unwrap();
    let changed = p.update_status(&far, 1.0).unwrap();
    assert!(
        changed > 0,
        "{formulation}: the attempt changed the contact state"
    );
    p.restore_step();
    let mut restored = vec![0.0; n];
    p.evaluate(&start, 1.0, &mut restored, false).unwrap();
    let scale = committed.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = committed
        .iter()
        .zip(&restored)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(
        worst <= 1e-12 * scale,
        "{formulation} {model} (slave swapped: {swap}): the restored residual differs from the committed one by {worst:.3e} \
         (scale {scale:.3e})"
    );
}

#[test]
fn mortar_restores_the_step_start() {
    for swap in [false, true] {
        for model in ["plane_strain", "axisymmetric"] {
            restored_residual_is_the_committed_one("mortar", swap, model);
        }
    }
}

#[test]
fn point_to_segment_restores_the_step_start() {
    for swap in [false, true] {
        for model in ["plane_strain", "axisymmetric"] {
            restored_residual_is_the_committed_one("point-to-segment", swap, model);
        }
    }
}

#[test]
fn node_to_segment_restores_the_step_start() {
    for swap in [false, true] {
        for model in ["plane_strain", "axisymmetric"] {
            restored_residual_is_the_committed_one("node-to-segment", swap, model);
        }
    }
}
