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
    /// The branch of node j at (λ, t) = (lam[j], lam[nm + j]) with weighted slip `slip`,
    /// weighted gap and D_j `gd`; `lmax` is the largest |λ|. `contribute` and
    /// `update_status` both use it. The Coulomb bound is μ times the augmented pressure
    /// λ_j − c g̃_j/D_j, the quantity whose sign makes the node active (Hüeber, Stadler,
    /// Wohlmuth 2008; Gitterle et al. 2010): the same as μ λ_j at a solution (g̃_j = 0),
    /// but far from it a node pressed in (active) with a multiplier still negative kept
    /// switching between no friction and slip. SSNP154 D with mortar in one load step at
    /// 0.13 mm: 241 Newton iterations and 4 step cuts → 32 and none.
    pub(super) fn branch(
        &self,
        j: usize,
        lam: &[f64],
        slip: f64,
        gd: (f64, f64),
        lmax: f64,
        mu: f64,
    ) -> Branch {
        let (g, d) = gd;
        let nm = self.mult_nodes.len();
        let pressure = if d != 0.0 {
            lam[j] - self.c * g / d
        } else {
            lam[j]
        };
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
