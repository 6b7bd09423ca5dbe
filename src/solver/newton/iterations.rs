//! Newton's iterations of one load step: the residual and tangent at each point (with the
//! shortcuts: frozen bodies, chord steps), friction's backtracking and the line search,
//! the correction, the contact status updates and active-set re-solves, and the tests that
//! end the step (converged, diverged, stalled, too many iterations, singular).

use super::super::line_search;
use super::super::linear::LinearSolver;
use super::super::problem::Norms;
use super::diagnosis::diagnosis;
use super::frozen::{frozen_stalled, later_points_may_freeze, FROZEN_BELOW, FROZEN_FINISH};
use super::step_start::rest_solution;
use super::{Iteration, NewtonReport, NewtonSettings, Nonlinear, StepReport};
use crate::error::{Error, Result};

/// Where the statuses on the linearisation stand at a Newton point after plain re-solves
/// swung there: not taken, their re-solves going on, or settled.
#[derive(Clone, Copy, PartialEq)]
enum Takeover {
    NotTaken,
    Running,
    Settled,
}

/// Active-set re-solves in a row from one linearisation point.
const MAX_RESOLVES: usize = 4;
/// Re-solves on the linearised constraints in a row from one linearisation point (the
/// primal-dual active set of a linear problem settles in a few, but may cycle).
const MAX_LINEARISED_RESOLVES: usize = 8;

/// What a load step's iterations take from the load stepping around them.
pub(super) struct StepContext<'a> {
    /// the time at the step's end
    pub lambda: f64,
    /// the time and the unknowns at its start (the last converged state), and the time at
    /// the loading's end
    pub start: f64,
    pub x_start: &'a [f64],
    pub end: f64,
    /// the step's number (from 1) and the number of step ends (progress reports)
    pub step_k: usize,
    pub step_n: usize,
    /// the problem's `Nonlinear::backtracking`
    pub backtracking: bool,
    /// the last step converged (its last correction factorised the bodies near this start)
    pub last_converged: bool,
    /// Newton iterations of the last converged step
    pub last_iterations: usize,
}

