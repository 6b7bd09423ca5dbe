//! Direct solve of a contact tangent by condensation on its interface. The unknowns Γ
//! that carry contact terms (every multiplier, every displacement coupled to one) are
//! set apart; removing them splits the displacements into blocks with no coupling
//! between them (the bodies, which touch only through the contact), each symmetric
//! positive definite. Each block is factorised on its own (both in parallel, LDLᵀ with
//! its interface unknowns ordered last), its Schur complement onto the interface is read
//! off the trailing block of the factor, and the interface system, with every contact
//! term exact (non-symmetric with friction, saddle point), is solved by dense LU with
//! partial pivoting. The result is the exact solution of the tangent system: no GMRES on
//! a symmetric approximation, and the two cores share the factorisation.
//!
//! Per block, with Γ_b its interface unknowns and σ < 0 a shift on their diagonal:
//!   M_b = [A_II A_IΓ; A_ΓI σI] = L D Lᵀ,  S'_b = σI − A_ΓI A_II⁻¹ A_IΓ (trailing L D Lᵀ)
//!   T = A_ΓΓ + Σ_b (S'_b − σI)                          (the interface matrix, dense)
//!   z = L⁻¹ [b_I; 0]  ⇒  A_ΓI A_II⁻¹ b_I = −L_ΓΓ z_Γ
//!   T x_Γ = b_Γ + Σ_b L_ΓΓ z_Γ,   then [x_I; x_Γ] = L⁻ᵀ [D_I⁻¹ z_I; L_ΓΓᵀ x_Γ]
//! (one forward and one backward pass per block, the cost of one solve).
//!
//! Files: `block.rs` (one body's block and its Schur complement), `dense_lu.rs` (the
//! interface matrix's LU), `update.rs` (an active-set re-solve as a low-rank change of the
//! last LU, where T changes in a few rows only), `reduced.rs` (T reduced onto the unknowns
//! that carry contact terms, so that a correction with the bodies' factorisations kept
//! costs an LU of those alone; `passive.rs` its passive part body by body), `growth.rs` (a
//! grown contact pattern taken while its new entries are zero), `live_lu.rs` (the live
//! part's LU, its decoupled unknowns apart).

mod block;
mod dense_lu;
mod growth;
mod live_lu;
mod passive;
mod reduced;
mod update;

use crate::assembly::matrix::SparseMatrix;
use crate::error::{Error, Result};
use block::Block;
use dense_lu::DenseLu;
use rayon::prelude::*;
use update::{Factorised, Update, ZColumns};

/// Larger interfaces go to the saddle-point LDLᵀ (GMRES on a symmetric approximation).
/// The interface matrix is dense: k² memory and a k³ LU. A 2D contact zone's interface
/// grows as √n (SSNP154 D set-up: k ≈ 7√n), so its LU grows as n^1.5, as the bodies'
/// sparse factorisations do. Measured on that set-up: the LU takes 0.13 s at k ≈ 2200
/// (92k unknowns; the whole run 14 s, against 55 s through the LDLᵀ and GMRES) and 0.8 s
/// at k ≈ 3700 (294k). SSNP154 A with mortar at 1.27M unknowns (k ≈ 6700, k growing as 1/h
/// from 2357 at 98k): 423 s and 5.3 GB with this path, where the LDLᵀ passed 11.8 GB in
/// 65 s. At 10 000 the dense matrices hold about 1.6 GB and the LU takes about 16 s (k³
/// from 0.8 s at 3700).
const MAX_INTERFACE: usize = 10_000;

const NONE: usize = usize::MAX;

/// Factors smaller than this many entries are factorised on one core (faer's parallel
/// kernels pay in large supernodes only: SSNP154 A at 98k unknowns, no gain).
const MIN_PARALLEL_FACTOR: usize = 1 << 24;

