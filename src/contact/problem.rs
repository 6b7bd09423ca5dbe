//! `ContactProblem`: elastic bodies plus contact pairs. Unknowns are the free displacements
//! followed by the multipliers of every pair; the matrix is the solid one plus the contact
//! blocks (symmetric indefinite: solved with LU).

use super::overlap::OverlapCheck;
use super::pair::ContactPair;
use crate::assembly::coupled::{CoupledMatrix, Triplets};
use crate::assembly::matrix::SparseMatrix;
use crate::error::Result;
use crate::fem::solid::Kinematics;
use crate::solver::newton::Nonlinear;
use crate::solver::problem::{Norms, SolidProblem};

/// The error allowed for a prediction of the displacement at the loading's end (see
/// `anticipate`), as a fraction of the largest motion it extrapolates: couplings within
/// that distance of the predicted geometry are taken in too. SSNP154 A point-to-segment at
/// 98k unknowns: without it, the first step's prediction fell 46 interface unknowns short
/// of the zone at the loading's end, and the second step analysed the pattern again; at
/// 960k D point-to-segment's did, twice. 0.5: D 266k took in no more than without.
const PREDICTION_ERROR: f64 = 0.5;

pub struct ContactProblem<'m> {
    pub solid: SolidProblem<'m>,
    pub pairs: Vec<Box<dyn ContactPair>>,
    /// First multiplier index of each pair.
    pub mult_base: Vec<usize>,
    /// All multipliers, current values.
    pub lam: Vec<f64>,
    coupled: CoupledMatrix,
    triplets: Triplets,
    ru: Vec<f64>,
    saved_lam: Vec<f64>,
    /// No contact node deep inside the other body (the formulations can miss a body
    /// pushed through another).
    overlap: OverlapCheck,
    /// The displacement of the last converged state, where the overlap check's paths start.
    committed_u: Vec<f64>,
    /// Called at each converged state before the pairs commit it: the outputs of a state
    /// are taken there, as the pairs' statuses and friction history move on with the solve
    /// (a state evaluated again after the solve would get the last step's).
    pub on_commit: Option<CommitHook<'m>>,
    /// The bodies' models with large kinematics (see `set_linear_kinematics`).
    large_models: Vec<usize>,
}

/// See `ContactProblem::on_commit`.
pub type CommitHook<'m> = Box<dyn FnMut(&ContactProblem<'m>) + 'm>;

impl<'m> ContactProblem<'m> {
    /// The coupled tangent from the solid values as last assembled and the contact
    /// triplets of the last evaluation.
    fn update_matrix(&mut self) -> Result<()> {
        let (target, dofs) = self.solid.asm.solid_target();
        self.coupled
            .update(target, dofs, self.lam.len(), &self.triplets)
    }

    pub fn new(solid: SolidProblem<'m>, mut pairs: Vec<Box<dyn ContactPair>>) -> Self {
        let mut mult_base = vec![];
        let mut n = 0;
        for p in &mut pairs {
            p.initialise(solid.mesh);
            mult_base.push(n);
            n += p.num_multipliers();
        }
        let ndof = solid.u.len();
        let overlap = OverlapCheck::new(solid.mesh, &pairs);
        let committed_u = solid.u.clone();
        let large_models = (solid.asm.cell_model.iter().enumerate())
            .filter(|(_, m)| m.kinematics == Kinematics::Large)
            .map(|(i, _)| i)
            .collect();
        ContactProblem {
            solid,
            pairs,
            mult_base,
            lam: vec![0.0; n],
            coupled: CoupledMatrix::default(),
            triplets: Triplets::default(),
            ru: vec![0.0; ndof],
            saved_lam: vec![0.0; n],
            overlap,
            committed_u,
            on_commit: None,
            large_models,
        }
    }

    /// The undeformed bodies overlapping deeper than the contact tolerates (see
    /// `overlap`): a message naming the pair, the nodes and the depth.
    pub fn initial_overlap(&self) -> Option<String> {
        self.overlap.at_start(self.solid.mesh)
    }

    pub fn pattern_rebuilds(&self) -> usize {
        self.coupled.rebuilds
    }

