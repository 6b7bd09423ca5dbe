//! The contact tangent is the derivative of the contact residual: finite-difference check
//! on two elastic blocks pressed together with non-matching interface meshes, linear
//! (Seg2) and quadratic (Seg3) surfaces, large kinematics, every point active.

mod common;

use tribo::case::{build_pairs, build_problem, schema::CaseFile};
use tribo::contact::problem::ContactProblem;
use tribo::mesh::generate::rectangle;
use tribo::mesh::CellKind;
use tribo::solver::newton::Nonlinear;

/// Two blocks (the upper one stiffer), large kinematics, in contact.
fn case_text() -> String {
    common::case_head(&[("LowerBody", 1000.0, 0.3), ("UpperBody", 3000.0, 0.25)])
        + "[model]\nkinematics = \"large\"\n"
        + common::HELD_BELOW_CONTACT_ABOVE
}

fn check(kind: CellKind, formulation: &str, tolerance: f64) {
    check_with(kind, formulation, "", tolerance)
}

/// `extra`: more keys of the contact pair (e.g. friction).
fn check_with(kind: CellKind, formulation: &str, extra: &str, tolerance: f64) {
    check_in(kind, formulation, extra, "plane_strain", tolerance)
}

fn check_in(kind: CellKind, formulation: &str, extra: &str, model: &str, tolerance: f64) {
    check_from(kind, formulation, extra, model, tolerance, false)
}

/// The same in a given modelisation (the blocks lie at x ≥ 0: axisymmetry is meaningful);
/// with `commit_half`, a load step first ends at half the state (slips are then measured
/// from there, and a tangential penalty starts from the forces there).
fn check_from(
    kind: CellKind,
    formulation: &str,
    extra: &str,
    model: &str,
    tolerance: f64,
    commit_half: bool,
) {
    let lower = rectangle([0.0, -1.0], 2.0, 1.0, 3, 2, kind, 0.0).unwrap();
    let upper = rectangle([0.15, 0.0], 1.7, 0.8, 4, 2, kind, 0.0).unwrap();
    let mesh = common::bodies(&[("Lower", &lower), ("Upper", &upper)]);
    let text = case_text().replace(
        "master = \"LowerTop\"",
        &format!("master = \"LowerTop\"\nformulation = \"{formulation}\"\n{extra}"),
    );
    // ("plane_strain small": small kinematics)
    let (model, kinematics) = model.split_once(' ').unwrap_or((model, "large"));
    let text = text.replace(
        "kinematics = \"large\"",
        &format!("kinematics = \"{kinematics}\"\nmodelisation = \"{model}\""),
    );
    let case: CaseFile = toml::from_str(&text).unwrap();
    let solid = build_problem(&case, &mesh).unwrap();
    let mut pairs = build_pairs(&case, &mesh).unwrap();
    for pair in pairs.iter_mut() {
        pair.set_exact_tangent(true);
    }
    let mut p = ContactProblem::new(solid, pairs);
    let n = p.num_unknowns();
    let nf = p.num_primal();
    // A state with the upper block pushed into the lower one, curved by a smooth field,
    // and compressive multipliers.
    let mut x = p.unknowns();
    let mut u = vec![0.0; 2 * mesh.num_nodes()];
    for (i, c) in mesh.coords.iter().enumerate() {
        if c[1] >= 0.0 && i >= lower.num_nodes() {
            u[2 * i] = 0.01 * (1.3 * c[0]).sin();
            u[2 * i + 1] = -0.02 + 0.01 * (2.1 * c[0]).cos();
        } else {
            u[2 * i] = 0.005 * (c[0] * c[1]).sin();
            u[2 * i + 1] = 0.004 * (1.7 * c[0]).cos() * (c[1] + 1.0);
        }
    }
    let mut xf = vec![0.0; nf];
    p.solid.asm.dofs.restrict(&u, &mut xf);
    x[..nf].copy_from_slice(&xf);
    // normal multipliers compressive; with friction, the tangential (semi-)multipliers
    // after them small, so that some points stick and others slip
    let n_normal = if extra.contains("friction") {
        (n - nf) / 2
    } else {
        n - nf
    };
    for (k, v) in x[nf..].iter_mut().enumerate() {
        // mortar multipliers are pressures (> 0), the others λ < 0 in compression
        let sign = if formulation == "mortar" { -1.0 } else { 1.0 };
        *v = if k < n_normal {
            sign * (-50.0 - 7.0 * (k as f64).sin())
        } else {
            0.9 * (1.7 * k as f64).sin()
        };
    }
    let mut r = vec![0.0; n];
    if commit_half {
        let half: Vec<f64> = x.iter().map(|v| 0.5 * v).collect();
        p.evaluate(&half, 1.0, &mut r, false).unwrap();
        p.commit_step();
    }
    // mortar's statuses are those of its last update: taken at this state, so that nodes
    // pressed in are active and their friction sticks or slips (the slip row's augmented
    // pressure −μ s g̃_j is then differentiated too)
    if formulation == "mortar" {
        p.update_status(&x, 1.0).unwrap();
    }
    p.evaluate(&x, 1.0, &mut r, true).unwrap();
    let a = p.matrix().clone();
    let dir: Vec<f64> = (0..n)
        .map(|i| ((i * 7919 % 101) as f64 / 101.0 - 0.5) * if i < nf { 1e-2 } else { 10.0 })
        .collect();
    let mut kd = vec![0.0; n];
    a.mul_vec(&dir, &mut kd);
    let h = 1e-6;
    let (mut rp, mut rm) = (vec![0.0; n], vec![0.0; n]);
    let xp: Vec<f64> = x.iter().zip(&dir).map(|(a, b)| a + h * b).collect();
    let xm: Vec<f64> = x.iter().zip(&dir).map(|(a, b)| a - h * b).collect();
    p.evaluate(&xp, 1.0, &mut rp, false).unwrap();
    p.evaluate(&xm, 1.0, &mut rm, false).unwrap();
    let scale = kd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut worst: f64 = 0.0;
    for i in 0..n {
        let fd = (rp[i] - rm[i]) / (2.0 * h);
        worst = worst.max((fd - kd[i]).abs());
    }
    println!(
        "{kind} {formulation} {extra} {model}: max |K d - FD| = {worst:.3e} (scale {scale:.3e})"
    );
    assert!(
        worst < tolerance * scale,
        "{kind} {formulation}: tangent error {worst} vs {scale}"
    );
}

