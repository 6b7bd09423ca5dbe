//! A load step's start: the candidate starts (the last state, the last increment
//! extrapolated, the tangent predictor) and the choice among them by the smallest residual,
//! and the bodies at rest when that is the step's solution.

use super::super::linear::LinearSolver;
use super::super::problem::Norms;
use super::Nonlinear;
use crate::error::Result;

/// x0 + Δx with K(x0, t0) Δx = −∂R/∂t (t1 − t0), the derivative taken by a difference
/// over a millionth of the step; None if the tangent cannot be factorised.
fn tangent_predictor(
    problem: &mut dyn Nonlinear,
    lin: &mut LinearSolver,
    x0: &[f64],
    t0: f64,
    t1: f64,
) -> Result<Option<Vec<f64>>> {
    let n = x0.len();
    let eps = 1e-6;
    let mut r0 = vec![0.0; n];
    let mut r = vec![0.0; n];
    problem.evaluate(x0, t0, &mut r0, false)?;
    problem.evaluate(x0, t0 + eps * (t1 - t0), &mut r, true)?;
    if lin.factor(problem.matrix()).is_err() {
        return Ok(None);
    }
    for (v, v0) in r.iter_mut().zip(&r0) {
        *v = -(*v - v0) / eps;
    }
    if lin.solve(problem.matrix(), &mut r).is_err() {
        return Ok(None);
    }
    Ok(Some(x0.iter().zip(&r).map(|(a, b)| a + b).collect()))
}

/// The relative residual of the bodies at rest (x = 0) when that is the solution at time
/// t: nothing loads them, nothing penetrates at rest (every contact status then opens:
/// points closed at the start by `initial_gap`, a device to hold bodies under load, open
/// again), and the residual meets the tolerance. The statuses are restored when it is not.
pub(super) fn rest_solution(
    problem: &mut dyn Nonlinear,
    x: &[f64],
    t: f64,
    r: &mut [f64],
    meets_tolerance: &dyn Fn(&Norms) -> bool,
) -> Result<Option<f64>> {
    if x.iter().any(|&v| v != 0.0) {
        return Ok(None);
    }
    if !problem.unloaded(t) {
        // (loaded from rest: the initial statuses, whatever an unloaded step left, so
        // that a body held by contact alone starts held)
        problem.restart_statuses();
        return Ok(None);
    }
    if problem.open_at_rest() {
        let norms = problem.evaluate(x, t, r, false)?;
        if meets_tolerance(&norms) {
            return Ok(Some(norms.relative()));
        }
    }
    problem.restore_step();
    Ok(None)
}

/// Sets `x`, the last state on entry, to the start of the step from time `lambda_done` to
/// `lambda`. `last_step`: the last converged step (its load-factor increment, its change of
/// the unknowns); `extrapolation_won`: the extrapolation won the last choice (updated
/// here); `r`: room for the residuals.
#[allow(clippy::too_many_arguments)] // the load stepping's state in, the start out
pub(super) fn choose_start(
    problem: &mut dyn Nonlinear,
    lin: &mut LinearSolver,
    x: &mut Vec<f64>,
    r: &mut [f64],
    lambda_done: f64,
    lambda: f64,
    last_step: &Option<(f64, Vec<f64>)>,
    extrapolation_won: &mut bool,
) -> Result<()> {
    // Candidate starts: the plain one (the last state), the previous step's increment
    // extrapolated to this step (SSNP154 D: 20 -> 15 Newton iterations; where it
    // overshoots, e.g. large strains on fine meshes, it loses), and with imposed motions
    // that jump at the step start (a rotation, a drag: they distort the bodies next to
    // them far beyond the step's real strains) the response linearised about the
    // converged state. The one with the smallest residual wins, the residuals measured
    // on one scale (the smallest of their force scales: a distorted start inflates its
    // reactions).
    let mut starts: Vec<Vec<f64>> = vec![];
    if let Some((dl_prev, dx_prev)) = last_step {
        let f = (lambda - lambda_done) / dl_prev;
        starts.push(x.iter().zip(dx_prev).map(|(xi, d)| xi + f * d).collect());
    }
    if problem.imposed_change(lambda_done, lambda) {
        if let Some(t) = tangent_predictor(problem, lin, x, lambda_done, lambda)? {
            starts.push(t);
        }
    }
    // Once the extrapolation has won, the plain start is not tried again (one residual
    // evaluation less per step of a long history).
    let only_extrapolation = *extrapolation_won && starts.len() == 1;
    if !starts.is_empty() && !only_extrapolation {
        starts.insert(0, x.clone());
        let mut norms = vec![];
        for s in &starts {
            norms.push(problem.evaluate(s, lambda, r, false)?);
        }
        let scale = norms
            .iter()
            .map(|n| n.reference)
            .filter(|&v| v > 0.0)
            .fold(f64::INFINITY, f64::min);
        let measure = |n: &Norms| {
            if scale.is_finite() {
                (n.residual / scale).max(n.constraint)
            } else {
                n.relative()
            }
        };
        let best = (0..starts.len())
            .min_by(|&a, &b| measure(&norms[a]).total_cmp(&measure(&norms[b])))
            .unwrap_or(0);
        *extrapolation_won = last_step.is_some() && best == 1;
        *x = starts.swap_remove(best);
    } else if let Some(start) = starts.pop() {
        *x = start;
    }
    Ok(())
}
