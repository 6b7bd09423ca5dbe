//! Newton's method with load steps: the time t goes from 0 to the end through the step ends
//! (by default `steps` equal steps to t = 1, t being the load factor); each step iterates
//! until the relative residual is below the tolerance; a step that fails is cut in half and
//! retried (up to `max_cuts` times). A step after the first starts from a linear
//! extrapolation of the previous one when that lowers the starting residual. Every
//! iteration is recorded for the report.
//!
//! | file | what |
//! |---|---|
//! | `mod.rs` | `solve`: load stepping, step cutting, what a step leaves for the next |
//! | `settings.rs` | `NewtonSettings` |
//! | `step_start.rs` | a step's start: candidate starts chosen by their residual, the bodies at rest |
//! | `iterations.rs` | one step's Newton iterations: shortcuts, line searches, status updates, re-solves |
//! | `frozen.rs` | frozen-body corrections: their thresholds, and where they pay without friction |
//! | `diagnosis.rs` | what a failure message adds about an unconverged step |

mod diagnosis;
mod frozen;
mod iterations;
mod settings;
mod step_start;

use super::linear::{LinearSolver, Method};
pub use super::nonlinear::{Iteration, NewtonReport, Nonlinear, StepReport};
use crate::error::{Error, Result};
use iterations::{iterate_step, StepContext};
pub use settings::NewtonSettings;

/// Solves the problem from its current state through the step ends.
pub fn solve(
    problem: &mut dyn Nonlinear,
    settings: &NewtonSettings,
    method: Method,
) -> Result<NewtonReport> {
    let mut report = NewtonReport::default();
    solve_into(problem, settings, method, &mut report)?;
    Ok(report)
}

/// `solve` that fills `report` as it goes, so that a failed solve still tells what it did:
/// its steps, and in `states` the converged ones (with `keep_states`), or at least the
/// last converged one when a step fails after some converged.
pub fn solve_into(
    problem: &mut dyn Nonlinear,
    settings: &NewtonSettings,
    method: Method,
    report: &mut NewtonReport,
) -> Result<()> {
    let mut lin = LinearSolver::new(method);
    lin.n_primal = problem.num_primal();
    solve_steps(problem, settings, &mut lin, report, false)
}

