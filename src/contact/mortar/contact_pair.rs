//! The `ContactPair` implementation of the mortar pair: initialisation (the initial active
//! set and the `adjust` offsets), the residual and tangent assembly (`contribute`), status
//! updates and re-pairing, step commit and restore, and the pair's outputs.

use super::super::pair::ContactPair;
use super::super::point_segment::{
    anticipated_candidates, candidates_within, overlap_candidates, swept_candidates,
};
use super::super::surface::Surface;
use super::active_set::{self, row_weights};
use super::friction::Branch;
use super::linearisation::linear_tangent;
use super::segments::CellTerms;
use super::{add_new, Mortar, PATTERN_MARGIN};
use crate::assembly::coupled::Triplets;
use crate::mesh::Mesh;
use std::sync::atomic::Ordering;

impl ContactPair for Mortar {
    fn num_multipliers(&self) -> usize {
        self.mult_nodes.len() * if self.friction.is_some() { 2 } else { 1 }
    }

    fn initialise(&mut self, mesh: &Mesh) {
        // Nodes already touching (normalised gap within 1e-6 of the cell size) start active.
        let u = vec![0.0; 2 * mesh.num_nodes()];
        // A closed start closes the nodes within initial_gap: each must see the master
        // cells it closes onto, also where the gap is more than a cell (fine meshes).
        // Without them a node at the edge of the closed zone faced nothing at the start,
        // was released by the first re-solve and left a hole in the active set that the
        // bodies then crossed (SSNP154 B at 0.094 mm: 0.28 mm deep, a step cut; 49 → 27
        // iterations, D 88 → 29).
        if let Some(gap) = self.initial_gap {
            let near = candidates_within(mesh, None, &self.slave, &self.master, 1.0, gap);
            // (also those a cut first step restores)
            self.saved_candidates.clone_from(&near);
            self.candidates = near;
        }
        self.offset.clear();
        let (g0, d, facing, _) = self.gaps(mesh, &u);
        self.offset = match self.adjust {
            Some(dist) => (0..g0.len())
                .map(|k| {
                    let near = facing[k] && d[k] != 0.0 && g0[k].abs() <= dist * d[k].abs();
                    if near {
                        g0[k]
                    } else {
                        0.0
                    }
                })
                .collect(),
            None => vec![0.0; g0.len()],
        };
        let touch: Vec<bool> = (0..self.active.len())
            .map(|k| self.touching(mesh, &u, self.mult_nodes[k]))
            .collect();
        for k in 0..self.active.len() {
            let adjusted = self.offset[k] != 0.0;
            self.active[k] = facing[k] && (self.initial_all || adjusted || touch[k]);
        }
        // A touching node without weight (a quadratic slave's corner on the axis, which
        // faces nothing by weight either) holds nothing: the weighted nodes of its cells,
        // the nearest that can, start active too (a body held by contact alone would
        // otherwise start free).
        for nodes in &self.cell_mults {
            if nodes.iter().any(|&k| touch[k] && d[k] == 0.0) {
                for &k in nodes {
                    self.active[k] |= facing[k] && d[k] != 0.0;
                }
            }
        }
        self.grow_pattern(None);
        self.saved = self.active.clone();
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
        let ndof = 2 * mesh.num_nodes();
        let nm = self.mult_nodes.len();
        let cached = self.terms_cache.lock().unwrap().take();
        let terms: Vec<CellTerms> = match cached {
            Some((u0, terms)) if u0 == u => terms,
            _ => self.all_cell_terms(mesh, u),
        };
        let (mut g, mut d) = (vec![0.0; nm], vec![0.0; nm]);
        for (j, o) in self.offset.iter().enumerate() {
            g[j] = -o;
        }
        for t in &terms {
            for &(j, v) in &t.gap {
                g[j] += v;
            }
            for &(j, v) in &t.dj {
                d[j] += v;
            }
            for &(j, dof, v) in &t.force {
                ru[dof] += lam[j] * v;
                // K_uλ (not of an open node with a zero multiplier: its correction is zero)
                if self.active[j] || lam[j] != 0.0 {
                    k.add(dof, ndof + mult_base + j, v);
                }
            }
        }
        self.last_d.lock().unwrap().clone_from(&d);
        // a node without weight (on the axis) carries no contact constraint
        let active: Vec<bool> = (0..nm).map(|j| self.active[j] && d[j] != 0.0).collect();
        // Augmentation on active nodes: the force of the energy (c/2) g̃_j²/D_j, zero at
        // convergence (g̃_j = 0) but giving the displacement block the stiffness that holds
        // bodies only held by contact, so that the saddle-point LDLT needs no pivoting.
        let mut fj: Vec<Vec<(usize, f64)>> = vec![vec![]; nm];
        for t in &terms {
            for &(j, dof, v) in &t.force {
                if active[j] {
                    fj[j].push((dof, v));
                }
            }
        }
        for j in 0..nm {
            if active[j] {
                for &(dof, v) in &fj[j] {
                    ru[dof] += -self.c * g[j] / d[j] * v;
                }
            }
        }
        let row_d = row_weights(&d);
        for j in 0..nm {
            if active[j] {
                rl[j] += -g[j];
            } else {
                rl[j] += -lam[j] * row_d[j] / self.c;
                k.add(
                    ndof + mult_base + j,
                    ndof + mult_base + j,
                    -row_d[j] / self.c,
                );
            }
        }
        // Coulomb friction per slave node (semi-smooth, decided from the iterate): with the
        // traction t_j and the trial t_j + c s̃_j / D_j, no contact (or no pressure): t_j = 0;
        // stick (|trial| ≤ μ λ_j): s̃_j = 0; slip: t_j = μ λ_j sign(trial). Rows scaled by
        // D_j / c like the normal ones.
        let mut sl = vec![0.0; nm];
        let mut law = vec![Branch::Free; nm];
        if let Some(mu) = self.friction {
            let mut tf: Vec<Vec<(usize, f64)>> = vec![vec![]; nm];
            for t in &terms {
                for &(j, v) in &t.slip {
                    sl[j] += v;
                }
                for &(j, dof, v) in &t.tforce {
                    tf[j].push((dof, v));
                }
            }
            let lmax = lam[..nm].iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for j in 0..nm {
                let tj = lam[nm + j];
                let row = ndof + mult_base + nm + j;
                law[j] = self.branch(j, lam, sl[j], d[j], lmax, mu);
                // (K_ut: not of a free node with a zero traction, as K_uλ above)
                let coupled = law[j] != Branch::Free || tj != 0.0;
                for &(dof, v) in &tf[j] {
                    ru[dof] += tj * v;
                    if coupled {
                        k.add(dof, row, v);
                    }
                }
                match law[j] {
                    Branch::Free => {
                        rl[nm + j] += -tj * row_d[j] / self.c;
                        k.add(row, row, -row_d[j] / self.c);
                    }
                    Branch::Stick => rl[nm + j] += -sl[j],
                    Branch::Slip(sg) => {
                        let scale = d[j] / self.c;
                        rl[nm + j] += -(tj - mu * lam[j] * sg) * scale;
                        k.add(row, row, -scale);
                        k.add(row, ndof + mult_base + j, mu * sg * scale);
                    }
                }
            }
        }
        // (a residual alone: no tangent, no linearisation, no pattern)
        if !self.tangent_wanted.load(Ordering::Relaxed) {
            return;
        }
        if self.small {
            linear_tangent(&terms, self.c, &active, &d, &law, ndof + mult_base, nm, k);
        } else {
            let rows = ndof + mult_base;
            let dg = self.exact_tangent(mesh, u, lam, (&g, &d), &fj, &active, &law, rows, k);
            let facing = self.facing(mesh, u, &terms, &d);
            *self.linearisation.lock().unwrap() = Some(active_set::Linearisation {
                u0: u.to_vec(),
                g,
                d,
                facing,
                dg,
            });
        }
        // pattern: every dof a cell may read couples with every dof and multiplier of its
        // cells; the matrix keeps a pattern once built, so these zeros are sent only when
        // the pattern's candidates have changed since they were last sent
        let generation = self.pattern_generation;
        if self.pattern_sent.swap(generation, Ordering::Relaxed) == generation {
            return;
        }
        let mut cliques = Vec::with_capacity(self.slave.cells.len());
        for (ic, &sc) in self.slave.cells.iter().enumerate() {
            let nodes = self.nodes_in_pattern(mesh, ic);
            let mut mults: Vec<usize> = mesh
                .cell_nodes(sc)
                .iter()
                .map(|n| ndof + mult_base + self.mult_of[n])
                .collect();
            if self.friction.is_some() {
                let tangential: Vec<usize> = mults.iter().map(|m| m + nm).collect();
                mults.extend(tangential);
            }
            // (a slave cell not reserved has no coupling yet: its nodes stay inside their
            // body, out of the interface)
            let mut all: Vec<usize> = if !self.reserved[ic] {
                vec![]
            } else {
                nodes.iter().flat_map(|&n| [2 * n, 2 * n + 1]).collect()
            };
            all.extend_from_slice(&mults);
            cliques.push(all);
        }
        k.add_clique_union(&cliques);
    }