pub struct InterfaceSolver {
    n: usize,
    /// The unknowns from this one on are multipliers (n: none known, then the interface
    /// matrix is never reduced onto its live unknowns, `reduced.rs`).
    np: usize,
    /// Global index of each interface unknown.
    gamma: Vec<usize>,
    blocks: Vec<Block>,
    /// Entries of A inside Γ × Γ: (position in A, interface row, interface column).
    gamma_entries: Vec<(usize, usize, usize)>,
    /// The interface matrix's LU of its coupled unknowns (see `update::Factorised`).
    base: Factorised,
    /// The values of A's interface entries the LU is of (empty: none usable), the
    /// columns of Z computed since, and the change to apply after it (see `update.rs`).
    /// `vanished`: entries the LU is of that a rebind took out of the pattern (interface
    /// row, column, value).
    factorised: Vec<f64>,
    vanished: Vec<(usize, usize, f64)>,
    z: ZColumns,
    update: Option<Update>,
    /// LUs (whole or live) made with the bodies' factorisations kept since the bodies
    /// were last factorised, and in the interval before: the reduction pays only where
    /// such LUs follow (frozen-body corrections, active-set re-solves beyond a low-rank
    /// update), and costs memory (`reduced.rs`).
    lus_with_bodies_kept: usize,
    lus_last_interval: usize,
    /// Positions in A of entries this analysis does not hold, all zero when it took A's
    /// pattern, and the unknowns that joined the interface then (`growth.rs`): it stands
    /// while those entries stay zero and these unknowns' entries symmetric (`stands`).
    ignored: Vec<usize>,
    joined: Vec<usize>,
}

/// The interface of `a` (first `np` unknowns primal; `transpose[p]` the position of the
/// transpose of entry p): the multipliers and the primal unknowns that share an entry with
/// one, or whose entries are not symmetric. None when it is empty, too large for a dense
/// solve, or more than a quarter of the unknowns (then it does not split the bodies).
pub fn interface_of(a: &SparseMatrix, np: usize, transpose: &[usize]) -> Option<Vec<bool>> {
    interface_with(a, np, |p, _, _| transpose[p])
}

/// As `interface_of`, each entry's transpose found by a search in its column (no buffer
/// of A's size: a rebind's cost is in fresh pages, not in comparisons).
pub fn interface_searched(a: &SparseMatrix, np: usize) -> Option<Vec<bool>> {
    interface_with(a, np, |_, r, c| a.position(c, r).unwrap_or(usize::MAX))
}

/// `transpose(p, r, c)`: the position of (c, r), entry p being (r, c); usize::MAX if none
/// (then the entry is not symmetric).
fn interface_with(
    a: &SparseMatrix,
    np: usize,
    transpose: impl Fn(usize, usize, usize) -> usize,
) -> Option<Vec<bool>> {
    let mut gamma = vec![false; a.n];
    for c in 0..a.n {
        for p in a.col_ptr[c]..a.col_ptr[c + 1] {
            let r = a.row_idx[p];
            let multiplier = r >= np || c >= np;
            if multiplier || {
                let t = transpose(p, r, c);
                t == usize::MAX || a.values[t] != a.values[p]
            } {
                gamma[r] = true;
                gamma[c] = true;
            }
        }
    }
    let k = gamma.iter().filter(|&&g| g).count();
    (k > 0 && k <= MAX_INTERFACE && 4 * k <= a.n).then_some(gamma)
}

/// The large buffers of an analysis, which the next one (of a changed pattern) takes over:
/// their pages are mapped already, where fresh ones are faulted in (glibc serves buffers
/// this large by fresh mappings). SSNP154 mortar, D set-up at 93k unknowns, 9 analyses:
/// 508k page faults, 1.4 s of system time without.
#[derive(Default)]
pub struct Storage {
    /// The blocks' factors' values.
    factors: Vec<Vec<f64>>,
    /// The interface matrix's storage (its last LU).
    interface: DenseLu,
}

/// The interface unknowns (increasing) and the blocks: the interior's connected
/// components packed into two blocks of about equal size (two cores), each as its interior
/// unknowns then the interface unknowns it couples to, its interior count, and the
/// positions in the interface of the latter.
struct Partition {
    gamma: Vec<usize>,
    parts: Vec<(Vec<usize>, usize, Vec<usize>)>,
}

