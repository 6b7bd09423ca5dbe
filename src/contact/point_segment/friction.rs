//! Coulomb friction at one contact point: the semi-multiplier form (stick or slip rows),
//! the tangential penalty form, and their geometric terms (τ turns, ξ̄ slides); each
//! point's branch at the status updates, whose slip-direction reversals cut its ρ_f.

use super::super::friction;
use super::{Eval, FrictionPoint, PointToSegment};
use crate::assembly::coupled::Triplets;
use crate::mesh::Mesh;

impl PointToSegment {
    /// The friction terms' dependence on the geometry: the slip Δw = τ·(Σ N_s Δu_s −
    /// Σ N_m(ξ̄) Δu_m) and the direction T = (N_s τ, −N_m τ) of the tangential force both
    /// turn with τ and slide with ξ̄ (Δu: displacement since the step start).
    #[allow(clippy::too_many_arguments)]
    fn friction_geometry(
        &self,
        fp: &FrictionPoint,
        u: &[f64],
        tv: &[(usize, f64)],
        cxi: &[(usize, f64)],
        cn: &[(usize, f64)],
        q: f64,
        stick: Option<(f64, f64)>,
        k: &mut Triplets,
        fm: &[(usize, f64)],
        mbase: usize,
    ) {
        let e = fp.e;
        let w = fp.w;
        let du = |n: usize, c: usize| u[2 * n + c] - self.u_start[2 * n + c];
        let mut big_du = [0.0; 2];
        for c in 0..2 {
            for (a, &n) in fp.snodes.iter().enumerate() {
                big_du[c] += e.ns[a] * du(n, c);
            }
            for (b, &n) in fp.mnodes.iter().enumerate() {
                big_du[c] -= e.nm[b] * du(n, c);
            }
        }
        let n_du = e.normal[0] * big_du[0] + e.normal[1] * big_du[1];
        let tdu_m: f64 = fp
            .mnodes
            .iter()
            .enumerate()
            .map(|(b, &n)| e.dnm[b] * (e.tau[0] * du(n, 0) + e.tau[1] * du(n, 1)))
            .sum();
        // geometric part of δΔw
        let g_dw: Vec<(usize, f64)> = cn
            .iter()
            .map(|&(col, v)| (col, n_du * v))
            .chain(cxi.iter().map(|&(col, v)| (col, -tdu_m * v)))
            .collect();
        // sticking: the force on the dofs T and the stick rows depend on Δw, with these
        // coefficients
        if let Some((force, row)) = stick {
            for &(d, v) in tv.iter().filter(|_| force != 0.0) {
                for &(col, gv) in &g_dw {
                    k.add(d, col, force * v * gv);
                }
            }
            for &(m, nv) in fm {
                for &(col, gv) in &g_dw {
                    k.add(mbase + m, col, row * nv * gv);
                }
            }
        }
        // −ω q δT: slave rows N_s n_c (n·δt)/|t|; master rows −N_m' τ_c δξ̄ − N_m n_c (n·δt)/|t|
        for (a, &n) in fp.snodes.iter().enumerate() {
            for c in 0..2 {
                for &(col, v) in cn {
                    k.add(2 * n + c, col, -w * q * e.ns[a] * e.normal[c] * v);
                }
            }
        }
        for (b, &n) in fp.mnodes.iter().enumerate() {
            for c in 0..2 {
                for &(col, v) in cxi {
                    k.add(2 * n + c, col, w * q * e.dnm[b] * e.tau[c] * v);
                }
                for &(col, v) in cn {
                    k.add(2 * n + c, col, w * q * e.nm[b] * e.normal[c] * v);
                }
            }
        }
    }

    /// The largest contact pressure over the slave nodes (λ over what turns it into one).
    pub(super) fn peak_pressure(&self, lam: &[f64]) -> f64 {
        let nm = self.mult_nodes.len();
        (lam[..nm]
            .iter()
            .zip(&self.node_weight)
            .zip(&self.weightless))
        .filter(|(_, &weightless)| !weightless)
        .fold(0.0f64, |m, ((l, w), _)| m.max(-l / w))
    }

