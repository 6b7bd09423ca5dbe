//! Backtracking line search for semi-smooth Newton on contact.
//!
//! The merit is the convergence measure itself, the relative residual, taken at each trial
//! point with the contact statuses of that point: that is the residual of the nonsmooth
//! equations (complementarity in max-form), so a Newton direction lowers it near a solution
//! and the test does not depend on which statuses the correction was computed with.
//! The acceptance test is non-monotone (Grippo, Lampariello and Lucidi 1986): a point is
//! compared with the largest merit of the step's last few Newton points, so that the
//! residual of a contact zone growing from a first touch, which rises and falls while the
//! statuses settle, is not cut back; only a correction that makes things worse than all of
//! them is. Halving stops at 1/16: below that the direction is poor. With friction, when
//! the step's best merit has not improved for `FULL_AFTER_STALL` Newton points, the
//! corrections are taken in full until it does: short steps let the stick and contact
//! statuses swing in place, semi-smooth Newton's own steps settle them. Otherwise the
//! step is cut after `STALL` points without progress (the load stepping is the last
//! resort).

use super::newton::Nonlinear;
use crate::error::Result;

/// Newton points in a row that do not lower the step's best merit, line searches having
/// shortened corrections, before the step is given up (cut).
pub const STALL: usize = 8;
/// With friction: Newton points in a row that do not lower the step's best merit before
/// the corrections are taken in full (semi-smooth Newton's own steps) until one does.
pub const FULL_AFTER_STALL: usize = 4;
/// How many of the step's last Newton merits the acceptance test compares with.
pub const MEMORY: usize = 3;
/// Sufficient decrease (Armijo) on the merit.
const ARMIJO: f64 = 1e-4;
/// Halvings of the correction tried before giving up.
const HALVINGS: u32 = 4;

/// The merits of a load step's Newton points (not re-solves or trial points).
#[derive(Default)]
pub struct Merits(Vec<f64>);

impl Merits {
    pub fn push(&mut self, m: f64) {
        self.0.push(m);
    }

    /// Whether the last `n` merits have not lowered the best one before them: Newton is
    /// stuck (with line searches shortening its corrections, not going to get out of it).
    pub fn stalled(&self, n: usize) -> bool {
        let k = self.0.len();
        k > n && {
            let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
            min(&self.0[k - n..]) >= min(&self.0[..k - n])
        }
    }

    /// Whether the last `n` merits, the current point's `current` the last of them, have
    /// brought the best one down by at least `ratio` (true while there are not more than
    /// `n`): a shortcut that converges linearly (frozen bodies) is still contracting.
    pub fn shrinks(&self, current: f64, n: usize, ratio: f64) -> bool {
        let k = self.0.len() + 1;
        k <= n || {
            let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
            let before = min(&self.0[..k - n]);
            min(&self.0[k - n..]).min(current) <= ratio * before
        }
    }

    /// The non-monotone reference: the largest of the last `MEMORY` merits.
    pub fn reference(&self) -> Option<f64> {
        let n = self.0.len();
        (n > 0).then(|| {
            self.0[n.saturating_sub(MEMORY)..]
                .iter()
                .copied()
                .fold(0.0, f64::max)
        })
    }
}

/// The full correction x0 + dx (the current x, evaluated: `full`) raised the merit above
/// `reference`: tries x0 + α dx for α = 1/2, 1/4, …, each with its own statuses, and keeps
/// the first that decreases the merit enough, or the best point tried when none does (the
/// full one included). Returns the fraction α kept, x moved there and the problem's
/// statuses updated for it (the caller evaluates it, with its tangent); None when the full
/// step stays (x, its statuses and r as they were).
pub fn backtrack(
    problem: &mut dyn Nonlinear,
    x: &mut [f64],
    dx: &[f64],
    lambda: f64,
    r: &mut [f64],
    full: f64,
    reference: f64,
) -> Result<Option<f64>> {
    let mut best = (1.0, full);
    let mut alpha = 1.0;
    let mut trial = x.to_vec();
    let mut accepted = None;
    for _ in 0..HALVINGS {
        let next = 0.5 * alpha;
        // x0 + next dx from x0 + alpha dx
        for (t, d) in trial.iter_mut().zip(dx) {
            *t -= (alpha - next) * d;
        }
        alpha = next;
        problem.update_status(&trial, lambda)?;
        let m = problem.evaluate(&trial, lambda, r, false)?.relative();
        if !m.is_finite() {
            continue;
        }
        if m <= (1.0 - ARMIJO * alpha) * reference {
            accepted = Some(alpha);
            break;
        }
        if m < best.1 {
            best = (alpha, m);
        }
    }
    let alpha = match accepted {
        Some(a) => a,
        None if best.0 == 1.0 => {
            // back to the full correction and its statuses
            problem.update_status(x, lambda)?;
            problem.evaluate(x, lambda, r, false)?;
            return Ok(None);
        }
        None => {
            let a = best.0;
            for (t, (xi, d)) in trial.iter_mut().zip(x.iter().zip(dx)) {
                *t = xi - (1.0 - a) * d;
            }
            problem.update_status(&trial, lambda)?;
            a
        }
    };
    x.copy_from_slice(&trial);
    Ok(Some(alpha))
}

#[cfg(test)]
mod tests {
    use super::Merits;

    fn merits(v: &[f64]) -> Merits {
        let mut m = Merits::default();
        for &x in v {
            m.push(x);
        }
        m
    }

    #[test]
    fn a_swing_between_two_points_does_not_shrink() {
        // frozen corrections swinging: 3.10e-3, 3.24e-3, … after a best of 5.1e-3
        let m = merits(&[5.1e-3, 5.3e-3, 3.8e-3, 4.0e-3, 3.4e-3, 3.5e-3]);
        assert!(!m.shrinks(3.3e-3, 4, 0.5));
        // nor does a steady creep of 1 % a point
        let creep: Vec<f64> = (0..8).map(|k| 1e-2 * 0.99f64.powi(k)).collect();
        assert!(!merits(&creep).shrinks(1e-2 * 0.99f64.powi(8), 4, 0.5));
    }

    #[test]
    fn linear_convergence_shrinks() {
        // a contraction of 0.8 a point halves the best in four
        let m = merits(&[1.0, 0.8, 0.64, 0.512]);
        assert!(m.shrinks(0.41, 4, 0.5));
        // the best of the window counts, wherever it is in it
        let m = merits(&[1.0, 0.9, 0.3, 0.9]);
        assert!(m.shrinks(0.95, 4, 0.5));
        // measured against the best before the window, not the window's first point
        let m = merits(&[0.2, 1.0, 0.9, 0.8, 0.7]);
        assert!(!m.shrinks(0.15, 4, 0.5));
    }

    #[test]
    fn too_few_points_say_nothing() {
        assert!(merits(&[1.0, 1.0, 1.0]).shrinks(1.0, 4, 0.5));
        assert!(!merits(&[1.0, 1.0, 1.0, 1.0]).shrinks(1.0, 4, 0.5));
    }

    #[test]
    fn stalled_and_reference() {
        let m = merits(&[1.0, 0.5, 0.6, 0.7]);
        assert!(m.stalled(2));
        assert!(!m.stalled(3));
        assert_eq!(m.reference(), Some(0.7));
    }
}