fn partition(a: &SparseMatrix, in_gamma: &[bool]) -> Partition {
    let n = a.n;
    let gamma: Vec<usize> = (0..n).filter(|&i| in_gamma[i]).collect();
    let mut gamma_pos = vec![NONE; n];
    for (k, &g) in gamma.iter().enumerate() {
        gamma_pos[g] = k;
    }
    // Connected components of the interior, then packed into two blocks of about
    // equal size (two cores).
    let mut component = vec![NONE; n];
    let mut sizes = vec![];
    for s in 0..n {
        if in_gamma[s] || component[s] != NONE {
            continue;
        }
        let id = sizes.len();
        component[s] = id;
        let mut stack = vec![s];
        let mut size = 0;
        while let Some(v) = stack.pop() {
            size += 1;
            for &r in &a.row_idx[a.col_ptr[v]..a.col_ptr[v + 1]] {
                if !in_gamma[r] && component[r] == NONE {
                    component[r] = id;
                    stack.push(r);
                }
            }
        }
        sizes.push(size);
    }
    let mut by_size: Vec<usize> = (0..sizes.len()).collect();
    by_size.sort_by_key(|&c| std::cmp::Reverse(sizes[c]));
    let mut bin_of = vec![0usize; sizes.len()];
    let mut load = [0usize; 2];
    for c in by_size {
        let bin = if load[0] <= load[1] { 0 } else { 1 };
        bin_of[c] = bin;
        load[bin] += sizes[c];
    }
    let mut parts = vec![];
    for bin in 0..2 {
        if load[bin] == 0 {
            continue;
        }
        let mut unknowns: Vec<usize> = (0..n)
            .filter(|&i| component[i] != NONE && bin_of[component[i]] == bin)
            .collect();
        let interior = unknowns.len();
        let mut touched = vec![false; gamma.len()];
        for &i in &unknowns {
            for &r in &a.row_idx[a.col_ptr[i]..a.col_ptr[i + 1]] {
                if in_gamma[r] {
                    touched[gamma_pos[r]] = true;
                }
            }
        }
        let block_gamma: Vec<usize> = (0..gamma.len()).filter(|&k| touched[k]).collect();
        unknowns.extend(block_gamma.iter().map(|&k| gamma[k]));
        parts.push((unknowns, interior, block_gamma));
    }
    Partition { gamma, parts }
}

/// The entries of A inside Γ × Γ: (position in A, interface row, interface column).
fn gamma_entries(a: &SparseMatrix, gamma: &[usize]) -> Vec<(usize, usize, usize)> {
    let mut gamma_pos = vec![NONE; a.n];
    for (k, &g) in gamma.iter().enumerate() {
        gamma_pos[g] = k;
    }
    let mut entries = vec![];
    for (jc, &c) in gamma.iter().enumerate() {
        for p in a.col_ptr[c]..a.col_ptr[c + 1] {
            let r = a.row_idx[p];
            if gamma_pos[r] != NONE {
                entries.push((p, gamma_pos[r], jc));
            }
        }
    }
    entries
}

impl InterfaceSolver {
    /// Analyses `a` (structurally symmetric) with its interface `in_gamma` (`interface_of`),
    /// in the `storage` of an earlier analysis (or a default one).
    pub fn new(a: &SparseMatrix, in_gamma: Vec<bool>, storage: Storage) -> Result<Self> {
        let n = a.n;
        let Partition { gamma, parts } = partition(a, &in_gamma);
        // the blocks' orderings and analyses, in parallel
        let mut factors = storage.factors;
        factors.resize_with(parts.len(), Vec::new);
        let mut blocks = parts
            .into_par_iter()
            .zip(factors)
            .map(|((unknowns, interior, block_gamma), values)| {
                Block::new(a, unknowns, interior, block_gamma, values)
            })
            .collect::<Result<Vec<Block>>>()?;
        // The largest block, when it holds most of the factors' entries, is factorised with
        // faer's parallel kernels: the smaller blocks finish early and leave it alone.
        let entries: Vec<usize> = blocks.iter().map(|b| b.ldlt.entries()).collect();
        let total: usize = entries.iter().sum();
        if let Some((big, &most)) = entries.iter().enumerate().max_by_key(|&(_, &e)| e) {
            if 2 * most > total && most >= MIN_PARALLEL_FACTOR {
                blocks[big].ldlt.factor_in_parallel();
            }
        }
        let gamma_entries = gamma_entries(a, &gamma);
        Ok(InterfaceSolver {
            n,
            np: n,
            gamma,
            blocks,
            gamma_entries,
            base: Factorised {
                lu: storage.interface,
                ..Default::default()
            },
            factorised: vec![],
            vanished: vec![],
            z: ZColumns::default(),
            update: None,
            lus_with_bodies_kept: 0,
            lus_last_interval: 0,
            ignored: vec![],
            joined: vec![],
        })
    }

