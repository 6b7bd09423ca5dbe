//! The interface matrix reduced onto its live unknowns. Most displacement unknowns of the
//! interface carry no contact term at a given point (SSNP154 D point-to-segment at 93k
//! unknowns: 1782 of them, of which 500–700 touch a contact point's multiplier): their
//! rows and columns of T hold the bodies' Schur complements and solid entries only, which
//! stay as they are while the bodies' factorisations are kept (frozen-body corrections,
//! active-set re-solves). With P those passive unknowns and L the others (multipliers,
//! displacements that share an entry with one, and their neighbours),
//!   T = [T_PP T_PL; T_LP T_LL],  X = T_PP⁻¹ T_PL,  R = T_LL − T_LP X,
//!   T x = b:  y = T_PP⁻¹ b_P,  x_L = R⁻¹ (b_L − T_LP y),  x_P = y − X x_L,
//! exact, as the LU of T. A reduction costs at least what that LU costs; a later matrix
//! that differs from it in L × L only is R plus that difference, whose LU is of order |L|
//! (`pays` decides where the one pays for the other).

use super::dense_lu::{factor_par as par, DenseLu};
use super::live_lu::LiveLu;
use super::passive::{reduce_by_blocks, PassiveBlocks};
use super::{InterfaceSolver, NONE};
use crate::assembly::matrix::SparseMatrix;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};

/// Passive unknowns below which the interface is factorised whole (the reduction's extra
/// passes do not pay on small interfaces, whose LU costs milliseconds).
const MIN_PASSIVE: usize = if cfg!(test) { 4 } else { 256 };

/// Whether reducing pays, in flops: with `whole` coupled unknowns factorised whole, or
/// `passive` and `live` ones reduced (the live LU of the `live_coupled` among them: the
/// others, decoupled, are solved by their diagonal), and `coming` LUs with the bodies kept
/// to follow (each a whole LU, or one of the live part). The flops predict the times
/// (SSNP154 D mortar at 266k: a reduction of 1694 + 1990 unknowns took 0.50 s, an LU of
/// 3096 0.30 s), but a reduction also holds more memory, and a live LU may not serve (a
/// point closing beyond the live unknowns): it is made when it saves a quarter of the flops
/// at least.
pub(super) fn pays(
    whole: usize,
    passive: usize,
    live: usize,
    live_coupled: usize,
    coming: usize,
) -> bool {
    let (k, p, l, lc) = (
        whole as f64,
        passive as f64,
        live as f64,
        live_coupled as f64,
    );
    let lu = |n: f64| 2.0 / 3.0 * n * n * n;
    let reduction = lu(p) + lu(lc) + 2.0 * p * p * l + 2.0 * l * l * p;
    reduction + coming as f64 * lu(lc) < 0.75 * (1 + coming) as f64 * lu(k)
}

#[cfg(test)]
mod tests {
    use super::{pays, Blocks};
    use faer::Mat;

    /// T x − b for the reduction of T (unknowns 4 and 5 live) with `diagonal` on T_PP's
    /// diagonal, T symmetric but for T_LL and `skew` added to T_PP[0, 1]; and whether T_PP
    /// went to Cholesky. None when the reduction declines (the whole LU then).
    fn reduced_residual(diagonal: [f64; 4], skew: f64) -> Option<(f64, bool)> {
        let n = 6;
        let t = Mat::from_fn(n, n, |i, j| {
            if i == j {
                if i < 4 {
                    diagonal[i]
                } else {
                    5.0 + i as f64
                }
            } else if i >= 4 && j >= 4 {
                if i > j {
                    0.7
                } else {
                    -0.4
                }
            } else {
                0.3 / (1.0 + (i + j) as f64) + if (i, j) == (0, 1) { skew } else { 0.0 }
            }
        });
        let mut blocks = Blocks::new(&[false, false, false, false, true, true]);
        for j in 0..n {
            for i in 0..n {
                blocks.add(i, j, t[(i, j)]);
            }
        }
        let red = blocks.finish(vec![])?;
        let b = Mat::from_fn(n, 1, |i, _| (1.3 * i as f64).sin() + 0.2);
        let mut x = b.clone();
        red.solve(&mut x);
        let r = &t * &x - &b;
        let res = (0..n).fold(0.0f64, |m, i| m.max(r[(i, 0)].abs()));
        Some((res, red.passive_cholesky()))
    }

