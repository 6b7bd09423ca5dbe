//! Kinematic continuation: a model with large kinematics solves its first load step with
//! linear kinematics first (small strains, contact on the reference geometry), then with
//! its own from that solution.
//!
//! Why: from the bodies at rest, Newton's first corrections with large kinematics are taken
//! on a linearisation that is poor far from the solution (contact terms on the deformed
//! geometry, master cells paired on a geometry one correction away), and on fine meshes
//! the first step failed or needed 20–40 iterations (SSNP154 A from 44k nodes). With linear
//! kinematics the gaps are linear in u and the active set settles in 5–9 iterations at
//! every size; that state differs from the large-kinematics one by the rotations' and
//! strains' second-order terms, a start from which Newton converges fast.
//!
//! Only the first step from rest: the linear problem is posed on the reference geometry,
//! a good model of the first increment, not of one from a deformed state. The stage does
//! not commit (friction's slips stay measured from the step start). When it does not
//! converge, its statuses are restored and the step starts from rest as without it.

use super::linear::LinearSolver;
use super::newton::{solve_steps, Iteration, NewtonReport, NewtonSettings, Nonlinear};
use crate::error::{Error, Result};

/// The unknowns that solve the first step, to time t, with linear kinematics and the
/// stage's iterations (marked), or None when the problem has no large kinematics, the
/// settings turn continuation off, or the stage failed (the problem is then as before).
/// The stage's iterations and linear-algebra counts are added to `report`.
pub(super) fn linear_stage(
    problem: &mut dyn Nonlinear,
    settings: &NewtonSettings,
    lin: &mut LinearSolver,
    t: f64,
    report: &mut NewtonReport,
) -> Result<Option<(Vec<f64>, Vec<Iteration>)>> {
    if !settings.kinematic_continuation || !problem.set_linear_kinematics(true) {
        return Ok(None);
    }
    if settings.verbose {
        eprintln!("first load step with linear kinematics (the start of the large-kinematics one)");
    }
    let stage_settings = NewtonSettings {
        times: vec![t],
        max_cuts: 0,
        keep_states: false,
        kinematic_continuation: false,
        ..settings.clone()
    };
    let mut stage = NewtonReport::default();
    let solved = solve_steps(problem, &stage_settings, lin, &mut stage, true);
    problem.set_linear_kinematics(false);
    report.total_iterations += stage.total_iterations;
    report.factorizations += stage.factorizations;
    report.time_evaluate_s += stage.time_evaluate_s;
    report.time_factor_s += stage.time_factor_s;
    report.time_solve_s += stage.time_solve_s;
    let mut iterations: Vec<Iteration> =
        stage.steps.into_iter().flat_map(|s| s.iterations).collect();
    for i in &mut iterations {
        i.linear_kinematics = true;
    }
    match solved {
        Ok(()) => Ok(Some((problem.unknowns(), iterations))),
        Err(Error::Solve(why)) => {
            if settings.verbose {
                eprintln!("  the linear-kinematics stage failed ({why}); starting from rest");
            }
            problem.restore_step();
            Ok(None)
        }
        Err(e) => Err(e),
    }
}
