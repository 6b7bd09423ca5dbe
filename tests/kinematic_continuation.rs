//! Kinematic continuation (src/solver/continuation.rs): a model with large kinematics
//! solves its first load step with linear kinematics first, then with its own from there.
//! The answer is the large-kinematics one, the same as without the stage to Newton's
//! tolerance, with friction too (slips measured from the step start, not from the stage's
//! solution: a stuck node stays where it was at the step start). And on a one-unknown
//! problem: the step starts from the linear solution, or from rest when it fails from there.

mod common;

use common::arctan::Arctan;
use common::{bodies, case_head};
use tribo::case::{self, schema::CaseFile};
use tribo::contact::problem::ContactProblem;
use tribo::mesh::generate::rectangle;
use tribo::mesh::{CellKind, Mesh};
use tribo::solver::linear::Method;
use tribo::solver::newton::{solve, NewtonReport, NewtonSettings, Nonlinear};

/// A 1 × 0.5 block on a 4 × 1 foundation (clamped below), its top pressed down 0.01 (2 %
/// strain) and moved 0.002 sideways in one load step: with μ = 0.3 the block's edges slip
/// and its middle sticks.
fn block_case(formulation: &str) -> (Mesh, CaseFile) {
    let lower = rectangle([-1.0, -1.0], 4.0, 1.0, 44, 4, CellKind::Quad4, 0.0).unwrap();
    let upper = rectangle([0.0, 0.0], 1.0, 0.5, 10, 5, CellKind::Quad4, 0.0).unwrap();
    let mesh = bodies(&[("Lower", &lower), ("Upper", &upper)]);
    let head = case_head(&[("LowerBody", 1000.0, 0.3), ("UpperBody", 1000.0, 0.3)]);
    let text = format!(
        r#"{head}
[model]
kinematics = "large"
[[displacement]]
group = "LowerBottom"
dx = 0.0
dy = 0.0
[[displacement]]
group = "UpperTop"
dx = 0.002
dy = -0.01
[[contact]]
slave = "UpperBottom"
master = "LowerTop"
formulation = "{formulation}"
initial = "all"
friction = 0.3
"#
    );
    (mesh, toml::from_str(&text).unwrap())
}

/// The converged unknowns, how many of them are displacements, and the report, with or
/// without the linear stage.
fn solve_block(formulation: &str, continuation: bool) -> (Vec<f64>, usize, NewtonReport) {
    let (mesh, c) = block_case(formulation);
    let solid = case::build_problem(&c, &mesh).unwrap();
    let pairs = case::build_pairs(&c, &mesh).unwrap();
    let mut p = ContactProblem::new(solid, pairs);
    let settings = NewtonSettings {
        tolerance: 1e-10,
        max_iterations: 40,
        kinematic_continuation: continuation,
        ..Default::default()
    };
    let report = solve(&mut p, &settings, Method::SaddleLdlt)
        .unwrap_or_else(|e| panic!("{formulation}, continuation {continuation}: {e}"));
    (p.unknowns(), p.num_primal(), report)
}

fn check(formulation: &str, staged: bool) {
    let (x_on, nu, on) = solve_block(formulation, true);
    let (x_off, _, off) = solve_block(formulation, false);
    let step = &on.steps[0].iterations;
    println!(
        "{formulation}: {} iterations with the stage ({} of them linear), {} without",
        on.total_iterations,
        step.iter().filter(|i| i.linear_kinematics).count(),
        off.total_iterations
    );
    // the stage ran (where the contact terms have linear kinematics), and the step ended
    // with large kinematics
    assert_eq!(step[0].linear_kinematics, staged, "{formulation}");
    assert!(!step.last().unwrap().linear_kinematics);
    assert!(off.steps[0].iterations.iter().all(|i| !i.linear_kinematics));
    // the same state: displacements and multipliers, each against its own scale
    let worst = |range: std::ops::Range<usize>| {
        let scale = x_off[range.clone()]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = (x_on[range.clone()].iter().zip(&x_off[range]))
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        diff / scale
    };
    let (du, dl) = (worst(0..nu), worst(nu..x_off.len()));
    println!(
        "{formulation}: relative differences {du:.1e} (displacements), {dl:.1e} (multipliers)"
    );
    assert!(du <= 1e-6 && dl <= 1e-6, "{formulation}: {du:e}, {dl:e}");
}

#[test]
fn mortar_with_friction_reaches_the_large_kinematics_state() {
    check("mortar", true);
}

#[test]
fn point_to_segment_takes_no_linear_stage() {
    // (its contact terms are on the deformed geometry with either kinematics: a stage with
    // linear bodies alone only added iterations)
    check("point-to-segment", false);
}

/// The arctangent (from 0, where full Newton converges) with a linear form whose root at
/// t = 1 is `linear_root`.
fn solve_stiffening(linear_root: f64) -> (f64, NewtonReport) {
    let mut p = Arctan::new(0.0);
    p.linear_root = Some(linear_root);
    p.line_search = false;
    let settings = NewtonSettings {
        tolerance: 1e-12,
        max_cuts: 0,
        chord_steps: false,
        ..Default::default()
    };
    let report = solve(&mut p, &settings, Method::Lu).expect("converges without a cut");
    assert!(!p.linear, "left with linear kinematics");
    (p.x, report)
}

/// A linear solution near the answer: the step starts from it.
#[test]
fn the_step_starts_from_the_linear_solution() {
    let (x, report) = solve_stiffening(1.1);
    assert!((x - 1.0).abs() < 1e-11, "x = {x}");
    assert_eq!(report.steps.len(), 1);
    let its = &report.steps[0].iterations;
    let linear = its.iter().filter(|i| i.linear_kinematics).count();
    assert!(linear >= 2 && its[0].linear_kinematics, "{its:?}");
    assert!(its.len() > linear, "no large-kinematics iteration");
}

/// A linear solution from which Newton diverges: the step is tried again from rest
/// without the stage, not cut (max_cuts = 0 here).
#[test]
fn a_step_that_fails_from_the_linear_solution_is_tried_from_rest() {
    // (from x = 4 full Newton on the arctangent overshoots without end)
    let (x, report) = solve_stiffening(4.0);
    assert!((x - 1.0).abs() < 1e-11, "x = {x}");
    let steps = &report.steps;
    assert_eq!(steps.len(), 2, "{steps:?}");
    assert!(!steps[0].converged && steps[0].iterations[0].linear_kinematics);
    assert!(steps[1].converged && steps[1].iterations.iter().all(|i| !i.linear_kinematics));
    assert_eq!(steps[1].time, 1.0);
}