    #[test]
    fn a_symmetric_passive_part_is_reduced_by_cholesky_an_unsymmetric_one_by_lu() {
        let (res, cholesky) = reduced_residual([2.0, 3.0, 1.5, 4.0], 0.0).unwrap();
        assert!(cholesky, "positive definite");
        assert!(res < 1e-14, "max residual {res}");
        let (res, cholesky) = reduced_residual([2.0, 3.0, 1.5, 4.0], 0.2).unwrap();
        assert!(!cholesky, "not symmetric: LU");
        assert!(res < 1e-14, "max residual {res}");
        assert!(
            reduced_residual([2.0, -3.0, 1.5, 4.0], 0.0).is_none(),
            "symmetric, indefinite: declined"
        );
    }

    /// Two bodies: passive unknowns 0–2 (body one) and 3–5 (body two), live 6–7 (body
    /// one's), 8 (body two's) and 9 (a multiplier between them); T_PP is block diagonal and
    /// each block couples to its body's live unknowns alone. The reduction factorises the
    /// two blocks apart and solves T exactly.
    #[test]
    fn a_block_diagonal_passive_part_is_factorised_block_by_block() {
        let n = 10;
        let body = |i: usize| match i {
            0..=2 | 6 | 7 => Some(0),
            3..=5 | 8 => Some(1),
            _ => None,
        };
        let t = Mat::from_fn(n, n, |i, j| {
            if i == j {
                return if i == 9 { 0.0 } else { 4.0 + 0.1 * i as f64 };
            }
            match (body(i), body(j)) {
                (Some(a), Some(b)) if a == b => -0.5 / (1.0 + (i + j) as f64),
                // (the multiplier's terms: with live unknowns only, not symmetric)
                (None, Some(_)) if j >= 6 => 0.2 * j as f64 - 0.3,
                (Some(_), None) if i >= 6 => 0.25 * i as f64 - 0.1,
                _ => 0.0,
            }
        });
        let is_live: Vec<bool> = (0..n).map(|i| i >= 6).collect();
        let mut blocks = Blocks::new(&is_live);
        for j in 0..n {
            for i in 0..n {
                blocks.add(i, j, t[(i, j)]);
            }
        }
        let red = blocks.finish(vec![]).expect("positive definite blocks");
        assert!(red.passive_cholesky());
        assert_eq!(red.passive_blocks(), 2, "one block per body");
        for c in [1, 3] {
            let b = Mat::from_fn(n, c, |i, k| (1.3 * i as f64 + k as f64).sin() + 0.2);
            let mut x = b.clone();
            red.solve(&mut x);
            let r = &t * &x - &b;
            let res = (0..n)
                .flat_map(|i| (0..c).map(move |k| (i, k)))
                .fold(0.0f64, |m, (i, k)| m.max(r[(i, k)].abs()));
            assert!(res < 1e-14, "{c} right-hand sides: max residual {res}");
        }
    }

    #[test]
    fn a_reduction_pays_where_live_lus_follow_and_the_live_part_is_small() {
        // (the interfaces of SSNP154 D at 93k with point-to-segment and 266k with mortar)
        assert!(pays(1985, 1300, 1000, 1000, 3));
        assert!(!pays(1985, 1300, 1000, 1000, 0), "no live LU to come");
        assert!(
            !pays(3096, 1694, 1990, 1990, 1),
            "one live LU of a large live part"
        );
        // the live part's decoupled unknowns cost its LU nothing (D mortar at 93k: 274 of
        // its 1554 live unknowns, the multipliers of open points next to the zone)
        assert!(pays(2186, 906, 1554, 1280, 1));
        assert!(!pays(2186, 906, 1554, 1554, 1));
        // with nothing to come, a reduction costs a whole LU's flops at least
        for (p, l) in [(10, 10), (500, 100), (100, 500)] {
            assert!(!pays(p + l, p, l, l, 0));
        }
    }
}

