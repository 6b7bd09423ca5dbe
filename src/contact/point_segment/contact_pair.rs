//! `PointToSegment` as a `ContactPair`.

use super::super::surface::Surface;
use super::PointToSegment;
use crate::assembly::coupled::Triplets;
use crate::mesh::Mesh;

impl super::super::pair::ContactPair for PointToSegment {
    fn num_multipliers(&self) -> usize {
        self.num_multipliers()
    }
    fn initialise(&mut self, mesh: &Mesh) {
        self.initialise(mesh)
    }
    fn contribute(
        &self,
        mesh: &Mesh,
        u: &[f64],
        lam: &[f64],
        ru: &mut [f64],
        rl: &mut [f64],
        k: &mut Triplets,
        mult_base: usize,
    ) {
        self.contribute(mesh, u, lam, ru, rl, k, mult_base)
    }
    fn update_status(&mut self, mesh: &Mesh, u: &[f64], lam: &[f64]) -> usize {
        self.update_status(mesh, u, lam)
    }
    fn linearised_status(
        &mut self,
        mesh: &Mesh,
        u_lin: &[f64],
        u: &[f64],
        lam: &[f64],
    ) -> Option<usize> {
        self.linearised_status(mesh, u_lin, u, lam)
    }
    fn pattern_generation(&self) -> usize {
        self.candidates_generation
    }
    fn status_signature(&self) -> u64 {
        self.status_signature()
    }
    fn anticipate(&mut self, mesh: &Mesh, u: &[f64], reach: f64) {
        self.anticipate(mesh, u, reach)
    }
    fn commit(&mut self, u: &[f64], lam: &[f64]) {
        self.commit(u, lam)
    }
    fn restore(&mut self) {
        self.restore()
    }
    fn multiplier_nodes(&self) -> &[usize] {
        &self.mult_nodes
    }
    fn excluded_nodes(&self) -> &[usize] {
        &self.opts.contact_excluded
    }
    fn changed_nodes(&self) -> Vec<usize> {
        self.changed.clone()
    }
    fn open_at_rest(&mut self, mesh: &Mesh) -> bool {
        let u = vec![0.0; 2 * mesh.num_nodes()];
        // (round-off of a touching point's gap: a millionth of the touch tolerance)
        let tol = 1e-6 * self.touch_tolerance(mesh);
        let penetrating = (0..self.points.len()).any(|i| {
            let p = &self.points[i];
            !p.excluded && !p.left_out && self.eval(mesh, &u, i).d > tol
        });
        if penetrating {
            return false;
        }
        for p in &mut self.points {
            p.active = false;
        }
        true
    }
    fn surfaces(&self) -> (&Surface, &Surface) {
        (&self.slave, &self.master)
    }
    fn nodal_pressures(&self, lam: &[f64]) -> Vec<(usize, f64)> {
        self.nodal_pressures(lam)
    }
    fn nodal_shear(&self, lam: &[f64]) -> Vec<(usize, f64)> {
        // traction μ λ Λ (λ < 0 in compression): its magnitude is μ p |Λ| ≤ μ p
        let Some(mu) = self.opts.friction else {
            return vec![];
        };
        let nm = self.mult_nodes.len();
        // (with a tangential penalty the multiplier is the force itself)
        let scale = |k: usize| match self.opts.tangential_penalty {
            Some(_) => 1.0,
            None => mu * lam[k],
        };
        self.mult_nodes
            .iter()
            .enumerate()
            .map(|(k, &n)| (n, scale(k) * lam[nm + k] / self.node_weight[k]))
            .collect()
    }
    fn branch_switches(&self) -> usize {
        self.branch_switches
    }
    fn friction(&self) -> f64 {
        self.opts.friction.unwrap_or(0.0)
    }
}