/// Newton's iterations of one load step, to time `at.lambda` from the start in `x`, which
/// they leave at the last iterate; `r` (of the unknowns' length) holds the last residual.
/// Returns the step's report and, when it did not converge, why; a state defect that ended
/// it is also kept in `last_defect` (the root cause when smaller steps then fail otherwise).
#[allow(clippy::too_many_arguments)] // the load stepping's state in, the step out
pub(super) fn iterate_step(
    problem: &mut dyn Nonlinear,
    settings: &NewtonSettings,
    lin: &mut LinearSolver,
    report: &mut NewtonReport,
    at: StepContext,
    x: &mut Vec<f64>,
    r: &mut [f64],
    last_defect: &mut Option<String>,
) -> Result<(StepReport, Option<String>)> {
    let StepContext {
        lambda,
        start,
        x_start,
        end,
        step_k,
        step_n,
        backtracking,
        last_converged,
        last_iterations,
    } = at;
    let n = r.len();
    let meets_tolerance = |n: &Norms| {
        n.relative() <= settings.tolerance
            || (n.residual == 0.0 && n.constraint <= settings.tolerance)
    };
    let mut step = StepReport {
        time: lambda,
        converged: false,
        iterations: vec![],
    };
    let mut failure = None;
    let mut changes = usize::MAX;
    // the last correction, for the backtracking below
    let mut last_dx: Option<Vec<f64>> = None;
    // re-solve from the last linearisation point with new statuses (see below)
    let mut resolve = false;
    let mut resolves = 0;
    let mut linearised_resolves = 0;
    let mut linearised_seen: Vec<u64> = vec![];
    let mut resolved_with: Vec<u64> = vec![];
    // the statuses on the linearisation taking over from swinging plain re-solves at this
    // point (see below)
    let mut takeover = Takeover::NotTaken;
    // the plain Newton iterate a re-solve replaced
    let mut before_resolve: Option<Vec<f64>> = None;
    // the correction of the plain Newton iterate that started this point's re-solves
    // (the iterate is the point plus it); whether re-solves are off for this step, and
    // whether the current point is a plain iterate taken back from swinging re-solves
    // (see below)
    let mut plain_correction: Option<Vec<f64>> = None;
    let mut first_changes = 0;
    let mut resolves_off = false;
    // frozen-body corrections follow the points of this step (friction: see `frozen`)
    let frozen_corrections = settings.frozen_bodies && backtracking;
    let mut taken_back = false;
    let mut last_size = f64::INFINITY;
    // c such that a chord step from the current point is predicted to leave c r² (see
    // below), while the last factorisation is that of this step's last linearisation
    let mut chord_coefficient: Option<f64> = None;
    // Newton iterations (linearisation points) of this step: re-solves at one point do
    // not count toward `max_iterations` (each point has at most
    // MAX_LINEARISED_RESOLVES, or MAX_RESOLVES, of them)
    let mut newton_its = 0;
    // how often each node's contact status changed in this attempt (failure messages)
    let mut status_counts = std::collections::BTreeMap::<usize, usize>::new();
    // the merits of this step's Newton points, for the line search
    let mut merits = line_search::Merits::default();
    // (at rest with nothing loading the bodies: that is the step's solution)
    let rest = rest_solution(problem, x, lambda, r, &meets_tolerance)?;
    for it in 0.. {
        if let Some(rel) = rest {
            step.iterations.push(Iteration {
                iteration: 0,
                relative_residual: rel,
                status_changes: 0,
                branch_switches: 0,
                active_set_resolve: false,
                chord: false,
                frozen_bodies: false,
                step_length: None,
                linear_kinematics: false,
            });
            step.converged = true;
            break;
        }
        if !resolve {
            takeover = Takeover::NotTaken;
        }
        if !resolve && it > 0 {
            newton_its += 1;
            // Re-solves that swung are off for the plain iterate taken back from them; a
            // later point is a new linearisation, where they come back when each new point
            // factorises the bodies (without friction: SSNP154 A node-to-segment at 89k
            // unknowns, 7 of them in a row with 7, 3, 3, 2, 2, 1 and 1 status changes,
            // 0.68–0.75× the time with re-solves, point-to-segment at 27k 0.81×). With
            // friction the frozen-body corrections that follow cost about what re-solves
            // cost and settle the statuses as well: re-solves stay off for the step (D at
            // 29k and 93k unknowns: 1.16× and 1.03× with them back).
            if !(taken_back || frozen_corrections) {
                resolves_off = false;
            }
        }
        let t = std::time::Instant::now();
        // Near convergence (small residual, statuses settled) the tangent is probably not
        // needed: check the residual alone first, and assemble the tangent only if it
        // is not converged after all, nor a chord step (SSNP154 A, B, E, F: the first
        // load step's last full correction starts from 2–5e-2 and is followed by chord
        // steps).
        let prev = step.iterations.last().map(|i| i.relative_residual);
        // friction branches switched by the last status update (see `frozen` below)
        let branches_switched = step
            .iterations
            .last()
            .is_some_and(|i| i.branch_switches > 0);
        let likely_converged = changes == 0
            && prev.is_some_and(|p| p < 1e-3 || (chord_coefficient.is_some() && p < 1e-1));
        // Frozen bodies: at the start of a step that follows a converged one (the bodies'
        // tangent is that of the last step's end), and with friction while the residual
        // is still far from the tolerance but the iterate moves little (stick and slip
        // settling), the bodies' tangent and factorisations are kept and only the contact
        // terms are current: after a point below FROZEN_BELOW, or after a frozen correction
        // if this point is below it (judged by the last point alone, a frozen correction
        // that swung the residual up through status changes was followed by full ones:
        // SSNP154 D node-to-segment at 960k unknowns, two in the first step, 8 s each).
        // Without friction, the same where a factorisation of the bodies is costly
        // (`frozen.rs`).
        // (the cost of a factorisation is looked up last: a walk over the factor's
        // supernodes, needless at re-solves and far from convergence)
        let last_frozen = step.iterations.last().is_some_and(|i| i.frozen_bodies);
        let frozen_candidate = settings.frozen_bodies
            && !resolve
            && lin.condenses_contact()
            && ((it == 0 && last_converged)
                || ((last_frozen || prev.is_some_and(|p| p < FROZEN_BELOW))
                    && later_points_may_freeze(backtracking, likely_converged, lin)));
        // Statuses that changed at a point near convergence, without friction (no
        // re-solve took them: mortar, or re-solves spent): the residual with them may
        // already meet the tolerance, and then one more correction only confirms them.
        // That one keeps the bodies' factorisations (contact terms current): its tangent
        // is the last point's, one correction away, so it lands far below the tolerance
        // as a full one does (SSNP154 A mortar at 98k unknowns: 8.6e-7 with one status
        // changed, then 1.1e-11 where the full correction gave 9e-14; the first step's
        // last body factorisation, the run's iterations and answers otherwise the same).
        // A point that does not meet the tolerance is evaluated whole, as before.
        let settling = settings.frozen_bodies
            && !resolve
            && !backtracking
            && lin.condenses_contact()
            && changes > 0
            && changes != usize::MAX
            && prev.is_some_and(|p| p < FROZEN_BELOW);
        let mut norms = if resolve || frozen_candidate || settling {
            problem.evaluate_contact_tangent(x, lambda, r)?
        } else {
            problem.evaluate(x, lambda, r, !likely_converged)?
        };
        // (a tangent evaluated below at the same point leaves the residual as it is)
        let met = meets_tolerance(&norms);
        // A frozen correction that raised the residual with the statuses it was made for
        // is followed by a full one, and the last corrections are full ones (see
        // FROZEN_FINISH); not while statuses change or friction branches switch: then
        // these, one or a few points per correction, set the pace, and a full tangent
        // brings the step no nearer its end (SSNP154 D, point-to-segment at 266k
        // unknowns: the second step's last 7 corrections, 1.1 s of factorisation each,
        // against 0.07 s frozen; 28.7 → 18.4 s in all).
        let raised = last_frozen
            && changes == 0
            && !branches_switched
            && prev.is_some_and(|p| norms.relative() > p);
        let below = (it == 0 && last_converged)
            || prev.is_some_and(|p| p < FROZEN_BELOW)
            || (last_frozen && norms.relative() < FROZEN_BELOW);
        let stalled = frozen_stalled(&step.iterations, &merits, norms.relative());
        // (a frozen candidate below the tolerance is one no more; settling applies there)
        let mut frozen = (frozen_candidate
            && below
            && !raised
            && !stalled
            && !met
            && (branches_switched || norms.relative() > FROZEN_FINISH * settings.tolerance))
            || (settling && met);
        if (frozen_candidate || settling) && !frozen && !met {
            norms = problem.evaluate(x, lambda, r, true)?;
        }
        // Chord step: after a Newton correction from x_{k-1} (residual r_{k-1}) to x_k
        // (r_k, statuses settled), a correction with the tangent of x_{k-1} leaves about
        // 2 r_k² / r_{k-1} (the tangent moved by O(|x_k − x_{k-1}|) ~ r_{k-1}, the
        // correction is ~ r_k); after a chord step from r_{k-1} to r_k, about
        // r_k² / r_{k-1} (the same contraction again). When that is below the
        // tolerance (after one chord step, or a second one), the factorisation at hand
        // serves: no tangent, no factorisation, one solve (SSNP154: the last corrections
        // of each load step). Not with friction: its stick/slip switches make the
        // prediction poor, and a chord step ends at the tolerance where the last Newton
        // correction goes far below it, and with it the Coulomb condition |t| ≤ μ p.
        let mut chord = settings.chord_steps
            && !backtracking
            && lin.factorisation_is_exact()
            && !resolve
            && changes == 0
            && !met
            && chord_coefficient.is_some_and(|c| {
                let r1 = c * norms.relative().powi(2);
                r1.min(r1 * r1 / norms.relative()) <= settings.tolerance
            });
        if likely_converged && !frozen_candidate && !met && !chord {
            norms = problem.evaluate(x, lambda, r, true)?;
        }
        // Backtracking: a full correction that raised the residual without changing any
        // contact status (semi-smooth Newton can cycle between stick and slip) is halved,
        // up to three times (a frozen one while branches switch stays frozen, as above).
        if let (Some(dx), Some(p), 0, true) = (&last_dx, prev, changes, backtracking) {
            let mut alpha = 1.0;
            let keep = frozen && branches_switched;
            while norms.relative() > p && alpha > 0.2 {
                frozen = keep;
                alpha *= 0.5;
                for (xi, d) in x.iter_mut().zip(dx) {
                    *xi -= alpha * d;
                }
                norms = if keep {
                    problem.evaluate_contact_tangent(x, lambda, r)?
                } else {
                    problem.evaluate(x, lambda, r, true)?
                };
            }
        }
        // Line search (line_search.rs): a correction whose point is worse than the
        // step's last few Newton points is shortened, each trial point with its own
        // statuses. (Not where the friction backtracking above already applies.)
        let mut step_length = None;
        // With friction, once `FULL_AFTER_STALL` Newton points have passed without
        // progress, the corrections are taken in full: a line search that keeps a sliver
        // of each lets the statuses swing in place (a quadratic surface pressed with
        // friction from every point closed: no progress at 1/16 of each correction, the
        // step cut to failure), while the full semi-smooth steps settle them
        // (tests/cattaneo_mindlin.rs). (Which formulations search at all: see
        // `ContactProblem::line_search`; mortar never does.)
        let searching = problem.line_search()
            && !(backtracking && merits.stalled(line_search::FULL_AFTER_STALL));
        if let (Some(dx), Some(reference), false, true) =
            (&last_dx, merits.reference(), resolve, searching)
        {
            let friction_handled = backtracking && changes == 0;
            // (not after an active-set re-solve: its correction meets its linearised
            // complementarity with the new statuses, shortening it leaves them, and
            // point-to-segment and node-to-segment then took up to 1.5× the iterations:
            // SSNP154 A and E in 4 steps at size 0.2)
            let after_resolve = problem.active_set_resolves()
                && !taken_back
                && step.iterations.last().is_some_and(|i| i.active_set_resolve);
            if !friction_handled
                && !after_resolve
                && !meets_tolerance(&norms)
                && norms.relative() > reference
            {
                let full = norms.relative();
                if let Some(alpha) =
                    line_search::backtrack(problem, x, dx, lambda, r, full, reference)?
                {
                    // the kept point's residual and tangent (a frozen correction's: its
                    // contact terms; the line search answers the statuses it changed)
                    norms = if frozen {
                        problem.evaluate_contact_tangent(x, lambda, r)?
                    } else {
                        problem.evaluate(x, lambda, r, true)?
                    };
                    chord = false;
                    step_length = Some(alpha);
                }
            }
        }
        taken_back = false;
        report.time_evaluate_s += t.elapsed().as_secs_f64();
        let rel = norms.relative();
        if !resolve {
            merits.push(rel);
        }
        step.iterations.push(Iteration {
            iteration: it,
            relative_residual: rel,
            status_changes: 0,
            branch_switches: 0,
            active_set_resolve: resolve,
            chord,
            frozen_bodies: frozen,
            step_length,
            linear_kinematics: false,
        });
        crate::progress::iteration(step_k, step_n, lambda, it, rel);
        if settings.verbose {
            let note = if resolve {
                "  (same point, new contact statuses)"
            } else if chord {
                "  (chord step: last factorisation)"
            } else if frozen {
                "  (bodies' factorisations kept, contact terms current)"
            } else {
                ""
            };
            let searched = step_length.map_or(String::new(), |a| {
                format!("  (line search: {a} of the correction)")
            });
            eprintln!("  step t={lambda:.4} iter {it:2}  residual {rel:.3e}{note}{searched}");
        }
        if !rel.is_finite() {
            failure = Some("non-finite residual".to_string());
            break;
        }
        // Divergence: a residual a thousand times the best one of this step (after the
        // first corrections) that is not improving on any of the last three is not going
        // to come back in time; cut the step instead. (A contact zone that grows node by
        // node from a first touch starts far above the first residual and falls steadily.)
        // (re-solves are left out: their residuals are those of the same point with
        // other statuses, e.g. an augmentation on nodes still far open)
        let residuals: Vec<f64> = step
            .iterations
            .iter()
            .filter(|i| !i.active_set_resolve)
            .map(|i| i.relative_residual)
            .collect();
        let best = residuals.iter().copied().fold(f64::INFINITY, f64::min);
        // (the last three corrected iterates: not the step's start, which no correction
        // has yet put in contact)
        let recent = residuals[1.min(residuals.len() - 1)..residuals.len() - 1]
            .iter()
            .rev()
            .take(3)
            .copied()
            .fold(f64::INFINITY, f64::min);
        if !resolve && residuals.len() > 3 && rel > 1e3 * best && rel >= recent {
            let why = diagnosis(problem, r, &status_counts);
            failure = Some(format!("divergence (residual {rel:.1e}){why}"));
            break;
        }
        // Stalled: line searches have been shortening corrections and the last Newton
        // points do not improve on the step's best; a smaller step will do better.
        if step_length.is_some() && merits.stalled(line_search::STALL) {
            let why = diagnosis(problem, r, &status_counts);
            failure = Some(format!(
                "no progress in {} iterations with line searches (residual {rel:.1e}){why}",
                line_search::STALL
            ));
            break;
        }
        // Converged: residual below the tolerance, or (with no load to measure it
        // against, e.g. a pure rigid motion) a correction at round-off size (of a
        // problem that knows its size: without one, every correction would do).
        if it > 0
            && changes == 0
            && (meets_tolerance(&norms)
                || (problem.length_scale().is_finite()
                    && last_size <= 1e-10 * problem.length_scale()
                    && norms.constraint <= settings.tolerance))
        {
            if let Some(defect) = problem.state_defect() {
                *last_defect = Some(defect.clone());
                failure = Some(defect);
                break;
            }
            step.converged = true;
            break;
        }
        if newton_its >= settings.max_iterations {
            failure = Some(format!(
                "no convergence in {} iterations (residual {rel:.1e}){}",
                settings.max_iterations,
                diagnosis(problem, r, &status_counts)
            ));
            break;
        }
        let t = std::time::Instant::now();
        // An earlier factorisation may precondition the first solve of a step (the
        // tangent barely moved since the last converged state: small steps, which
        // converge in a few iterations); later iterations of a step, or steps after one
        // that needed many, change it more than GMRES recovers cheaply (SSNP154 F: 20 %
        // slower; B and D lost a factorisation's time on the failed attempt).
        lin.reuse_factor = settings.reuse_factor && it == 0 && last_iterations <= 3;
        let factored = if chord {
            Ok(())
        } else {
            lin.factor(problem.matrix())
        };
        report.time_factor_s += t.elapsed().as_secs_f64();
        let solved = factored.and_then(|()| {
            report.factorizations += usize::from(!chord);
            for v in r.iter_mut() {
                *v = -*v;
            }
            let t = std::time::Instant::now();
            // a chord step solves with the factorisation at hand alone
            let solved = if chord {
                lin.solve_factored(r)
            } else {
                lin.solve(problem.matrix(), r)
            };
            report.time_solve_s += t.elapsed().as_secs_f64();
            solved
        });
        // A (numerically) singular matrix may factorise with tiny pivots: an increment
        // a million times the model size means a body is free to move.
        let step_size = r[..lin.n_primal.min(n)]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let singular = solved.is_err() || step_size > 1e6 * problem.length_scale();
        // A re-solve is a shortcut: if its statuses make the system singular, Newton
        // goes on from the plain iterate it replaced, as without re-solves.
        if let (true, true, Some(_)) = (singular, resolve, &before_resolve) {
            if settings.verbose {
                eprintln!("                        (singular with these statuses: back to the last iterate)");
            }
            *x = before_resolve.take().unwrap();
            resolve = false;
            resolves = 0;
            continue;
        }
        // (a solve whose values overflowed is the same singular matrix as one whose
        // increment is huge, whichever the factorisation's order made it)
        let overflowed = solved.is_err() && r.iter().any(|v| !v.is_finite());
        if let (Err(e), false) = (solved, overflowed) {
            // no smaller step needs less memory: stop at once
            if matches!(e, Error::Memory(_)) {
                return Err(e);
            }
            failure = Some(e.to_string());
            break;
        }
        last_size = step_size;
        if singular {
            let increment = if overflowed {
                "non-finite displacement increment".to_string()
            } else {
                format!("displacement increment {step_size:.1e}")
            };
            failure = Some(format!(
                "the stiffness matrix is singular ({increment}): the model has a \
                 rigid-body mode (a body not held by imposed displacements or contact; a body \
                 held by contact alone needs some contact points closed at the start: \
                 initial = \"closed\" with initial_gap = a small distance)"
            ));
            break;
        }
        chord_coefficient = (!frozen).then(|| if chord { 1.0 } else { 2.0 } / rel);
        let x_lin = x.clone();
        for (xi, dx) in x.iter_mut().zip(r.iter()) {
            *xi += dx;
        }
        last_dx = Some(r.to_vec());
        // Active-set iterations at a fixed linearisation: where the problem keeps one
        // (mortar with large kinematics), statuses that change on the linearised
        // constraints at the trial point are re-solved from the same point first, the
        // correction then satisfying its own linearised complementarity; the plain
        // statuses (nonlinear gaps) are taken once they settle. At a step's first point;
        // without friction at every point where a re-solve costs the interface alone:
        // the zone's edge then closes in re-solves, not one or two nodes per body
        // factorisation (SSNP154 A mortar, second step: at 320k unknowns 6 full
        // corrections → 3, 0.84× the time; at 98k 4 → 3, 0.92×; the iterations, re-solves
        // counted, 21 → 24 and 19 → 20). With friction the frozen-body corrections settle
        // the statuses at that cost already (D mortar at 93k: 0.99–1.00×, 21 → 23
        // iterations: at every point with friction too, this was tried and not kept).
        // (where the problem re-solves on the iterate's own statuses, only after those
        // swung: see below)
        let linearised_here = (!problem.active_set_resolves()
            && (newton_its == 0 || (!backtracking && lin.condenses_contact())))
            || takeover == Takeover::Running;
        let linearised =
            if !chord && linearised_here && linearised_resolves < MAX_LINEARISED_RESOLVES {
                problem.update_status_linearised(x, lambda)?
            } else {
                None
            };
        // (a set of statuses met before at this point is a cycle: go on from here)
        let cycled = linearised.is_some_and(|ch| ch > 0) && {
            let signature = problem.status_signature();
            let seen = linearised_seen.contains(&signature);
            linearised_seen.push(signature);
            seen
        };
        if let Some(ch) = linearised.filter(|&ch| ch > 0 && !cycled) {
            linearised_resolves += 1;
            step.iterations.last_mut().unwrap().status_changes = ch;
            if settings.verbose {
                eprintln!("                        {ch} status changes on the linearisation");
            }
            changes = ch;
            resolve = true;
            before_resolve = Some(std::mem::replace(x, x_lin));
            continue;
        }
        linearised_resolves = 0;
        linearised_seen.clear();
        if takeover == Takeover::Running {
            takeover = Takeover::Settled;
        }
        let before = changes;
        // the statuses solved with from this linearisation point (a cycle, below), where
        // re-solves may follow at all
        let may_resolve = problem.active_set_resolves() && lin.condenses_contact();
        if !resolve {
            resolved_with.clear();
        }
        if may_resolve {
            resolved_with.push(problem.status_signature());
        }
        let generation = problem.pattern_generation();
        changes = problem.update_status(x, lambda)?;
        // Re-solves settle a few statuses. One that changes more of them than the one
        // before it, and more than half as many as started them, is swinging, not
        // settling (SSNP154 D at 0.05 mm, a step's start: 154, 127, 149, 139 …
        // changes, and corrections that then threw the residual up; the reference
        // mesh's 7, 1, 2, 2 settle): Newton goes on from the plain iterate, as without
        // re-solves, and takes no more there (with friction: no more in this step; see
        // where Newton points are counted, above).
        // Where the problem has them, the statuses of the linearised problem take over
        // first (once per point): they are those the corrections satisfy, and their
        // re-solves settle where the plain ones, read on cells a correction pushed far
        // from a point contact, swung (SSNP154 A node-to-segment at 1.27M unknowns, the
        // first step: 457, 217, then more than 228 changes; from the plain iterate then,
        // 27 iterations and a cut step).
        // (plain re-solves that swung: not the linearised ones' own, whose plain statuses
        // are taken at the next point)
        let swung = resolve
            && plain_correction.is_some()
            && changes > before
            && 2 * changes > first_changes;
        // (with friction at a step's first point only, as mortar's: later, the normal
        // statuses of the linearisation, friction's branches left to the iterate, did not
        // settle (D node-to-segment at 960k unknowns, the second step: 84, 62, 19, 20, 30
        // … changes, then divergence and a cut step)
        let may_take_over = swung && (newton_its == 0 || !backtracking);
        let linearised = if may_take_over && takeover == Takeover::NotTaken {
            problem.update_status_linearised(x, lambda)?
        } else {
            None
        };
        if let Some(ch) = linearised.filter(|&ch| ch > 0) {
            if settings.verbose {
                eprintln!(
                    "                        {changes} contact status changes: swinging; \
                     {ch} status changes on the linearisation instead"
                );
            }
            takeover = Takeover::Running;
            linearised_resolves = 1;
            linearised_seen.push(problem.status_signature());
            step.iterations.last_mut().unwrap().status_changes = ch;
            changes = ch;
            before_resolve = Some(std::mem::replace(x, x_lin));
            continue;
        }
        if takeover == Takeover::Settled {
            // (the linearised problem's solution, settled: Newton goes on from it with its
            // own statuses, without plain re-solves here, which had swung)
            resolves_off = true;
        } else if swung {
            if let Some(dx) = plain_correction.take() {
                for ((xi, &x0), d) in x.iter_mut().zip(&x_lin).zip(&dx) {
                    *xi = x0 + d;
                }
                last_dx = Some(dx);
                changes = problem.update_status(x, lambda)?;
                resolves_off = true;
                taken_back = true;
            }
        }
        // The contact zone grew out of the tangent's pattern, so that the next solve
        // analyses a new one: the pattern takes in at once the couplings within reach at
        // the loading's end, the iterate's change since the step's start extrapolated
        // there (with a margin for the prediction's error), instead of growing a few cells
        // at a time with an analysis each (SSNP154 D point-to-segment at 960k unknowns: 5
        // analyses, 4 of them at active-set re-solves or frozen-body corrections that then
        // factorised the bodies, 49 s of 127; now 2).
        if settings.anticipate_pattern
            && problem.pattern_generation() != generation
            && lambda > start
        {
            let s = (end - start) / (lambda - start);
            let predicted: Vec<f64> = x_start
                .iter()
                .zip(x.iter())
                .map(|(a, b)| a + s * (b - a))
                .collect();
            problem.anticipate(x, lambda, &predicted, end);
        }
        if changes > 0 {
            for n in problem.changed_nodes() {
                *status_counts.entry(n).or_default() += 1;
            }
        }
        let last = step.iterations.last_mut().unwrap();
        last.status_changes = changes;
        last.branch_switches = problem.branch_switches();
        if settings.verbose && changes > 0 {
            eprintln!("                        {changes} contact status changes");
        }
        // Statuses changed: solve again from the same point with the new statuses (an
        // active-set iteration on this linearisation), when the solver condenses on
        // the contact interface: the bodies' tangent and factorisations are those of
        // this point, only the contact terms and the interface are redone. A few in a
        // row at most (cycling statuses), then the step moves on.
        // The formulation decides whether that pays (mortar: no). Not when the new
        // statuses are ones already solved with from this point (a cycle: one node's points
        // on, off, on …; SSNP154 D at 93k unknowns, the first step).
        resolve = changes > 0
            && !resolves_off
            && resolves < MAX_RESOLVES
            && may_resolve
            && !resolved_with.contains(&problem.status_signature());
        if resolve {
            resolves += 1;
            if resolves == 1 {
                plain_correction = Some(r.to_vec());
                first_changes = changes;
            }
            before_resolve = Some(std::mem::replace(x, x_lin));
        } else {
            resolves = 0;
            before_resolve = None;
            plain_correction = None;
        }
    }
    Ok((step, failure))
}