    /// |λ| below which a point carries no friction: 1e-8 of the largest normal multiplier.
    pub(super) fn friction_floor(&self, lam: &[f64]) -> f64 {
        let nm = self.mult_nodes.len();
        1e-8 * lam[..nm].iter().fold(0.0f64, |m, v| m.max(v.abs()))
    }

    /// The slip Δw since the step start along the master tangent, Tᵀ (u − u_start) with T =
    /// (N_s τ, −N_m τ), and the semi-multiplier Λ = Σ N_s Λ_s at a point of geometry `e`.
    pub(super) fn slip_and_semi_multiplier(
        &self,
        e: &Eval,
        snodes: &[usize],
        mnodes: &[usize],
        u: &[f64],
        lam: &[f64],
    ) -> (f64, f64) {
        let du = |n: usize, c: usize| u[2 * n + c] - self.u_start[2 * n + c];
        let mut dw = 0.0;
        for (a, &n) in snodes.iter().enumerate() {
            for c in 0..2 {
                dw += e.ns[a] * e.tau[c] * du(n, c);
            }
        }
        for (b, &n) in mnodes.iter().enumerate() {
            for c in 0..2 {
                dw -= e.nm[b] * e.tau[c] * du(n, c);
            }
        }
        let nm = self.mult_nodes.len();
        let big_l = snodes
            .iter()
            .enumerate()
            .map(|(a, n)| e.ns[a] * lam[nm + self.mult_of[n]])
            .sum();
        (dw, big_l)
    }

    /// Point i's Coulomb branch at (u, λ) as `friction_point` takes it (None: no friction
    /// there), given its geometry, its λ, the floor below which |λ| carries none and the
    /// pair's peak pressure, with its ρ_f balanced on its pressure there (kept until the
    /// next update, so that the residual and its tangent see one ρ_f); a point whose slip
    /// keeps reversing its direction in this step gets a smaller ρ_f
    /// (`friction::count_reversal`).
    pub(super) fn count_friction_switch(
        &mut self,
        mesh: &Mesh,
        u: &[f64],
        lam: &[f64],
        i: usize,
        (e, lp, lambda_floor, peak): (&Eval, f64, f64, f64),
    ) {
        let p = &self.points[i];
        let mut dw = 0.0;
        let law = if !p.active || p.excluded || lp >= -lambda_floor {
            None
        } else {
            let snodes = mesh.cell_nodes(self.slave.cells[p.cell]);
            let mnodes = mesh.cell_nodes(self.master.cells[p.master]);
            let big_l;
            (dw, big_l) = self.slip_and_semi_multiplier(e, snodes, mnodes, u, lam);
            // (λ is a pressure, or for node-to-segment the node's force: over its share)
            let share: f64 = (e.ns.iter().zip(snodes))
                .map(|(v, n)| v * self.node_weight[self.mult_of[n]])
                .sum();
            let (mu, stiffness) = (self.opts.friction.unwrap_or(0.0), self.opts.trial_stiffness);
            self.balanced_rho_f[i] =
                friction::balanced_rho_f(self.opts.rho_f, stiffness, mu, -lp / share, peak);
            let rho_f = self.balanced_rho_f[i] * self.trial_scale[i];
            Some(friction::state(big_l, dw, rho_f).1)
        };
        if let (Some(friction::State::Slip(a)), Some(friction::State::Slip(b))) = (self.law[i], law)
        {
            if a != b {
                let (switches, scale) = (&mut self.switches[i], &mut self.trial_scale[i]);
                friction::count_reversal(switches, scale, self.balanced_rho_f[i], dw);
            }
        }
        if law != self.law[i] {
            self.branch_switches += 1;
        }
        self.law[i] = law;
    }