/// Where a coupled interface unknown sits in the reduction.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Place {
    Passive(usize),
    Live(usize),
}

pub(super) struct Reduction {
    /// positions among the coupled unknowns (`Factorised::kept`) of P and of L
    passive: Vec<usize>,
    live: Vec<usize>,
    /// T_PP factorised (with what the solves need of T_PL and T_LP), and R = T_LL − T_LP
    /// T_PP⁻¹ T_PL at the values reduced.
    passive_factor: PassiveFactor,
    r: Mat<f64>,
    /// the LU of the live matrix: R plus the change of T_LL since the reduction
    ll: LiveLu,
    /// each coupled unknown's place (by position among the coupled ones)
    place: Vec<Place>,
    /// A's interface entries' values at the reduction, in the order of the interface
    /// entries (emptied when they are relabelled: a rebind)
    pub(super) values: Vec<f64>,
    /// the decoupled unknowns' diagonal at the reduction (by interface position)
    diagonal: Vec<f64>,
}

/// T_PP's factorisation. Where T is symmetric between the passive unknowns and the rest
/// (they carry the bodies' terms alone: the usual case), T_PP is the bodies' Schur
/// complements on them, block diagonal and positive definite: Cholesky factors and
/// W = L⁻¹ T_PL block by block (`passive.rs`), R = T_LL − Wᵀ W, a fraction of the LU's
/// flops (SSNP154 D point-to-segment near 1M unknowns: reductions of 2.1–3.2 s by LU,
/// p ≈ 4000, l ≈ 3000, 1.2–1.9 s by Cholesky of T_PP whole). Otherwise (T not symmetric
/// there) its LU, X = T_PP⁻¹ T_PL and T_LP.
enum PassiveFactor {
    Cholesky(PassiveBlocks),
    Lu {
        pp: Box<DenseLu>,
        x: Mat<f64>,
        lp: Mat<f64>,
    },
}

/// The four blocks of T, filled by `add` and reduced by `finish`.
pub(super) struct Blocks {
    passive: Vec<usize>,
    live: Vec<usize>,
    /// each coupled unknown's place (by position among the coupled ones)
    place: Vec<Place>,
    pp: Mat<f64>,
    pl: Mat<f64>,
    lp: Mat<f64>,
    ll: Mat<f64>,
}

impl Blocks {
    /// Zero blocks for the coupled unknowns split by `is_live` (by position among them).
    pub(super) fn new(is_live: &[bool]) -> Self {
        let mut place = Vec::with_capacity(is_live.len());
        let (mut passive, mut live) = (vec![], vec![]);
        for (i, &l) in is_live.iter().enumerate() {
            if l {
                place.push(Place::Live(live.len()));
                live.push(i);
            } else {
                place.push(Place::Passive(passive.len()));
                passive.push(i);
            }
        }
        let (p, l) = (passive.len(), live.len());
        Blocks {
            passive,
            live,
            place,
            pp: Mat::zeros(p, p),
            pl: Mat::zeros(p, l),
            lp: Mat::zeros(l, p),
            ll: Mat::zeros(l, l),
        }
    }

    /// T[i, j] += v (i, j by position among the coupled unknowns).
    #[inline]
    pub(super) fn add(&mut self, i: usize, j: usize, v: f64) {
        match (self.place[i], self.place[j]) {
            (Place::Passive(a), Place::Passive(b)) => self.pp[(a, b)] += v,
            (Place::Passive(a), Place::Live(b)) => self.pl[(a, b)] += v,
            (Place::Live(a), Place::Passive(b)) => self.lp[(a, b)] += v,
            (Place::Live(a), Place::Live(b)) => self.ll[(a, b)] += v,
        }
    }

