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
    /// Whether the next `contribute` calls need the tangent triplets (a residual alone
    /// may skip their costly part); they do until told otherwise.
    fn set_tangent_wanted(&self, _wanted: bool) {}
    /// Updates statuses (and pairing) from the iterate; returns how many changed.
    fn update_status(&mut self, mesh: &Mesh, u: &[f64], lam: &[f64]) -> usize;
    /// Bumped whenever the pair's matrix pattern grows (couplings that come within reach).
    fn pattern_generation(&self) -> usize {
        0
    }
    /// Takes into its pattern the couplings within reach at displacement u, predicted for
    /// the end of the loading, or within `reach` (a distance) of it (see
    /// `Nonlinear::anticipate`).
    fn anticipate(&mut self, _mesh: &Mesh, _u: &[f64], _reach: f64) {}
    /// Slave nodes whose status changed in the last `update_status` (for failure messages:
    /// where the statuses cycle).
    fn changed_nodes(&self) -> Vec<usize> {
        vec![]
    }
    /// A hash of the pair's discrete statuses (active set, friction branches).
    fn status_signature(&self) -> u64 {
        0
    }
    /// Statuses of the problem linearised at the last evaluation (its gaps and slips
    /// extended linearly to u), for active-set iterations at a fixed linearisation; how
    /// many changed, or None if the pair does not keep a linearisation (its Newton
    /// iterations already are such iterations, e.g. gaps linear in u). `u_lin` is the
    /// displacement of the last evaluation, the linearisation point (for a pair that does
    /// not store its linearisation: point-to-segment recomputes it there).
    fn linearised_status(
        &mut self,
        _mesh: &Mesh,
        _u_lin: &[f64],
        _u: &[f64],
        _lam: &[f64],
    ) -> Option<usize> {
        None
    }
    /// Opens every status (no contact, no friction) when no slave node penetrates the
    /// master in the undeformed geometry, and says whether it did: with nothing loading
    /// the bodies, the rest state is then the solution (a discretisation of the gap that
    /// sees a touching point as slightly closed, as dual mortar's weighted gap does, must
    /// not lift the bodies apart). False where the rest state is not checked so.
    fn open_at_rest(&mut self, _mesh: &Mesh) -> bool {
        false
    }
    /// The load step converged at displacement u and multipliers `lam` (this pair's).
    fn commit(&mut self, u: &[f64], lam: &[f64]);
    fn restore(&mut self);
    /// The slave and master surfaces.
    fn surfaces(&self) -> (&Surface, &Surface);
    /// (slave node, contact pressure) from the multipliers.
    fn nodal_pressures(&self, lam: &[f64]) -> Vec<(usize, f64)>;
    /// (slave node, tangential traction along the master tangent) from the multipliers;
    /// empty without friction.
    fn nodal_shear(&self, _lam: &[f64]) -> Vec<(usize, f64)> {
        vec![]
    }
    /// Slave node of each normal multiplier (multiplier k; with friction the tangential
    /// one of node k is multiplier `len + k`).
    fn multiplier_nodes(&self) -> &[usize];
    /// Slave nodes left out of contact (node-to-segment's `exclude`).
    fn excluded_nodes(&self) -> &[usize] {
        &[]
    }
    /// (slave node, [normal, tangential] multiplier) as the formulation stores them (the
    /// tangential one 0 without friction).
    fn nodal_multipliers(&self, lam: &[f64]) -> Vec<(usize, [f64; 2])> {
        let nodes = self.multiplier_nodes();
        let nm = nodes.len();
        let with_t = self.num_multipliers() >= 2 * nm;
        nodes
            .iter()
            .enumerate()
            .map(|(k, &n)| (n, [lam[k], if with_t { lam[nm + k] } else { 0.0 }]))
            .collect()
    }
    /// How far the last `contribute`'s constraint rows `rl` are from being satisfied,
    /// relative to the contact pressure scale (0: not measured, the displacement rows decide).
    fn constraint_residual(&self, _rl: &[f64], _lam: &[f64]) -> f64 {
        0.0
    }
    /// Whether Newton should re-solve from the same point when this pair's statuses change
    /// (cheap when the contact terms are: the bodies' factorisations stand).
    fn active_set_resolves(&self) -> bool {
        true
    }
    /// How far the bodies may overlap besides what the formulation's penetration allows
    /// (a distance: mortar's adjust keeps initial overlaps up to it).
    fn overlap_allowance(&self) -> f64 {
        0.0
    }
    /// Whether the contact forces act along normals of the reference geometry (mortar with
    /// small kinematics) rather than of the current one: the frame the outputs split the
    /// nodal forces in.
    fn reference_normals(&self) -> bool {
        false
    }
    /// Contact points whose friction branch (stick, slip either way) the last status
    /// update changed where the formulation does not count these among its status
    /// changes (point-to-segment decides the branches in the residual).
    fn branch_switches(&self) -> usize {
        0
    }
    /// Coulomb coefficient of the pair (0 without friction).
    fn friction(&self) -> f64 {
        0.0
    }
    /// Whether the tangent is the exact derivative of the residual everywhere, rather than
    /// only at solutions (where a formulation drops terms that vanish there: mortar's
    /// augmentation curvature). For finite-difference checks of the tangent.
    fn set_exact_tangent(&mut self, _exact: bool) {}
    /// Whether the formulation's terms exist with small kinematics (on the reference
    /// geometry) as well as large (see `ContactProblem`'s `set_linear_kinematics`).
    fn supports_small_kinematics(&self) -> bool {
        false
    }
    /// Whether the contact terms take the reference geometry (small kinematics) instead of
    /// the current one (where `supports_small_kinematics`).
    fn set_small_kinematics(&mut self, _small: bool) {}
}