#[test]
fn contact_tangent_matches_finite_differences_linear() {
    check(CellKind::Quad4, "point-to-segment", 1e-6);
}

#[test]
fn contact_tangent_matches_finite_differences_quadratic() {
    check(CellKind::Quad8, "point-to-segment", 1e-6);
}

/// The mortar tangent is exact (dual numbers through the whole cell kernel).
#[test]
fn mortar_tangent_matches_finite_differences() {
    check(CellKind::Quad4, "mortar", 1e-6);
    check(CellKind::Quad8, "mortar", 1e-6);
}

/// Coulomb friction (stick and slip points, slips measured from the undeformed state): the
/// exact tangent, geometry terms included, is not symmetric.
#[test]
fn frictional_tangent_matches_finite_differences() {
    check_with(CellKind::Quad4, "point-to-segment", "friction = 0.3", 1e-6);
    check_with(CellKind::Quad8, "point-to-segment", "friction = 0.3", 1e-6);
    let nodal = "friction = 0.3\nintegration = \"nodal\"";
    check_with(CellKind::Quad4, "point-to-segment", nodal, 1e-6);
    check_with(CellKind::Quad8, "point-to-segment", nodal, 1e-6);
    check_with(CellKind::Quad8, "node-to-segment", "friction = 0.3", 1e-6);
}

/// Node-to-segment friction with a tangential penalty (stick stiffness): the tangential
/// multiplier is the force; stick and slip nodes, with and without a normal penalty, from
/// rest and from a committed step (forces and slips carried over).
#[test]
fn tangential_penalty_tangent_matches_finite_differences() {
    for kind in [CellKind::Quad4, CellKind::Quad8] {
        for extra in [
            "friction = 0.3\ntangential_penalty = 1000.0",
            "friction = 0.3\ntangential_penalty = 1000.0\npenalty = 1e4",
        ] {
            for commit_half in [false, true] {
                check_from(
                    kind,
                    "node-to-segment",
                    extra,
                    "plane_strain",
                    1e-6,
                    commit_half,
                );
            }
        }
    }
}

/// Mortar with Coulomb friction: stick and slip nodes.
#[test]
fn mortar_frictional_tangent_matches_finite_differences() {
    for mu in ["0.3", "0.05", "0.02"] {
        check_with(CellKind::Quad4, "mortar", &format!("friction = {mu}"), 1e-6);
        check_with(CellKind::Quad8, "mortar", &format!("friction = {mu}"), 1e-6);
    }
}

/// Mortar with Coulomb friction on the reference geometry (small kinematics): the slip
/// rows' augmented pressure −μ s g̃_j is linear in u there.
#[test]
fn small_kinematics_mortar_frictional_tangent_matches_finite_differences() {
    for mu in ["0.3", "0.02"] {
        for kind in [CellKind::Quad4, CellKind::Quad8] {
            check_in(
                kind,
                "mortar",
                &format!("friction = {mu}"),
                "plane_strain small",
                1e-6,
            );
        }
    }
}

/// Axisymmetry: the measure 2πr of the mortar integrals is differentiated too.
#[test]
fn axisymmetric_mortar_tangent_matches_finite_differences() {
    for kind in [CellKind::Quad4, CellKind::Quad8] {
        check_in(kind, "mortar", "", "axisymmetric", 1e-6);
        check_in(kind, "mortar", "friction = 0.3", "axisymmetric", 1e-6);
    }
}