    /// The reduction (and the LU of R) of the blocks filled, for A's interface values
    /// `values`; None where T_PP is symmetric but not positive definite (not the bodies'
    /// Schur complement: rare, then the interface matrix is factorised whole).
    pub(super) fn finish(self, values: Vec<f64>) -> Option<Reduction> {
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
        let (p, l) = (self.passive.len(), self.live.len());
        let symmetric = (0..p).all(|j| (j + 1..p).all(|i| same(self.pp[(i, j)], self.pp[(j, i)])))
            && (0..p).all(|j| (0..l).all(|i| same(self.lp[(i, j)], self.pl[(j, i)])));
        let (passive_factor, r) = if symmetric {
            // (dropped before W and R are made: the reduction's peak)
            drop(self.lp);
            let (blocks, r) = reduce_by_blocks(self.pp, self.pl, self.ll)?;
            (PassiveFactor::Cholesky(blocks), r)
        } else {
            reduce_by_lu(self.pp, self.pl, self.lp, self.ll)
        };
        let mut reduction = Reduction {
            passive: self.passive,
            live: self.live,
            passive_factor,
            r,
            ll: LiveLu::default(),
            place: self.place,
            values,
            diagonal: vec![],
        };
        reduction.refactor_live(&[]);
        Some(reduction)
    }
}

/// T_PP's LU, X = T_PP⁻¹ T_PL, R = T_LL − T_LP X (T not symmetric: T_LP kept).
fn reduce_by_lu(
    pp: Mat<f64>,
    pl: Mat<f64>,
    lp: Mat<f64>,
    ll: Mat<f64>,
) -> (PassiveFactor, Mat<f64>) {
    let (p, n) = (pl.nrows(), pl.ncols());
    let mut lu = DenseLu::default();
    lu.factor(pp);
    let mut x = pl;
    // (X's columns on both cores, whatever p: this solve costs 2p²l, the most of any)
    lu.solve_with(&mut x, par(p + n));
    let mut r = ll;
    matmul(
        r.as_mut(),
        Accum::Add,
        lp.as_ref(),
        x.as_ref(),
        -1.0,
        par(n),
    );
    (
        PassiveFactor::Lu {
            pp: Box::new(lu),
            x,
            lp,
        },
        r,
    )
}

impl Reduction {
    pub(super) fn num_live(&self) -> usize {
        self.live.len()
    }

    /// Whether T_PP is factorised by Cholesky (else by LU, T_LP kept: T not symmetric
    /// between the passive unknowns and the rest).
    #[cfg(test)]
    pub(super) fn passive_cholesky(&self) -> bool {
        matches!(self.passive_factor, PassiveFactor::Cholesky(_))
    }

    /// The number of blocks of a passive part factorised by Cholesky.
    #[cfg(test)]
    pub(super) fn passive_blocks(&self) -> usize {
        match &self.passive_factor {
            PassiveFactor::Cholesky(b) => b.len(),
            PassiveFactor::Lu { .. } => 0,
        }
    }

    /// Where the coupled unknown at position i sits.
    pub(super) fn place(&self, i: usize) -> Place {
        self.place[i]
    }

    /// Factorises R + `change` (live rows and columns) as the live matrix.
    pub(super) fn refactor_live(&mut self, change: &[(usize, usize, f64)]) {
        let l = self.r.nrows();
        let mut m = self.ll.take_storage(l);
        m.copy_from(&self.r);
        for &(i, j, v) in change {
            m[(i, j)] += v;
        }
        self.ll.factor(m);
    }

