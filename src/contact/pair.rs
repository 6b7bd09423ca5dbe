//! The interface every contact formulation offers to `ContactProblem`.

use super::surface::Surface;
use crate::assembly::coupled::Triplets;
use crate::mesh::Mesh;

pub trait ContactPair {
    fn num_multipliers(&self) -> usize;
    /// Initial statuses from the undeformed geometry.
    fn initialise(&mut self, mesh: &Mesh);
    /// Adds the residual (`ru` on full dofs, `rl` on this pair's multipliers) and the
    /// tangent triplets (multiplier k of this pair is extended id `ndof + mult_base + k`).
    #[allow(clippy::too_many_arguments)] // state in, three accumulators out
    fn contribute(
        &self,
        mesh: &Mesh,
        u: &[f64],
        lam: &[f64],
        ru: &mut [f64],
        rl: &mut [f64],
        k: &mut Triplets,
        mult_base: usize,
    );
    /// Updates statuses (and pairing) from the iterate; returns how many changed.
    fn update_status(&mut self, mesh: &Mesh, u: &[f64], lam: &[f64]) -> usize;
    fn commit(&mut self);
    fn restore(&mut self);
    /// The slave and master surfaces.
    fn surfaces(&self) -> (&Surface, &Surface);
    /// (slave node, contact pressure) from the multipliers.
    fn nodal_pressures(&self, lam: &[f64]) -> Vec<(usize, f64)>;
}