/// `solve_into` with a given linear solver. `stage`: the solve is a stage of a load step
/// (see `continuation.rs`), whose converged state is not committed nor kept.
pub(super) fn solve_steps(
    problem: &mut dyn Nonlinear,
    settings: &NewtonSettings,
    lin: &mut LinearSolver,
    report: &mut NewtonReport,
    stage: bool,
) -> Result<()> {
    let n = problem.num_unknowns();
    let mut x = problem.unknowns();
    let mut r = vec![0.0; n];
    let ends = settings.step_ends();
    let t_end = *ends.last().unwrap_or(&1.0);
    let mut lambda_done = 0.0;
    // the next step end, and how many times the current step has been halved
    let mut next = 0;
    let mut level = 0u32;
    let mut cuts = 0;
    // the last state defect that cut a step: the root cause when smaller steps then fail
    // otherwise (a body pushed through another, then a singular system)
    let mut last_defect: Option<String> = None;
    let backtracking = problem.backtracking();
    // the last converged step: (its load-factor increment, its change of the unknowns)
    let mut last_step: Option<(f64, Vec<f64>)> = None;
    let mut extrapolation_won = false;
    // the last step converged (its last correction factorised the bodies near this start)
    let mut last_converged = false;
    // Newton iterations of the last converged step
    let mut last_iterations = usize::MAX;
    // the step is retried without the linear stage (see below)
    let mut without_stage = false;
    while next < ends.len() {
        let start = if next == 0 { 0.0 } else { ends[next - 1] };
        let dl = (ends[next] - start) / 2f64.powi(level as i32);
        let mut lambda = lambda_done + dl;
        if lambda >= ends[next] - 1e-12 * t_end.abs().max(1.0) {
            lambda = ends[next];
        }
        let x_start = x.clone();
        let (step_k, step_n) = (next + 1, ends.len());
        if settings.verbose {
            eprintln!("load step {step_k} of {step_n}: t = {lambda:.4}");
        }
        crate::progress::load_step(step_k, step_n, lambda);
        // (a model with large kinematics: its first step from the step's solution with
        // linear kinematics, when that converged)
        let linear_stage = if next == 0 && lambda_done == 0.0 && !stage && !without_stage {
            super::continuation::linear_stage(problem, settings, lin, lambda, report)?
        } else {
            None
        };
        let staged = linear_stage.is_some();
        let mut stage_iterations = vec![];
        if let Some((x_linear, iterations)) = linear_stage {
            x = x_linear;
            stage_iterations = iterations;
        } else {
            // (otherwise the best of the candidate starts: see step_start.rs)
            step_start::choose_start(
                problem,
                lin,
                &mut x,
                &mut r,
                lambda_done,
                lambda,
                &last_step,
                &mut extrapolation_won,
            )?;
        }
        let at = StepContext {
            lambda,
            start: lambda_done,
            x_start: &x_start,
            end: t_end,
            step_k,
            step_n,
            backtracking,
            last_converged,
            last_iterations,
        };
        let (mut step, failure) = iterate_step(
            problem,
            settings,
            lin,
            report,
            at,
            &mut x,
            &mut r,
            &mut last_defect,
        )?;
        report.total_iterations += step.iterations.len() - 1;
        step.iterations.splice(0..0, stage_iterations);
        let converged = step.converged;
        report.steps.push(step);
        if converged {
            last_iterations = report
                .steps
                .last()
                .map_or(usize::MAX, |s| s.iterations.len() - 1);
            last_step = Some((
                lambda - lambda_done,
                x.iter().zip(&x_start).map(|(a, b)| a - b).collect(),
            ));
            if stage {
                break;
            }
            if settings.keep_states {
                report.states.push((lambda, x.clone()));
            }
            problem.commit_step();
            last_converged = true;
            lambda_done = lambda;
            if lambda == ends[next] {
                next += 1;
            }
            level = level.saturating_sub(1); // grow back after a cut
            continue;
        }
        let why = failure.unwrap_or_default();
        // A step that failed from the linear stage's solution is tried once from the
        // start without it before it is cut (a large-kinematics answer far from the
        // linear one, e.g. a body that buckles, may be reached better from rest).
        if staged {
            if settings.verbose {
                eprintln!("  step to t={lambda:.4} failed ({why}); again without the linear stage");
            }
            without_stage = true;
            last_converged = false;
            x = x_start;
            problem.restore_step();
            continue;
        }
        without_stage = false;
        if cuts >= settings.max_cuts {
            // x_start is the last converged state (when a step converged at all)
            let kept = report.states.last().is_some_and(|s| s.0 == lambda_done);
            if lambda_done > 0.0 && !kept {
                report.states.push((lambda_done, x_start));
            }
            report.symbolic_factorizations = lin.symbolic_count;
            report.gmres_stalls = lin.gmres_stalls;
            report.numeric_factorizations = lin.numeric_count;
            let earlier = match &last_defect {
                Some(d) if *d != why => format!(" (an earlier attempt: {d})"),
                _ => String::new(),
            };
            return Err(Error::solve(format!(
                "Newton failed at t = {lambda:.4} after {cuts} step cuts: {why}{earlier}"
            )));
        }
        if settings.verbose {
            eprintln!("  step to t={lambda:.4} failed ({why}); cutting the step");
        }
        cuts += 1;
        level += 1;
        last_converged = false;
        x = x_start;
        problem.restore_step();
    }
    // leave the problem at the converged state
    problem.evaluate(&x, t_end, &mut r, false)?;
    report.symbolic_factorizations = lin.symbolic_count;
    report.gmres_stalls = lin.gmres_stalls;
    report.numeric_factorizations = lin.numeric_count;
    Ok(())
}