    /// Solves T x = b in place for the columns of `m` (rows: the coupled unknowns).
    pub(super) fn solve(&self, m: &mut Mat<f64>) {
        let c = m.ncols();
        let mut bp = Mat::from_fn(self.passive.len(), c, |i, j| m[(self.passive[i], j)]);
        let mut bl = Mat::from_fn(self.live.len(), c, |i, j| m[(self.live[i], j)]);
        match &self.passive_factor {
            // z = L⁻¹ b_P, b_L − Wᵀ z, x_L = R⁻¹ (…), x_P = L⁻ᵀ (z − W x_L)
            PassiveFactor::Cholesky(blocks) => {
                blocks.forward(&mut bp, &mut bl);
                self.ll.solve(&mut bl);
                blocks.backward(&mut bp, &bl);
            }
            PassiveFactor::Lu { pp, x, lp } => {
                // b_L − T_LP T_PP⁻¹ b_P
                pp.solve_many(&mut bp);
                matmul(bl.as_mut(), Accum::Add, lp, bp.as_ref(), -1.0, Par::Seq);
                self.ll.solve(&mut bl);
                matmul(
                    bp.as_mut(),
                    Accum::Add,
                    x.as_ref(),
                    bl.as_ref(),
                    -1.0,
                    Par::Seq,
                );
            }
        }
        for j in 0..c {
            for (i, &k) in self.passive.iter().enumerate() {
                m[(k, j)] = bp[(i, j)];
            }
            for (i, &k) in self.live.iter().enumerate() {
                m[(k, j)] = bl[(i, j)];
            }
        }
    }
}

impl InterfaceSolver {
    /// Factorises the interface matrix of `a` (coupled unknowns at `at`, decoupled ones by
    /// their `diagonal`; A's interface `values`) reduced onto its `live` unknowns.
    pub(super) fn reduce(
        &mut self,
        a: &SparseMatrix,
        at: Vec<usize>,
        diagonal: Vec<f64>,
        values: Vec<f64>,
        live: &[bool],
    ) {
        let k = self.gamma.len();
        // (the full LU's storage is not needed while reduced, nor the last reduction
        // once this one is made)
        self.base.lu = DenseLu::default();
        self.base.reduction = None;
        let is_live: Vec<bool> = self.base.kept.iter().map(|&i| live[i]).collect();
        let mut blocks = Blocks::new(&is_live);
        self.visit_interface(a, |i, j, v| {
            if at[i] != NONE && at[j] != NONE {
                blocks.add(at[i], at[j], v);
            }
        });
        // (the values kept aside: a reduction that cannot be made falls back on them)
        let Some(mut reduction) = blocks.finish(values.clone()) else {
            self.factor_whole(a, at, diagonal, values);
            return;
        };
        reduction.diagonal.clone_from(&diagonal);
        let base = &mut self.base;
        base.reduction = Some(reduction);
        base.at = at;
        base.diagonal = diagonal;
        self.factorised = values;
        self.z.clear(k);
    }

    /// Whether the interface matrix of `a` (its coupled unknowns, its decoupled ones'
    /// diagonal) is to be reduced, and the live unknowns: where that is predicted to cost
    /// fewer flops than whole LUs, counting the LUs with the bodies kept still to come
    /// (SSNP154 A mortar at 98k has almost none: reduced at every factorisation, it took
    /// 5 % longer and 20 MiB more; D mortar at 266k reduced with one to come took 0.50 s
    /// against 0.30 s for a whole LU, as the flops predict), and with at least a quarter
    /// of the interface passive. The multipliers of open points next to the contact zone
    /// are then kept, so that such a point that closes changes the live part only.
    pub(super) fn reduction_wanted(
        &self,
        a: &SparseMatrix,
        coupled: &[bool],
        diagonal: &[f64],
        bodies_kept: bool,
    ) -> (bool, Vec<bool>) {
        let k = self.gamma.len();
        let mut live = self.live_unknowns(a);
        for i in 0..k {
            // (a multiplier coupled to others only: mortar's friction rows)
            live[i] |= coupled[i] && self.gamma[i] >= self.np;
        }
        let passive = (0..k).filter(|&i| coupled[i] && !live[i]).count();
        let whole = (0..k).filter(|&i| coupled[i] || diagonal[i] == 0.0).count();
        let reduced = (0..k)
            .filter(|&i| coupled[i] || diagonal[i] == 0.0 || live[i])
            .count();
        // (the LUs with the bodies kept still to come: as many as in the last interval,
        // at least this one when it is such an LU)
        let coming = if bodies_kept {
            self.lus_last_interval.max(1)
        } else {
            self.lus_last_interval
        };
        // (the live unknowns decoupled from the rest, open points' multipliers, are solved
        // by their diagonal: the live part's LU is of the others, `live_lu.rs`)
        let live_coupled = whole - passive;
        let reduce = passive >= MIN_PASSIVE
            && 4 * passive >= k
            && pays(whole, passive, reduced - passive, live_coupled, coming);
        (reduce, live)
    }