    /// Takes `a`, a matrix of another pattern (`in_gamma` its interface), as this
    /// analysis's when only its entries between interface unknowns differ: the same
    /// interface, the same blocks with the same entries. A contact pattern change is
    /// usually that (mortar segments that start or stop overlapping among the interface
    /// unknowns); the blocks' analyses, and their factorisations while their values are
    /// unchanged, then stand. False when `a` needs an analysis of its own (this one is
    /// then unusable: `into_storage` only).
    pub fn rebind(&mut self, a: &SparseMatrix, in_gamma: &[bool]) -> bool {
        if a.n != self.n {
            return false;
        }
        // (the interface first: its partition costs a pass over A)
        let same_gamma = in_gamma.iter().filter(|&&g| g).count() == self.gamma.len()
            && self.gamma.iter().all(|&g| in_gamma[g]);
        if !same_gamma {
            return false;
        }
        let Partition { gamma, parts } = partition(a, in_gamma);
        let same_blocks = gamma == self.gamma
            && parts.len() == self.blocks.len()
            && parts.iter().zip(&self.blocks).all(|((u, interior, g), b)| {
                *u == b.unknowns && *interior == b.interior && *g == b.gamma
            });
        if !same_blocks {
            return false;
        }
        let rebound = self
            .blocks
            .par_iter_mut()
            .map(|b| {
                let at = b.positions(a.n);
                b.rebind(a, &at, false)
            })
            .collect::<Vec<bool>>();
        if rebound.contains(&false) {
            return false;
        }
        self.ignored.clear();
        self.joined.clear();
        self.take_interface_entries(a);
        true
    }

    /// After a rebind (the same interface, the entries of A in Γ × Γ at other positions):
    /// the values the LU is of, labelled by the new entries, and those of entries out of
    /// the pattern kept aside as changes to undo (an entry back in the pattern takes its
    /// value from there; one never seen was zero). An active-set re-solve whose contact
    /// pattern changed is then still a low-rank change of the LU at hand, not a new LU.
    /// `old` and the new entries are sorted by (interface column, row).
    fn relabel_factorised(&mut self, old: &[(usize, usize, usize)]) {
        if self.factorised.len() != old.len() {
            return;
        }
        // (ordered: the update's sums come out the same in every run)
        let mut aside: std::collections::BTreeMap<(usize, usize), f64> =
            self.vanished.iter().map(|&(i, j, v)| ((j, i), v)).collect();
        let mut values = Vec::with_capacity(self.gamma_entries.len());
        let mut o = 0;
        for &(_, i, j) in &self.gamma_entries {
            while o < old.len() && (old[o].2, old[o].1) < (j, i) {
                aside.insert((old[o].2, old[o].1), self.factorised[o]);
                o += 1;
            }
            if o < old.len() && (old[o].2, old[o].1) == (j, i) {
                values.push(self.factorised[o]);
                o += 1;
            } else {
                values.push(aside.remove(&(j, i)).unwrap_or(0.0));
            }
        }
        for (e, &v) in old[o..].iter().zip(&self.factorised[o..]) {
            aside.insert((e.2, e.1), v);
        }
        self.vanished = aside
            .into_iter()
            .filter(|&(_, v)| v != 0.0)
            .map(|((j, i), v)| (i, j, v))
            .collect();
        self.factorised = values;
    }

    /// Calls `f(i, j, v)` for every term of the interface matrix of `a` (interface row,
    /// column, value): A's entries in Γ × Γ, then the blocks' Schur complements column by
    /// column (each entry's sum in the same order at every visit).
    fn visit_interface(&self, a: &SparseMatrix, mut f: impl FnMut(usize, usize, f64)) {
        for &(p, i, j) in &self.gamma_entries {
            f(i, j, a.values[p]);
        }
        for b in &self.blocks {
            for (lj, &gj) in b.gamma.iter().enumerate() {
                for (&gi, v) in b.gamma.iter().zip(b.schur_column(lj)) {
                    f(gi, gj, v);
                }
            }
        }
    }

    /// A's values at the interface entries (in their order).
    fn interface_values(&self, a: &SparseMatrix) -> Vec<f64> {
        self.gamma_entries
            .iter()
            .map(|&(p, _, _)| a.values[p])
            .collect()
    }

    /// The unknowns from `np` on are multipliers: the interface matrix may then be reduced
    /// onto the unknowns that carry contact terms (`reduced.rs`).
    pub fn with_multipliers_from(mut self, np: usize) -> Self {
        self.np = np.min(self.n);
        self
    }

    /// How many solves one factorisation of the bodies costs, counted in multiply-adds
    /// (a solve's: forward and backward passes, about two per stored factor entry). A pure
    /// number of the mesh: it grows as the factor's fronts do, about as √n in 2D.
    pub fn solves_per_factorisation(&self) -> f64 {
        let flops: f64 = self.blocks.iter().map(|b| b.ldlt.factor_flops()).sum();
        let entries: usize = self.blocks.iter().map(|b| b.ldlt.entries()).sum();
        flops / (2 * entries).max(1) as f64
    }