    fn update_status(&mut self, mesh: &Mesh, u: &[f64], lam: &[f64]) -> usize {
        // Re-pair on the current geometry (large sliding): the master cells near each slave
        // cell now; a new set changes the residual, so it counts as a status change.
        // Small kinematics integrates on the reference configuration: the cells near in it
        // stay candidates whatever the iterate (a first iterate held by one touching node
        // may move a body far through the other), and those near in the deformed one join
        // them (the initial gaps that have closed, and overlaps however deep: see
        // `overlap_reach`), sought along the slave cell's normal, on both geometries (its
        // normals project on the reference one).
        // Large kinematics seeks along the normal too, inward only: the master cells a
        // slave cell has passed through. Within a cell size alone, a node overlapping
        // deeper faced nothing and could not close: SSNP154 A at 1.27M unknowns (cells of
        // 0.017 mm), the second step's first correction overlapped 0.017 mm and more
        // beyond the first step's zone; the zone then closed and reopened a few nodes per
        // body factorisation, 40 iterations (now 14) and 123 s → 90 s for the whole run.
        let reach = self.overlap_reach(mesh, u);
        let mut near = if self.small {
            swept_candidates(mesh, Some(u), &self.slave, &self.master, 1.0, reach)
        } else {
            overlap_candidates(mesh, u, &self.slave, &self.master, 1.0, reach)
        };
        if self.small {
            let reference = swept_candidates(mesh, None, &self.slave, &self.master, 1.0, reach);
            for (n, r) in near.iter_mut().zip(reference) {
                for im in r {
                    if !n.contains(&im) {
                        n.push(im);
                    }
                }
                n.sort_unstable();
            }
        }
        let mut changes = 0;
        let mut changed = vec![];
        if near != self.candidates {
            changes += 1;
            self.candidates = near;
        }
        let (g, d, facing, sl) = self.gaps(mesh, u);
        for j in 0..self.active.len() {
            let active = facing[j] && d[j] != 0.0 && lam[j] - self.c * g[j] / d[j] > 0.0;
            if active != self.active[j] {
                changes += 1;
                self.active[j] = active;
                changed.push(self.mult_nodes[j]);
            }
        }
        if let Some(mu) = self.friction {
            // the branch `contribute` takes at this iterate
            let nm = self.mult_nodes.len();
            self.law.resize(nm, Branch::Free);
            self.trial_scale.resize(nm, 1.0);
            self.switches.resize(nm, 0);
            let lmax = lam[..nm].iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for j in 0..nm {
                let law = self.branch(j, lam, sl[j], d[j], lmax, mu);
                if law != self.law[j] {
                    super::super::friction::count_switch(
                        &mut self.switches[j],
                        &mut self.trial_scale[j],
                    );
                    changes += 1;
                    self.law[j] = law;
                    changed.push(self.mult_nodes[j]);
                }
            }
        }
        self.changed = changed;
        self.grow_pattern(Some(lam));
        changes
    }