    /// The interface unknowns that carry contact terms or may soon: the displacements with
    /// a nonzero entry to a multiplier, their neighbours (a nonzero entry between
    /// displacements: the next points to touch), and the multipliers with an entry to
    /// either. All, when the multipliers are not known.
    fn live_unknowns(&self, a: &SparseMatrix) -> Vec<bool> {
        let k = self.gamma.len();
        if self.np >= self.n {
            return vec![true; k];
        }
        let multiplier = |i: usize| self.gamma[i] >= self.np;
        let mut touching = vec![false; k];
        for &(p, i, j) in &self.gamma_entries {
            if a.values[p] != 0.0 && multiplier(i) != multiplier(j) {
                touching[i] = true;
                touching[j] = true;
            }
        }
        let mut live = touching.clone();
        for &(p, i, j) in &self.gamma_entries {
            if a.values[p] != 0.0 && !multiplier(i) && !multiplier(j) && touching[j] {
                live[i] = true;
            }
        }
        // the multipliers of open points next to live displacements (an entry in the
        // pattern, of any value): the next to close
        for &(_, i, j) in &self.gamma_entries {
            if multiplier(i) && !multiplier(j) && live[j] {
                live[i] = true;
            }
        }
        live
    }

    /// Takes `a`'s interface matrix as the reduced one at hand with a new LU of its live
    /// part, if it differs from the one reduced in live rows and columns only (the blocks
    /// must be those factorised): true when done.
    pub(super) fn live_refactored(&mut self, a: &SparseMatrix) -> bool {
        let k = self.gamma.len();
        let Some(red) = self.base.reduction.as_mut() else {
            return false;
        };
        if red.values.len() != self.gamma_entries.len() {
            return false;
        }
        let mut change = vec![];
        // (a decoupled unknown's diagonal, solved on its own: mortar's open points, whose
        // weight moves with the geometry)
        let mut diagonal = vec![];
        for (&(p, i, j), &old) in self.gamma_entries.iter().zip(&red.values) {
            let v = a.values[p];
            if v.to_bits() == old.to_bits() {
                continue;
            }
            if !v.is_finite() {
                return false;
            }
            let (ai, aj) = (self.base.at[i], self.base.at[j]);
            if i == j && ai == NONE {
                diagonal.push((i, v - old));
                continue;
            }
            if ai == NONE || aj == NONE {
                return false;
            }
            match (red.place(ai), red.place(aj)) {
                (Place::Live(li), Place::Live(lj)) => change.push((li, lj, v - old)),
                _ => return false,
            }
        }
        // (from the reduction's: an entry back at its value there is no change above; a
        // zero diagonal goes to an LU, as in `factor`)
        if diagonal.iter().any(|&(i, d)| red.diagonal[i] + d == 0.0) {
            return false;
        }
        self.base.diagonal.clone_from(&red.diagonal);
        for (i, d) in diagonal {
            self.base.diagonal[i] += d;
        }
        red.refactor_live(&change);
        self.factorised = self.interface_values(a);
        self.vanished.clear();
        self.update = None;
        self.z.clear(k);
        true
    }
}
