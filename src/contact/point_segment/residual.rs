//! The normal contact terms: residual and tangent of every point (augmented Lagrangian or
//! penalty), rows of weightless and friction-excluded multipliers, and the matrix pattern
//! over the candidates.

use super::super::smoothed_normal::smoothed_frame;
use super::{Eval, FrictionPoint, OwnedCoefs, PointToSegment};
use crate::assembly::coupled::Triplets;
use crate::mesh::Mesh;

/// B = [N_s n ; −N_m n] over (dof id, value): the gap's change with the displacements on
/// a point's frame (its projection and normal held).
pub(super) fn gap_row(e: &Eval, snodes: &[usize], mnodes: &[usize]) -> OwnedCoefs {
    let mut b = Vec::with_capacity(2 * (snodes.len() + mnodes.len()));
    for (a, &n) in snodes.iter().enumerate() {
        b.push((2 * n, e.ns[a] * e.normal[0]));
        b.push((2 * n + 1, e.ns[a] * e.normal[1]));
    }
    for (a, &n) in mnodes.iter().enumerate() {
        b.push((2 * n, -e.nm[a] * e.normal[0]));
        b.push((2 * n + 1, -e.nm[a] * e.normal[1]));
    }
    b
}

impl PointToSegment {
    /// Residual contributions (`ru` on full dofs, `rl` on multipliers, both added to) and
    /// tangent triplets over extended ids (multiplier k is `ndof + mult_base + k`).
    #[allow(clippy::too_many_arguments)] // state in, three accumulators out
    pub fn contribute(
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
        let rho = self.opts.rho;
        let lambda_floor = self.friction_floor(lam);
        for i in 0..self.points.len() {
            // (one group per point: see `Triplets::group`)
            k.group(i as u64);
            let p = &self.points[i];
            let e = self.eval(mesh, u, i);
            let lp = self.point_lambda(mesh, i, &e.ns, lam);
            let chi = p.active && !p.excluded;
            let sc = self.slave.cells[p.cell];
            let mc = self.master.cells[p.master];
            let snodes = mesh.cell_nodes(sc);
            let mnodes = mesh.cell_nodes(mc);
            let b = gap_row(&e, snodes, mnodes);
            // (an excluded node's multiplier stays zero by its own row)
            let mults: Vec<(usize, f64)> = snodes
                .iter()
                .enumerate()
                .filter(|(_, n)| {
                    self.opts.node_to_segment || !self.opts.contact_excluded.contains(n)
                })
                .map(|(a, n)| (self.mult_of[n], e.ns[a]))
                .collect();
            let w = p.omega;
            // Penalty (node-to-segment): the force is λ itself and the row d + λ/k = 0;
            // otherwise the augmented λ̂ = λ − ρ d with d = 0.
            let rho_u = if self.opts.penalty.is_some() {
                0.0
            } else {
                rho
            };
            let lhat = lp - rho_u * e.d;
            if chi {
                for &(dof, bv) in &b {
                    ru[dof] += -w * lhat * bv;
                }
                for &(m, nv) in &mults {
                    rl[m] += -w * e.d * nv;
                }
                if let Some(kp) = self.opts.penalty {
                    for &(m, nv) in &mults {
                        rl[m] += -w * lp / kp * nv;
                        for &(m2, n2) in &mults {
                            k.add(
                                ndof + mult_base + m,
                                ndof + mult_base + m2,
                                -w / kp * nv * n2,
                            );
                        }
                    }
                }
            } else {
                for &(m, nv) in &mults {
                    rl[m] += -w * lp / rho * nv;
                }
            }
            // Variations of the projection and of the master frame (normal part and friction):
            //   δξ̄ = [(δx_s − Σ N_m δu_m)·t + d n·Σ N_m' δu_m] / (|t|² − d n·t'')
            //   δn  = −τ (n·δt)/|t|,  δτ = n (n·δt)/|t|,  δt = Σ N_m' δu_m + t'' δξ̄
            // as coefficient lists over dofs: cxi for δξ̄, cn for (n·δt)/|t|.
            let mut geo: Option<(OwnedCoefs, OwnedCoefs)> = None;
            if (chi || self.opts.friction.is_some()) && !e.clamped {
                let tn2 = e.t[0] * e.t[0] + e.t[1] * e.t[1];
                let (sn, ds) = (e.seg_normal, e.d_seg);
                let den = tn2 - ds * (sn[0] * e.tt[0] + sn[1] * e.tt[1]);
                let lt = tn2.sqrt();
                let mut cxi: Vec<(usize, f64)> = vec![];
                for (a, &n) in snodes.iter().enumerate() {
                    cxi.push((2 * n, e.ns[a] * e.t[0] / den));
                    cxi.push((2 * n + 1, e.ns[a] * e.t[1] / den));
                }
                for (a, &n) in mnodes.iter().enumerate() {
                    for comp in 0..2 {
                        cxi.push((
                            2 * n + comp,
                            (-e.nm[a] * e.t[comp] + ds * e.dnm[a] * sn[comp]) / den,
                        ));
                    }
                }
                let ntt = sn[0] * e.tt[0] + sn[1] * e.tt[1];
                let mut cn: Vec<(usize, f64)> =
                    cxi.iter().map(|&(dof, v)| (dof, ntt * v / lt)).collect();
                for (a, &n) in mnodes.iter().enumerate() {
                    for comp in 0..2 {
                        cn.push((2 * n + comp, e.dnm[a] * sn[comp] / lt));
                    }
                }
                if e.smoothed {
                    let at = |n: usize| Self::current(mesh, u, n);
                    cn = smoothed_frame(
                        mesh,
                        &self.master,
                        &self.master_cells_of_node,
                        &at,
                        p.master,
                        e.xi_m,
                        Some(&cxi),
                    )
                    .2;
                }
                geo = Some((cxi, cn));
            }
            if let (true, Some((cxi, cn))) = (chi, &geo) {
                // −ω λ̂ ∂B/∂u: B moves with the master normal n and the projection ξ̄.
                let f = -w * lhat;
                for (a, &n) in snodes.iter().enumerate() {
                    for comp in 0..2 {
                        for &(col, v) in cn.iter() {
                            k.add(2 * n + comp, col, f * e.ns[a] * (-e.tau[comp]) * v);
                        }
                    }
                }
                for (a, &n) in mnodes.iter().enumerate() {
                    for comp in 0..2 {
                        for &(col, v) in cxi.iter() {
                            k.add(2 * n + comp, col, f * (-e.dnm[a] * e.normal[comp]) * v);
                        }
                        for &(col, v) in cn.iter() {
                            k.add(2 * n + comp, col, f * (-e.nm[a]) * (-e.tau[comp]) * v);
                        }
                    }
                }
            }
            if chi {
                for &(r, br) in &b {
                    for &(cc, bc) in &b {
                        k.add(r, cc, rho_u * w * br * bc);
                    }
                    for &(m, nv) in &mults {
                        k.add(r, ndof + mult_base + m, -w * br * nv);
                        k.add(ndof + mult_base + m, r, -w * br * nv);
                    }
                }
                // smoothed normal: δd = B·δu − (t·n) δξ̄ − ((x_s − x̄)·τ) ω (it is not normal
                // to the cell, and turns with the neighbouring cells)
                if let (Some((cxi, cn)), true) = (&geo, e.smoothed) {
                    let extra = cxi
                        .iter()
                        .map(|&(col, v)| (col, e.tn * v))
                        .chain(cn.iter().map(|&(col, v)| (col, e.tq * v)));
                    for (col, v) in extra {
                        for &(m, nv) in &mults {
                            k.add(ndof + mult_base + m, col, w * nv * v);
                        }
                        for &(r, br) in &b {
                            k.add(r, col, -rho_u * w * br * v);
                        }
                    }
                }
            } else {
                for &(m1, n1) in &mults {
                    for &(m2, n2) in &mults {
                        k.add(
                            ndof + mult_base + m1,
                            ndof + mult_base + m2,
                            -w / rho * n1 * n2,
                        );
                    }
                }
            }
            if let Some(mu) = self.opts.friction {
                let fp = FrictionPoint {
                    lambda_floor,
                    mu,
                    rho_f: self.balanced_rho_f[i] * self.trial_scale[i],
                    w,
                    lp,
                    chi,
                    e: &e,
                    snodes,
                    mnodes,
                    geo: geo.as_ref().map(|(a, b)| (a.as_slice(), b.as_slice())),
                };
                self.friction_point(&fp, u, lam, ru, rl, k, ndof + mult_base);
            }
        }
        // weightless multipliers (no point weighs them): λ = 0 by a row on the scale of the
        // inactive ones (−ω λ / ρ)
        k.ungrouped();
        let wmax = self.points.iter().fold(0.0f64, |m, p| m.max(p.omega));
        for (m, _) in self.weightless.iter().enumerate().filter(|w| *w.1) {
            if !self.opts.node_to_segment {
                let s = wmax / rho;
                rl[m] += -s * lam[m];
                k.add(ndof + mult_base + m, ndof + mult_base + m, -s);
            }
        }
        if self.opts.friction.is_some() {
            // excluded nodes: Λ = 0 by a unit row
            let nm = self.mult_nodes.len();
            for &n in &self.opts.friction_excluded {
                if let Some(&m) = self.mult_of.get(&n) {
                    rl[nm + m] += lam[nm + m];
                    k.add(ndof + mult_base + nm + m, ndof + mult_base + nm + m, 1.0);
                }
            }
            for m in 0..nm {
                let excluded = self.opts.friction_excluded.contains(&self.mult_nodes[m]);
                if self.weightless[m] && !self.opts.node_to_segment && !excluded {
                    rl[nm + m] += lam[nm + m];
                    k.add(ndof + mult_base + nm + m, ndof + mult_base + nm + m, 1.0);
                }
            }
        }
        // The pattern: explicit zeros over every coupling a slave cell may have, so that
        // status and pairing changes within the candidates keep the pattern (and the
        // symbolic factorisation) unchanged. The matrix keeps a pattern once built, so the
        // zeros are sent only while the candidates have changed since they were last sent.
        if self.pattern_sent.get() == Some(self.candidates_generation) {
            return;
        }
        self.pattern_sent.set(Some(self.candidates_generation));
        // A point reads its slave cell and one master cell with the cells next to it (the
        // smoothed normal's vertex normals): the pattern couples the slave cell's dofs and
        // multipliers with each candidate's stencil, and each stencil with itself, not every
        // candidate with every other (a long slave cell far from the contact zone has
        // hundreds of small master cells within reach: their clique made the pattern, and
        // its memory, grow as the square of the refinement).
        let nm = self.mult_nodes.len();
        let mut cliques = vec![];
        for (ic, &sc) in self.slave.cells.iter().enumerate() {
            // a slave cell with no master cell within reach has no coupling (yet)
            let mut own: Vec<usize> = vec![];
            if !self.candidates[ic].is_empty() {
                for &n in mesh.cell_nodes(sc) {
                    own.extend([2 * n, 2 * n + 1]);
                }
            }
            let mults: Vec<usize> = mesh
                .cell_nodes(sc)
                .iter()
                .map(|n| ndof + mult_base + self.mult_of[n])
                .collect();
            if self.opts.friction.is_some() {
                let friction: Vec<usize> = mults.iter().map(|m| m + nm).collect();
                own.extend(friction);
            }
            own.extend(mults);
            if self.candidates[ic].is_empty() {
                cliques.push(own.clone());
            }
            for &im in &self.candidates[ic] {
                let mut stencil = own.clone();
                for &n in mesh.cell_nodes(self.master.cells[im]) {
                    for &jm in self.master_cells_of_node.get(&n).into_iter().flatten() {
                        for &m in mesh.cell_nodes(self.master.cells[jm]) {
                            stencil.extend([2 * m, 2 * m + 1]);
                        }
                    }
                }
                stencil.sort_unstable();
                stencil.dedup();
                cliques.push(stencil);
            }
        }
        k.add_clique_union(&cliques);
    }
}