    fn pattern_generation(&self) -> usize {
        self.pattern_generation
    }

    /// Reserves the slave cells near the master at the predicted displacement `u`
    /// (`anticipated_candidates`, as point-to-segment's), with the master cells found
    /// there and their candidates at `u`.
    fn anticipate(&mut self, mesh: &Mesh, u: &[f64], reach: f64) {
        let surfaces = (&self.slave, &self.master);
        let held = self
            .pattern_candidates
            .iter()
            .zip(&self.reserved)
            .filter(|(_, &r)| r)
            .map(|(l, _)| l);
        let found = anticipated_candidates(mesh, u, surfaces, (PATTERN_MARGIN, reach), held);
        let integration = candidates_within(mesh, Some(u), surfaces.0, surfaces.1, 1.0, 0.0);
        let mut grew = false;
        for (ic, (found, near)) in found.iter().zip(&integration).enumerate() {
            if found.is_empty() {
                continue;
            }
            grew |= !self.reserved[ic];
            self.reserved[ic] = true;
            let pattern = &mut self.pattern_candidates[ic];
            grew |= add_new(pattern, found) | add_new(pattern, near);
        }
        // (and the current candidates of the cells reserved here)
        if !self.grow_pattern(None) && grew {
            self.pattern_generation += 1;
        }
    }

    fn changed_nodes(&self) -> Vec<usize> {
        self.changed.clone()
    }

    fn set_tangent_wanted(&self, wanted: bool) {
        self.tangent_wanted.store(wanted, Ordering::Relaxed);
    }

    fn open_at_rest(&mut self, mesh: &Mesh) -> bool {
        // (with adjust the rest state keeps its removed overlaps: not checked here)
        if self.adjust.is_some() {
            return false;
        }
        let u = vec![0.0; 2 * mesh.num_nodes()];
        let penetrating = self.mult_nodes.iter().any(|&n| {
            self.nodal_gaps(mesh, &u, n)
                .iter()
                .any(|&(gap, size)| gap < -1e-9 * size)
        });
        if penetrating {
            return false;
        }
        self.active.fill(false);
        self.law.fill(Branch::Free);
        true
    }