    /// Coulomb friction at one contact point (contact.md §1.8): with the semi-multiplier
    /// Λ (|Λ| ≤ 1) and the slip Δw since the start of the step along the master tangent,
    /// t = Λ + ρ_f Δw; stick if |t| ≤ 1 (then Δw = 0 weakly), slip otherwise (Λ = ±1);
    /// the tangential traction is μ|λ||Λ|. No contact (or λ = 0): Λ = 0.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn friction_point(
        &self,
        fp: &FrictionPoint,
        u: &[f64],
        lam: &[f64],
        ru: &mut [f64],
        rl: &mut [f64],
        k: &mut Triplets,
        mbase: usize,
    ) {
        let nm = self.mult_nodes.len();
        let e = fp.e;
        let (w, mu, lp, rho_f) = (fp.w, fp.mu, fp.lp, fp.rho_f);
        // T over dofs: slave N_s τ, master −N_m τ; Δw = Tᵀ (u − u_start)
        let mut tv: Vec<(usize, f64)> = vec![];
        for (a, &n) in fp.snodes.iter().enumerate() {
            for c in 0..2 {
                tv.push((2 * n + c, e.ns[a] * e.tau[c]));
            }
        }
        for (b, &n) in fp.mnodes.iter().enumerate() {
            for c in 0..2 {
                tv.push((2 * n + c, -e.nm[b] * e.tau[c]));
            }
        }
        let (dw, big_l) = self.slip_and_semi_multiplier(e, fp.snodes, fp.mnodes, u, lam);
        let excluded = |n: usize| self.opts.friction_excluded.contains(&n);
        // friction multipliers (index, N_s) of this cell; excluded nodes keep their unit row
        let fm: Vec<(usize, f64)> = fp
            .snodes
            .iter()
            .enumerate()
            .filter(|(_, n)| !excluded(**n))
            .map(|(a, n)| (nm + self.mult_of[n], e.ns[a]))
            .collect();
        let nmults: Vec<(usize, f64)> = fp
            .snodes
            .iter()
            .enumerate()
            .map(|(a, n)| (self.mult_of[n], e.ns[a]))
            .collect();
        if let (true, Some(k_t)) = (fp.chi, self.opts.tangential_penalty) {
            let pen = Penalty {
                k_t,
                tv: &tv,
                fm: &fm,
                nmults: &nmults,
                q: big_l,
                dw,
            };
            self.penalty_friction(fp, &pen, u, ru, rl, k, mbase);
            return;
        }
        // Friction needs a pressure: a point with (numerically) no normal multiplier gets the
        // "no contact" row, as an exactly zero λ does in the reference, so that the slip row
        // μ λ (Λ − sign t) / ρ_f never degenerates.
        if !fp.chi || lp >= -fp.lambda_floor {
            for &(m, nv) in &fm {
                rl[m] += w * big_l * nv;
                for &(m2, n2) in &fm {
                    k.add(mbase + m, mbase + m2, w * nv * n2);
                }
            }
            return;
        }
        let (t, law) = friction::state(big_l, dw, rho_f);
        if let Some((cxi, cn)) = fp.geo {
            // q = μ λ t (stick: μ λ (Λ + ρ_f Δw)) or μ λ sign(t) (slip)
            let q = friction::traction(mu, lp, t, law);
            let stick =
                (law == friction::State::Stick).then_some((-w * mu * lp * rho_f, -w * mu * lp));
            self.friction_geometry(fp, u, &tv, cxi, cn, q, stick, k, &fm, mbase);
        }
        if law == friction::State::Stick {
            let q = friction::traction(mu, lp, t, law); // μ λ t
            for &(d, v) in &tv {
                ru[d] += -w * q * v;
                for &(d2, v2) in &tv {
                    k.add(d, d2, -w * mu * lp * rho_f * v * v2);
                }
                for &(m, nv) in &fm {
                    k.add(d, mbase + m, -w * mu * lp * v * nv);
                    k.add(mbase + m, d, -w * mu * lp * nv * v);
                }
                for &(m, nv) in &nmults {
                    k.add(d, mbase + m, -w * mu * t * v * nv);
                }
            }
            for &(m, nv) in &fm {
                rl[m] += -w * mu * lp * dw * nv;
                for &(m2, n2) in &nmults {
                    k.add(mbase + m, mbase + m2, -w * mu * dw * nv * n2);
                }
            }
        } else {
            let sg = t.signum();
            let q = friction::traction(mu, lp, t, law); // μ λ sign(t)
            for &(d, v) in &tv {
                ru[d] += -w * q * v;
                for &(m, nv) in &nmults {
                    k.add(d, mbase + m, -w * mu * sg * v * nv);
                }
            }
            for &(m, nv) in &fm {
                rl[m] += w * mu * lp * (big_l - sg) / rho_f * nv;
                for &(m2, n2) in &fm {
                    k.add(mbase + m, mbase + m2, w * mu * lp / rho_f * nv * n2);
                }
                for &(m2, n2) in &nmults {
                    k.add(
                        mbase + m,
                        mbase + m2,
                        w * mu * (big_l - sg) / rho_f * nv * n2,
                    );
                }
            }
        }
    }
}

