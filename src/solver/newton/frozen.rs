//! Frozen-body corrections: a Newton point that keeps the bodies' tangent and
//! factorisations and makes only its contact terms current (the interface's LU alone).
//! The thresholds that allow one (`iterations.rs` decides at each point), and the cost
//! that makes one pay without friction.

use super::super::line_search::Merits;
use super::super::linear::LinearSolver;
use super::Iteration;

/// Frozen-body corrections: only from a residual below FROZEN_BELOW (that of the last point,
/// or after a frozen correction this point's; or at a step's start), not once the residual
/// is within FROZEN_FINISH times the tolerance (the last corrections are full Newton ones,
/// so friction's constraint rows converge as far below the tolerance as they do without),
/// unless friction branches still switch (see `frozen` in `iterations.rs`).
pub(super) const FROZEN_BELOW: f64 = 0.1;
pub(super) const FROZEN_FINISH: f64 = 1e2;
/// Frozen-body corrections in a row after which they must have halved the step's best
/// residual to go on (see `frozen_stalled`).
const FROZEN_STALL: usize = 8;

/// Without friction, later points take frozen-body corrections as friction's do only where
/// one factorisation of the bodies costs at least this many solves (in multiply-adds:
/// `LinearSolver::solves_per_factorisation`, about √n in 2D). A frozen correction
/// converges linearly (rate ~0.05–0.1) where a full one converges quadratically, so it
/// may cost an iteration more: that pays only where the factorisation it saves is large.
/// SSNP154 A node-to-segment / point-to-segment, paired runs: at 27k–31k unknowns (77–80
/// solves per factorisation) 1.03–1.07× the time, at 89k–98k (153–162) 0.87–0.94×, at
/// 320k (264) 0.54× and 0.63×; the reference meshes are at 29–54 (their runs unchanged).
const FROZEN_WITHOUT_FRICTION_SOLVES: f64 = 120.0;

/// Whether points after a step's first may keep the bodies' factorisations (once below
/// FROZEN_BELOW): with friction (`backtracking`: stick and slip settle over many cheap
/// corrections), and without it where a factorisation of the bodies is costly
/// (FROZEN_WITHOUT_FRICTION_SOLVES) and the point is not `likely_converged` (its residual
/// alone is checked first there, then a chord step may serve).
pub(super) fn later_points_may_freeze(
    backtracking: bool,
    likely_converged: bool,
    lin: &LinearSolver,
) -> bool {
    backtracking
        || (!likely_converged
            && lin
                .solves_per_factorisation()
                .is_some_and(|s| s >= FROZEN_WITHOUT_FRICTION_SOLVES))
}

/// Frozen corrections converge linearly at best; while statuses or friction branches
/// change they are kept whatever the residual does, and they may then swing between two
/// points for good (SSNP154 D at 960k unknowns on another Newton path: 40 frozen
/// corrections between 3.10e-3 and 3.24e-3, the step cut at 50 iterations). After
/// FROZEN_STALL of them in a row (the step's `iterations` so far, re-solves left out)
/// that have not halved the best residual (`merits`, the current point's residual
/// `current` the last), the next correction is a full one. (Settling statuses make frozen
/// corrections rise and fall: D's second step at 960k, 1.7e-2 → 2.5e-2 → 6.3e-3 over six,
/// and on to the tolerance; four in a row would have cut that short.)
pub(super) fn frozen_stalled(iterations: &[Iteration], merits: &Merits, current: f64) -> bool {
    let run = iterations
        .iter()
        .rev()
        .filter(|i| !i.active_set_resolve)
        .take_while(|i| i.frozen_bodies)
        .count();
    run >= FROZEN_STALL && !merits.shrinks(current, FROZEN_STALL, 0.5)
}