    fn status_signature(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        self.active.hash(&mut h);
        for l in &self.law {
            format!("{l:?}").hash(&mut h);
        }
        h.finish()
    }

    fn linearised_status(
        &mut self,
        _mesh: &Mesh,
        _u_lin: &[f64],
        u: &[f64],
        lam: &[f64],
    ) -> Option<usize> {
        self.statuses_linearised(u, lam)
    }

    fn commit(&mut self, u: &[f64], _lam: &[f64]) {
        // (the terms measure slips from the step start, which moves)
        self.terms_cache.lock().unwrap().take();
        self.switches.fill(0);
        if self.saved_candidates != self.candidates {
            self.saved_candidates = self.candidates.clone();
        }
        self.saved = self.active.clone();
        self.saved_law = self.law.clone();
        self.u_start.copy_from_slice(u);
    }

    fn restore(&mut self) {
        self.terms_cache.lock().unwrap().take();
        if self.candidates != self.saved_candidates {
            self.candidates = self.saved_candidates.clone();
        }
        self.active = self.saved.clone();
        self.law = self.saved_law.clone();
    }

    fn constraint_residual(&self, rl: &[f64], lam: &[f64]) -> f64 {
        // every row (weighted gap or slip, or multiplier × D_j / c) times c / D_j is a
        // pressure; relative to the largest normal multiplier
        let d = self.last_d.lock().unwrap();
        let nm = self.mult_nodes.len();
        if d.len() != nm {
            return 0.0;
        }
        let scale = lam[..nm]
            .iter()
            .fold(self.pressure_floor, |m, v| m.max(v.abs()));
        let w = row_weights(&d);
        let worst = rl
            .iter()
            .enumerate()
            .map(|(k, r)| (r * self.c / w[k % nm]).abs())
            .fold(0.0f64, f64::max);
        if scale > 0.0 {
            worst / scale
        } else {
            worst
        }
    }

    fn multiplier_nodes(&self) -> &[usize] {
        &self.mult_nodes
    }
    fn excluded_nodes(&self) -> &[usize] {
        &self.excluded_nodes
    }
    fn surfaces(&self) -> (&Surface, &Surface) {
        (&self.slave, &self.master)
    }

    fn nodal_pressures(&self, lam: &[f64]) -> Vec<(usize, f64)> {
        let mut p: Vec<f64> = lam[..self.mult_nodes.len()].to_vec();
        // A node of zero weight (∫ N_j dA = 0: the Seg3 corner on the axis in axisymmetry)
        // carries no multiplier: its pressure is its neighbours' limit.
        let d = self.last_d.lock().unwrap();
        let dmax = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let axis = crate::contact::axis::on_axis(&self.mult_coords, self.axisymmetric);
        let weightless: Vec<bool> = (0..p.len())
            .map(|k| axis[k] || d.get(k).is_some_and(|v| v.abs() <= 1e-12 * dmax))
            .collect();
        crate::contact::axis::fill_weightless(&self.mult_coords, &mut p, &weightless);
        self.mult_nodes.iter().copied().zip(p).collect()
    }

    fn nodal_shear(&self, lam: &[f64]) -> Vec<(usize, f64)> {
        let nm = self.mult_nodes.len();
        match self.friction {
            Some(_) => (0..nm).map(|k| (self.mult_nodes[k], lam[nm + k])).collect(),
            None => vec![],
        }
    }

    /// adjust keeps initial overlaps up to it.
    fn overlap_allowance(&self) -> f64 {
        self.adjust.unwrap_or(0.0)
    }
    /// No: a mortar re-solve redoes the contact terms and their tangent, a large part of an
    /// iteration, and on fine meshes the nodal active set cycles at a fixed
    /// linearisation (SSNP154 quadratic, 0.375 mm: 41 Newton iterations with re-solves,
    /// 10 without; reference meshes A–D: 10/12/13/14 → 7/8/9/9).
    fn active_set_resolves(&self) -> bool {
        false
    }
    fn friction(&self) -> f64 {
        self.friction.unwrap_or(0.0)
    }
    fn set_exact_tangent(&mut self, exact: bool) {
        self.exact_augmentation = exact;
    }
    fn reference_normals(&self) -> bool {
        self.small
    }
    fn supports_small_kinematics(&self) -> bool {
        true
    }
    fn set_small_kinematics(&mut self, small: bool) {
        if small != self.small {
            self.small = small;
            // (the friction trial's factors and switch counts of a linear stage are not
            // the large-kinematics problem's: it starts from those before the stage)
            if small {
                self.before_switch = (self.trial_scale.clone(), self.switches.clone());
            } else {
                (self.trial_scale, self.switches) = std::mem::take(&mut self.before_switch);
            }
            // (both hold terms of the other kinematics)
            *self.terms_cache.lock().unwrap() = None;
            *self.linearisation.lock().unwrap() = None;
        }
    }
}
