//! Coulomb friction per slave node: the branch (free, stick, slip) from the iterate.

use super::Mortar;

/// The Coulomb branch of a slave node: no friction (no contact or no pressure), stick, or
/// slip with the sign of the trial traction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Branch {
    Free,
    Stick,
    Slip(f64),
}

impl Mortar {
    /// The branch of node j at (λ, t) = (lam[j], lam[nm + j]) with weighted slip `slip` and
    /// D_j = `d`; `lmax` is the largest |λ|. `contribute` and `update_status` both use it.
    pub(super) fn branch(
        &self,
        j: usize,
        lam: &[f64],
        slip: f64,
        d: f64,
        lmax: f64,
        mu: f64,
    ) -> Branch {
        let nm = self.mult_nodes.len();
        let pressure = lam[j];
        if !self.active[j]
            || d == 0.0
            || self.friction_excluded.contains(&j)
            || pressure <= 1e-8 * lmax
        {
            return Branch::Free;
        }
        let cf = self.trial_scale.get(j).copied().unwrap_or(1.0);
        let trial = lam[nm + j] + cf * self.c * slip / d;
        if trial.abs() <= mu * pressure {
            Branch::Stick
        } else {
            Branch::Slip(trial.signum())
        }
    }
}