    /// Sets the state, writes the residual, assembles the solid tangent and the coupled
    /// matrix with the contact tangent as asked (a residual alone skips the contact
    /// tangent's costly part).
    fn evaluate_with(
        &mut self,
        x: &[f64],
        lambda: f64,
        r: &mut [f64],
        solid_tangent: bool,
        contact_tangent: bool,
    ) -> Result<Norms> {
        let nf = self.solid.num_free();
        self.solid.set_state(&x[..nf], lambda, solid_tangent)?;
        self.lam.copy_from_slice(&x[nf..]);
        self.ru.fill(0.0);
        r[nf..].fill(0.0);
        self.triplets.clear();
        let mesh = self.solid.mesh;
        for (i, (p, &base)) in self.pairs.iter().zip(&self.mult_base).enumerate() {
            let n = p.num_multipliers();
            self.triplets.begin_pair(i);
            p.set_tangent_wanted(contact_tangent);
            p.contribute(
                mesh,
                &self.solid.u,
                &self.lam[base..base + n],
                &mut self.ru,
                &mut r[nf + base..nf + base + n],
                &mut self.triplets,
                base,
            );
            p.set_tangent_wanted(true);
        }
        let mut norms = self.solid.finish_residual(Some(&self.ru), &mut r[..nf]);
        for (p, &base) in self.pairs.iter().zip(&self.mult_base) {
            let n = p.num_multipliers();
            let c = p.constraint_residual(&r[nf + base..nf + base + n], &self.lam[base..base + n]);
            norms.constraint = norms.constraint.max(c);
        }
        if contact_tangent {
            self.update_matrix()?;
        }
        Ok(norms)
    }
}

