//! Mortar with small kinematics sees an overlap however deep: an iterate that carries a
//! body several cells through the other (a first correction on a fine mesh) must close the
//! slave nodes inside, whose master cells were more than a cell away at the start. With
//! master cells sought within one cell of the deformed slave only, those nodes had no
//! weighted gap and stayed open: the bodies passed through each other (SSNP154 A with small
//! kinematics at 0.033 mm: 0.34 mm deep at a "converged" state, then 9 step cuts and a
//! failure).

mod common;

use tribo::case::{build_pairs, build_problem, schema::CaseFile};
use tribo::contact::problem::ContactProblem;
use tribo::mesh::generate::rectangle;
use tribo::mesh::CellKind;
use tribo::solver::newton::Nonlinear;

/// Upper block (1.7 × 0.8, cells 0.1) 0.25 above the lower one (2 × 1, cells 0.1): 2.5
/// cells apart. Statuses updated at the upper block moved down by `drop`; how many changed.
fn changes_after_drop(drop: f64) -> usize {
    let lower = rectangle([0.0, -1.0], 2.0, 1.0, 20, 10, CellKind::Quad4, 0.0).unwrap();
    let upper = rectangle([0.15, 0.25], 1.7, 0.8, 17, 8, CellKind::Quad4, 0.0).unwrap();
    let mesh = common::bodies(&[("Lower", &lower), ("Upper", &upper)]);
    let text = common::case_head(&[("LowerBody", 1000.0, 0.3), ("UpperBody", 1000.0, 0.3)])
        + "[model]\nkinematics = \"small\"\n"
        + common::HELD_BELOW_CONTACT_ABOVE
        + "formulation = \"mortar\"\n";
    let case: CaseFile = toml::from_str(&text).unwrap();
    let solid = build_problem(&case, &mesh).unwrap();
    let pairs = build_pairs(&case, &mesh).unwrap();
    let mut p = ContactProblem::new(solid, pairs);
    let nf = p.num_primal();
    let mut u = vec![0.0; 2 * mesh.num_nodes()];
    for i in lower.num_nodes()..mesh.num_nodes() {
        u[2 * i + 1] = -drop;
    }
    let mut x = p.unknowns();
    let mut xf = vec![0.0; nf];
    p.solid.asm.dofs.restrict(&u, &mut xf);
    x[..nf].copy_from_slice(&xf);
    p.update_status(&x, 1.0).unwrap()
}

#[test]
fn nodes_several_cells_inside_the_master_close() {
    // 0.35 inside: every one of the 18 slave nodes overlaps (plus the candidates' change)
    let deep = changes_after_drop(0.6);
    assert!(deep >= 18, "{deep} status changes");
    // still 0.05 apart: no node closes (the candidates alone may change: one change)
    let apart = changes_after_drop(0.2);
    assert!(apart <= 1, "{apart} status changes");
}