    /// Its large buffers, for the next analysis.
    pub fn into_storage(self) -> Storage {
        Storage {
            factors: self
                .blocks
                .into_iter()
                .map(|b| b.ldlt.into_storage())
                .collect(),
            interface: self.base.lu,
        }
    }

    /// Factorises the blocks (in parallel) and the interface matrix of `a` (the pattern
    /// given to `new`).
    pub fn factor(&mut self, a: &SparseMatrix) -> Result<()> {
        let k = self.gamma.len();
        let refactored = self
            .blocks
            .par_iter_mut()
            .map(|b| b.factor(a))
            .collect::<Result<Vec<bool>>>()?;
        // An active-set re-solve or a frozen-body correction: the LU at hand and a
        // low-rank change (`update.rs`), or the reduction at hand and a new LU of its live
        // part (`reduced.rs`).
        let bodies_kept = !refactored.contains(&true);
        if bodies_kept && self.updated(a) {
            return Ok(());
        }
        if bodies_kept {
            self.lus_with_bodies_kept += 1;
            if self.live_refactored(a) {
                return Ok(());
            }
        } else {
            self.lus_last_interval = self.lus_with_bodies_kept;
            self.lus_with_bodies_kept = 0;
        }
        self.factorised.clear(); // until this factorisation is made
        self.vanished.clear();
        self.update = None;
        // Unknowns decoupled from the rest of the interface (the multipliers of open
        // contact points: row and column hold only the diagonal) are solved on their own;
        // the dense LU, k³, gets the others only, and the interface matrix is built for
        // them alone (SSNP154 D with mortar at 93k unknowns: 2100 of 3064). Only the
        // entries of A in Γ × Γ and of the blocks' Schur complements can be nonzero: they
        // alone are looked at, and the diagonal is summed as the matrix's would be.
        let mut coupled = vec![false; k];
        let mut diagonal = vec![0.0; k];
        let mut finite = true;
        let mut look = |i: usize, j: usize, v: f64| {
            finite &= v.is_finite();
            if i == j {
                diagonal[i] += v;
            } else if v != 0.0 {
                coupled[i] = true;
                coupled[j] = true;
            }
        };
        self.visit_interface(a, &mut look);
        if !finite {
            return Err(Error::solve(
                "the system matrix is singular: non-finite interface matrix",
            ));
        }
        // Reduced onto its live unknowns where that pays (`reduced.rs`).
        let (reduce, live) = self.reduction_wanted(a, &coupled, &diagonal, bodies_kept);
        let values = self.interface_values(a);
        let base = &mut self.base;
        base.kept.clear();
        let mut at = vec![NONE; k];
        for i in 0..k {
            if coupled[i] || diagonal[i] == 0.0 || (reduce && live[i]) {
                at[i] = base.kept.len();
                base.kept.push(i);
            }
        }
        if reduce {
            self.reduce(a, at, diagonal, values, &live);
        } else {
            self.factor_whole(a, at, diagonal, values);
        }
        Ok(())
    }

    /// Factorises the interface matrix of `a` whole (its kept unknowns at `at`, the
    /// decoupled ones by their `diagonal`; A's interface `values`).
    pub(super) fn factor_whole(
        &mut self,
        a: &SparseMatrix,
        at: Vec<usize>,
        diagonal: Vec<f64>,
        values: Vec<f64>,
    ) {
        let k = self.gamma.len();
        let base = &mut self.base;
        base.reduction = None;
        // The interface matrix of the kept unknowns, in the storage of the last LU (no
        // fresh pages to fault in at every Newton iteration).
        let mut t = base.lu.take_storage(base.kept.len(), k);
        self.visit_interface(a, |i, j, v| {
            if at[i] != NONE && at[j] != NONE {
                t[(at[i], at[j])] += v;
            }
        });
        let base = &mut self.base;
        base.lu.factor(t);
        base.at = at;
        base.diagonal = diagonal;
        self.factorised = values;
        self.z.clear(k);
    }