impl Nonlinear for ContactProblem<'_> {
    fn state_defect(&self) -> Option<String> {
        self.solid.solid_defect().or_else(|| {
            self.overlap
                .during_step(self.solid.mesh, &self.committed_u, &self.solid.u)
        })
    }
    fn num_unknowns(&self) -> usize {
        self.solid.num_free() + self.lam.len()
    }

    fn length_scale(&self) -> f64 {
        self.solid.length_scale()
    }

    fn num_primal(&self) -> usize {
        self.solid.num_free()
    }

    fn unknowns(&self) -> Vec<f64> {
        let mut x = self.solid.free_unknowns();
        x.extend_from_slice(&self.lam);
        x
    }

    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        r: &mut [f64],
        with_tangent: bool,
    ) -> Result<Norms> {
        self.evaluate_with(x, lambda, r, with_tangent, with_tangent)
    }

    fn evaluate_contact_tangent(&mut self, x: &[f64], lambda: f64, r: &mut [f64]) -> Result<Norms> {
        // the solid matrix keeps the last assembled tangent; contact terms are current
        self.evaluate_with(x, lambda, r, false, true)
    }

    fn matrix(&self) -> &SparseMatrix {
        // (the solid matrix, extended with the contact terms by `update_matrix`)
        &self.solid.asm.matrix
    }

    fn update_status(&mut self, x: &[f64], lambda: f64) -> Result<usize> {
        let nf = self.solid.num_free();
        let mut u = vec![0.0; self.solid.u.len()];
        self.solid.displacement(&x[..nf], lambda, &mut u);
        let lam = &x[nf..];
        let mesh = self.solid.mesh;
        let mut changes = 0;
        for (p, &base) in self.pairs.iter_mut().zip(&self.mult_base) {
            let n = p.num_multipliers();
            changes += p.update_status(mesh, &u, &lam[base..base + n]);
        }
        Ok(changes)
    }

    fn pattern_generation(&self) -> usize {
        self.pairs.iter().map(|p| p.pattern_generation()).sum()
    }

    fn anticipate(&mut self, x: &[f64], lambda: f64, predicted: &[f64], end: f64) {
        let nf = self.solid.num_free();
        let mut u = vec![0.0; self.solid.u.len()];
        self.solid.displacement(&x[..nf], lambda, &mut u);
        let mut u_end = vec![0.0; self.solid.u.len()];
        self.solid.displacement(&predicted[..nf], end, &mut u_end);
        let motion = u
            .chunks(2)
            .zip(u_end.chunks(2))
            .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
            .fold(0.0, f64::max);
        let mesh = self.solid.mesh;
        for p in &mut self.pairs {
            p.anticipate(mesh, &u_end, PREDICTION_ERROR * motion);
        }
    }

    fn restart_statuses(&mut self) {
        let mesh = self.solid.mesh;
        for p in &mut self.pairs {
            p.initialise(mesh);
        }
    }

    fn open_at_rest(&mut self) -> bool {
        let mesh = self.solid.mesh;
        self.pairs.iter_mut().all(|p| p.open_at_rest(mesh))
    }

    fn changed_nodes(&self) -> Vec<usize> {
        self.pairs.iter().flat_map(|p| p.changed_nodes()).collect()
    }

    fn residual_location(&self, r: &[f64]) -> Option<String> {
        self.solid.residual_location(r)
    }

    fn status_signature(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        for p in &self.pairs {
            p.status_signature().hash(&mut h);
        }
        h.finish()
    }

    fn update_status_linearised(&mut self, x: &[f64], lambda: f64) -> Result<Option<usize>> {
        let nf = self.solid.num_free();
        let mut u = vec![0.0; self.solid.u.len()];
        self.solid.displacement(&x[..nf], lambda, &mut u);
        let lam = &x[nf..];
        let mesh = self.solid.mesh;
        let mut changes = Some(0);
        for (p, &base) in self.pairs.iter_mut().zip(&self.mult_base) {
            let n = p.num_multipliers();
            // (the last evaluation's displacement is the linearisation point)
            let linearised = p.linearised_status(mesh, &self.solid.u, &u, &lam[base..base + n]);
            changes = match (changes, linearised) {
                (Some(a), Some(b)) => Some(a + b),
                _ => None,
            };
        }
        Ok(changes)
    }

    fn imposed_change(&self, t0: f64, t1: f64) -> bool {
        self.solid.imposed_change(t0, t1)
    }

    // (bodies without contact go through Newton: its factorisation tells a model with a
    // rigid-body mode; with contact, bodies held by contact alone are free at rest)
    fn unloaded(&self, t: f64) -> bool {
        self.solid.unloaded(t)
    }

    fn active_set_resolves(&self) -> bool {
        self.pairs.iter().all(|p| p.active_set_resolves())
    }

    // Only where the statuses are those of the iterate (point-to-segment, node-to-segment):
    // with friction, a correction that follows many status changes can throw a fine mesh
    // far off (SSNP154 D at 0.07 mm: the residual 100× up in one correction, then step
    // cuts to failure). Not mortar's: its corrections are semi-smooth Newton's on the
    // plain mortar equations (the augmentation's curvature left out), whose full steps
    // settle the active set; shortened, they left a contact zone growing by a node or two
    // per iteration (SSNP154 A at 0.047 mm, second load step: 1/16 steps, a stall and a
    // cut; full steps: 8 iterations), and with friction they cut steps of a block
    // sliding round a ring under large rotation (tests/history.rs).
    fn line_search(&self) -> bool {
        self.active_set_resolves()
    }

    fn branch_switches(&self) -> usize {
        self.pairs.iter().map(|p| p.branch_switches()).sum()
    }

    fn backtracking(&self) -> bool {
        self.pairs.iter().any(|p| p.friction() > 0.0)
    }

    // The bodies and the pairs switch, when every pair's terms have both kinematics
    // (mortar's). Then the linear problem is piecewise linear: its active set settles
    // without the geometry's nonlinearity. Point-to-segment's and node-to-segment's terms
    // stay on the deformed geometry, and a stage with linear bodies alone only added
    // iterations (SSNP154 A and D, 7 meshes each × 1–3 load steps: 504 → 658 and
    // 796 → 957 Newton iterations).
    fn set_linear_kinematics(&mut self, linear: bool) -> bool {
        if self.large_models.is_empty() || !self.pairs.iter().all(|p| p.supports_small_kinematics())
        {
            return false;
        }
        let k = if linear {
            Kinematics::Small
        } else {
            Kinematics::Large
        };
        for &i in &self.large_models {
            self.solid.asm.cell_model[i].kinematics = k;
        }
        for p in &mut self.pairs {
            p.set_small_kinematics(linear);
        }
        self.solid.forget_assembly();
        true
    }

    fn commit_step(&mut self) {
        if let Some(mut hook) = self.on_commit.take() {
            hook(self);
            self.on_commit = Some(hook);
        }
        for (p, &base) in self.pairs.iter_mut().zip(&self.mult_base) {
            let n = p.num_multipliers();
            p.commit(&self.solid.u, &self.lam[base..base + n]);
        }
        self.saved_lam.clone_from(&self.lam);
        self.committed_u.clone_from(&self.solid.u);
    }

    fn restore_step(&mut self) {
        for p in &mut self.pairs {
            p.restore();
        }
    }
}