/// What a tangential-penalty point needs besides the normal terms.
struct Penalty<'a> {
    k_t: f64,
    /// T over dofs (slave N_s τ, master −N_m τ), the friction multipliers and the normal
    /// ones of the cell with their N_s
    tv: &'a [(usize, f64)],
    fm: &'a [(usize, f64)],
    nmults: &'a [(usize, f64)],
    /// the tangential force at the point (its multiplier) and the slip since the step start
    q: f64,
    dw: f64,
}

impl PointToSegment {
    /// Coulomb friction with a tangential penalty k_t at an active point: the tangential
    /// multiplier Q is the force on the slave along τ (not a semi-multiplier: at λ = 0 a
    /// multiplier scaled by μλ would be undetermined, and a body held by friction alone
    /// would start singular). With the trial force q_tr = q_start − k_t Δw and the cone
    /// μ max(−λ, 0): stick if |q_tr| ≤ the cone (row Q = q_tr), otherwise slip (row
    /// Q = cone · sign q_tr). The force −Q T goes to the dofs.
    #[allow(clippy::too_many_arguments)]
    fn penalty_friction(
        &self,
        fp: &FrictionPoint,
        pen: &Penalty,
        u: &[f64],
        ru: &mut [f64],
        rl: &mut [f64],
        k: &mut Triplets,
        mbase: usize,
    ) {
        let (e, w, mu, lp) = (fp.e, fp.w, fp.mu, fp.lp);
        let q_start: f64 = fp
            .snodes
            .iter()
            .enumerate()
            .map(|(a, n)| e.ns[a] * self.q_start[self.mult_of[n]])
            .sum();
        let trial = q_start - pen.k_t * pen.dw;
        let cone = mu * (-lp).max(0.0);
        let stick = trial.abs() <= cone;
        if let Some((cxi, cn)) = fp.geo {
            let rows = stick.then_some((0.0, w * pen.k_t));
            self.friction_geometry(fp, u, pen.tv, cxi, cn, pen.q, rows, k, pen.fm, mbase);
        }
        for &(d, v) in pen.tv {
            ru[d] += -w * pen.q * v;
            for &(m, nv) in pen.fm {
                k.add(d, mbase + m, -w * v * nv);
            }
        }
        let sg = trial.signum();
        let target = if stick { trial } else { cone * sg };
        for &(m, nv) in pen.fm {
            rl[m] += w * (pen.q - target) * nv;
            for &(m2, n2) in pen.fm {
                k.add(mbase + m, mbase + m2, w * nv * n2);
            }
            if stick {
                for &(d, v) in pen.tv {
                    k.add(mbase + m, d, w * pen.k_t * nv * v);
                }
            } else if lp < 0.0 {
                for &(m2, n2) in pen.nmults {
                    k.add(mbase + m, mbase + m2, w * mu * sg * nv * n2);
                }
            }
        }
    }
}