    /// Takes `a`'s interface matrix as the one factorised plus a low-rank change, if the
    /// change is small enough (`update.rs`): true when done. The blocks must be those
    /// factorised.
    fn updated(&mut self, a: &SparseMatrix) -> bool {
        if self.factorised.len() != self.gamma_entries.len() {
            return false;
        }
        let mut changes: Vec<(usize, usize, f64)> =
            self.vanished.iter().map(|&(i, j, v)| (i, j, -v)).collect();
        for (&(p, i, j), &old) in self.gamma_entries.iter().zip(&self.factorised) {
            let v = a.values[p];
            if !v.is_finite() {
                return false;
            }
            if v.to_bits() != old.to_bits() {
                changes.push((i, j, v - old));
            }
        }
        // With the matrix reduced, Z's columns (2k² flops each) pay against a new LU of
        // its live part ((2/3) l³) for fewer than l³ / 3k² changed rows.
        if let Some(red) = &self.base.reduction {
            let mut rows: Vec<usize> = changes.iter().map(|c| c.0).collect();
            rows.sort_unstable();
            rows.dedup();
            let (k, l) = (self.base.kept.len() as f64, red.num_live() as f64);
            if 3.0 * k * k * rows.len() as f64 > l * l * l {
                return false;
            }
        }
        self.update = if changes.is_empty() {
            None
        } else {
            match Update::new(changes, &self.base, &mut self.z) {
                Some(u) => Some(u),
                None => return false,
            }
        };
        true
    }

    /// Solves with the last factorisation, in place: per block one forward pass (the
    /// interface rows at zero), the interface system, one backward pass.
    pub fn solve(&mut self, b: &mut [f64]) {
        debug_assert_eq!(b.len(), self.n);
        let rhs: &[f64] = b;
        // z = L⁻¹ [b_I; 0]; then A_ΓI A_II⁻¹ b_I = −S'_b v_Γ = −L_ΓΓ z_Γ
        let forward: Vec<Vec<f64>> = self
            .blocks
            .par_iter_mut()
            .map(|blk| {
                let order = blk.ldlt.order();
                let b_interior: Vec<f64> = order[..blk.interior]
                    .iter()
                    .map(|&l| rhs[blk.unknowns[l]])
                    .collect();
                if let Some((last_b, last_z)) = &blk.last_forward {
                    let same = last_b.len() == b_interior.len()
                        && last_b
                            .iter()
                            .zip(&b_interior)
                            .all(|(a, b)| a.to_bits() == b.to_bits());
                    if same {
                        return last_z.clone();
                    }
                }
                let mut z = b_interior.clone();
                z.resize(order.len(), 0.0);
                blk.ldlt.forward(&mut z);
                blk.last_forward = Some((b_interior, z.clone()));
                z
            })
            .collect();
        let mut xg: Vec<f64> = self.gamma.iter().map(|&g| rhs[g]).collect();
        for (blk, z) in self.blocks.iter().zip(&forward) {
            // L_ΓΓ z_Γ column by column (L is stored by columns); each row's sum still
            // adds its terms in the order of the columns
            let zg = &z[blk.interior..];
            let mut s = zg.to_vec();
            for (lj, &zj) in zg.iter().enumerate() {
                let column = &blk.trailing.col_as_slice(lj)[lj + 1..];
                for (si, &l) in s[lj + 1..].iter_mut().zip(column) {
                    *si += l * zj;
                }
            }
            for (&gi, si) in blk.gamma.iter().zip(s) {
                xg[gi] += si;
            }
        }
        self.base.solve(&mut xg);
        if let Some(u) = &self.update {
            u.apply(&mut xg, &self.z);
        }
        // backward pass from [D_I⁻¹ z_I; L_ΓΓᵀ x_Γ]: its interface part is x_Γ, its
        // interior part A_II⁻¹ (b_I − A_IΓ x_Γ)
        let xg = &xg;
        let backward: Vec<Vec<f64>> = self
            .blocks
            .par_iter()
            .zip(forward)
            .map(|(blk, mut w)| {
                let m = blk.interior;
                for (v, d) in w[..m].iter_mut().zip(&blk.pivots) {
                    *v /= d;
                }
                for li in 0..blk.gamma.len() {
                    let mut s = xg[blk.gamma[li]];
                    for lj in li + 1..blk.gamma.len() {
                        s += blk.trailing[(lj, li)] * xg[blk.gamma[lj]];
                    }
                    w[m + li] = s;
                }
                blk.ldlt.backward(&mut w);
                w
            })
            .collect();
        for (blk, w) in self.blocks.iter().zip(&backward) {
            for (&l, &x) in blk.ldlt.order()[..blk.interior].iter().zip(w) {
                b[blk.unknowns[l]] = x;
            }
        }
        for (&g, &x) in self.gamma.iter().zip(xg.iter()) {
            b[g] = x;
        }
    }
}

#[cfg(test)]
mod tests;
