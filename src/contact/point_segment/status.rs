//! Statuses: the initial ones, the active set update from the iterate or on the
//! linearisation, what a step commits and a cut step restores; contact pressures from the
//! multipliers.

use super::residual::gap_row;
use super::{InitialStatus, PointToSegment, Saved};
use crate::mesh::Mesh;

impl PointToSegment {
    /// Sets the initial statuses from the undeformed geometry.
    pub fn initialise(&mut self, mesh: &Mesh) {
        let u = vec![0.0; 2 * mesh.num_nodes()];
        for i in 0..self.points.len() {
            self.pair(mesh, &u, i, false, &[], false);
            let p = &self.points[i];
            let active = !p.excluded
                && match self.opts.initial {
                    InitialStatus::All => true,
                    InitialStatus::Closed => {
                        let gap = self
                            .opts
                            .initial_gap
                            .unwrap_or_else(|| self.touch_tolerance(mesh));
                        self.eval(mesh, &u, i).d >= -gap
                    }
                };
            self.points[i].active = active;
        }
        // A touching point of no weight (on the axis) holds nothing: the other points of its
        // cell start active in its place (a body held by contact alone would start free).
        let gap = self
            .opts
            .initial_gap
            .unwrap_or_else(|| self.touch_tolerance(mesh));
        let wmax = self.points.iter().fold(0.0f64, |m, p| m.max(p.omega));
        for i in 0..self.points.len() {
            let p = &self.points[i];
            let weightless = p.omega <= 1e-12 * wmax && !self.opts.node_to_segment;
            if weightless
                && self.opts.initial == InitialStatus::Closed
                && self.eval(mesh, &u, i).d >= -gap
            {
                let cell = p.cell;
                for q in self
                    .points
                    .iter_mut()
                    .filter(|q| q.cell == cell && !q.excluded)
                {
                    q.active = true;
                }
            }
        }
        self.save_start();
    }

    /// The statuses and pairings a cut step restores.
    pub(super) fn save_start(&mut self) {
        self.saved = self
            .points
            .iter()
            .map(|p| Saved {
                active: p.active,
                master: p.master,
                xi_m: p.xi_m,
                excluded: p.excluded,
            })
            .collect();
    }

    /// Re-pairs and updates the statuses from the iterate (u, λ); returns the number of changes.
    pub fn update_status(&mut self, mesh: &Mesh, u: &[f64], lam: &[f64]) -> usize {
        self.pair_all(mesh, u);
        let mut changes = 0;
        self.changed.clear();
        self.branch_switches = 0;
        let lambda_floor = self.friction_floor(lam);
        let count_switches = self.opts.friction.is_some() && self.opts.tangential_penalty.is_none();
        // (the balanced ρ_f's pressure floor: only where the branches are decided here)
        let peak = if count_switches {
            self.peak_pressure(lam)
        } else {
            0.0
        };
        for i in 0..self.points.len() {
            let e = self.eval(mesh, u, i);
            let lp = self.point_lambda(mesh, i, &e.ns, lam);
            let p = &self.points[i];
            let active = !p.excluded && lp - self.opts.rho * e.d < 0.0;
            if active != p.active {
                changes += 1;
                self.points[i].active = active;
                self.changed.push(self.nearest_slave_node(mesh, i, &e.ns));
            }
            if count_switches {
                self.count_friction_switch(mesh, u, lam, i, (&e, lp, lambda_floor, peak));
            }
        }
        changes
    }

    /// Statuses of the problem linearised at `u_lin` (the last evaluation), taken at the
    /// trial point (u, λ): each point keeps its pairing, and its gap is extended linearly
    /// along its normal there (B·Δu; the smoothed normal's turn with the cells around,
    /// second order at a solution, is left out). Newton takes them where re-solves on the
    /// iterate's own statuses swing: a first correction from a point contact pushes a body
    /// far through the other, where the gaps of the deformed cells say little of the
    /// contact zone, and the linearised gaps are those the correction itself satisfies.
    /// Friction branches stay with the iterate's update.
    pub fn linearised_status(
        &mut self,
        mesh: &Mesh,
        u_lin: &[f64],
        u: &[f64],
        lam: &[f64],
    ) -> Option<usize> {
        let mut changes = 0;
        self.changed.clear();
        for i in 0..self.points.len() {
            // (a point left unpaired, beyond reach at the linearisation point, is paired
            // there however far: the correction may have closed it)
            if self.points[i].excluded && !self.points[i].left_out {
                self.pair(mesh, u_lin, i, false, &[], true);
            }
            let e = self.eval(mesh, u_lin, i);
            let p = &self.points[i];
            let snodes = mesh.cell_nodes(self.slave.cells[p.cell]);
            let mnodes = mesh.cell_nodes(self.master.cells[p.master]);
            let d = e.d
                + gap_row(&e, snodes, mnodes)
                    .iter()
                    .map(|&(dof, v)| v * (u[dof] - u_lin[dof]))
                    .sum::<f64>();
            let lp = self.point_lambda(mesh, i, &e.ns, lam);
            let active = !p.excluded && lp - self.opts.rho * d < 0.0;
            if active != p.active {
                changes += 1;
                let (ic, im) = (p.cell, p.master);
                self.points[i].active = active;
                self.changed.push(self.nearest_slave_node(mesh, i, &e.ns));
                if active && !self.candidates[ic].contains(&im) {
                    self.add_candidates(mesh, ic, im);
                }
            }
        }
        Some(changes)
    }

    /// The slave node nearest point i (of shape functions `ns` on its cell).
    fn nearest_slave_node(&self, mesh: &Mesh, i: usize, ns: &[f64]) -> usize {
        let (a, _) = ns
            .iter()
            .enumerate()
            .fold((0, f64::MIN), |b, (a, &v)| if v > b.1 { (a, v) } else { b });
        mesh.cell_nodes(self.slave.cells[self.points[i].cell])[a]
    }

    /// A hash of the points' contact statuses, their active flags alone (what a status
    /// update counts as changes): a cycle of active-set re-solves.
    pub(super) fn status_signature(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        for p in &self.points {
            p.active.hash(&mut h);
        }
        h.finish()
    }

    pub fn commit(&mut self, u: &[f64], lam: &[f64]) {
        self.save_start();
        self.u_start.copy_from_slice(u);
        self.switches.fill(0);
        if self.opts.friction.is_some() && self.opts.tangential_penalty.is_some() {
            // (the tangential multipliers are the forces)
            let nm = self.mult_nodes.len();
            self.q_start.copy_from_slice(&lam[nm..2 * nm]);
        }
    }

    pub fn restore(&mut self) {
        for (p, s) in self.points.iter_mut().zip(&self.saved) {
            p.active = s.active;
            p.master = s.master;
            p.xi_m = s.xi_m;
            p.excluded = s.excluded;
        }
    }

    /// Contact pressure at each slave node from the multipliers: (node, −λ).
    pub fn nodal_pressures(&self, lam: &[f64]) -> Vec<(usize, f64)> {
        let mut p: Vec<f64> = (0..self.mult_nodes.len())
            .map(|k| {
                if self.weightless[k] {
                    0.0
                } else {
                    -lam[k] / self.node_weight[k]
                }
            })
            .collect();
        super::super::axis::fill_weightless(
            &self.mult_coords,
            &mut p,
            &self.reported_from_neighbours,
        );
        self.mult_nodes.iter().copied().zip(p).collect()
    }
}
