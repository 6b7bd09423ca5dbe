//! `OrderedLdlt`: LDLᵀ without pivoting of a symmetric matrix in a fixed order (analysis
//! once, numeric factorisations into reused storage, solves, and the passes over the
//! factor's supernodes), and the AMD orders it is used with (`leading_order`, and the
//! grouped AMD under `constrained_order`).

use crate::assembly::matrix::{group_by_key, SparseMatrix};
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLdltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{Conj, Mat, MatMut, Par, Side};

mod forest;
mod numeric;
mod passes;

/// LDLᵀ without pivoting of P A Pᵀ for a fixed pattern of A and a fixed ordering. The
/// analysis (permuted pattern, symbolic factorisation) is done once; each numeric
/// factorisation writes its values straight into the permuted lower triangle, so faer has
/// nothing to permute, and reuses its storage.
pub struct OrderedLdlt {
    /// Position i of the factorised matrix is unknown `fwd[i]`.
    fwd: Vec<usize>,
    /// P A Pᵀ, lower triangle: its pattern and values.
    permuted: SymbolicSparseColMat<usize>,
    permuted_values: Vec<f64>,
    /// For each entry of `permuted`, the entry of A it comes from (its lower one of each
    /// symmetric pair): half the size of a map the other way.
    origin: Vec<usize>,
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// Factorisation and solve workspaces, kept between factorisations.
    scratch: MemBuffer,
    solve_scratch: MemBuffer,
    /// The supernodes' subtrees passed in parallel (`passes.rs`).
    split: passes::Split,
    /// The supernodes' tree, for the factorisation by subtrees on both cores (`numeric.rs`;
    /// None: faer's, in sequence).
    tree: Option<numeric::Tree>,
    /// The numeric factorisation uses faer's parallel kernels (see `factor_in_parallel`).
    par: Par,
}

/// The error of a factorisation that met a zero pivot (`e` names its position).
fn singular(e: impl std::fmt::Debug) -> Error {
    Error::solve(format!(
        "the system matrix is singular ({e:?}): a body may be free (not held by supports or \
         contact)"
    ))
}

/// AMD on the graph whose vertex j has the sorted neighbours `idx[ptr[j]..ptr[j + 1]]`
/// (itself included). Unknowns with the same adjacency (the two dofs of a node) are
/// ordered together: AMD runs on the graph of these groups, about four times smaller.
/// Returns the elimination order.
pub(super) fn grouped_amd(ptr: &[usize], idx: &[usize]) -> Result<Vec<usize>> {
    let np = ptr.len() - 1;
    let list = |j: usize| &idx[ptr[j]..ptr[j + 1]];
    let mut group_of = vec![0usize; np];
    let mut groups: Vec<usize> = vec![]; // first unknown of each group
    for j in 0..np {
        if j > 0 && list(j) == list(j - 1) {
            group_of[j] = group_of[j - 1];
        } else {
            group_of[j] = groups.len();
            groups.push(j);
        }
    }
    let ng = groups.len();
    // Groups are runs of consecutive unknowns, so a sorted list maps to sorted group ids:
    // only the repeats go.
    let mut col_ptr = Vec::with_capacity(ng + 1);
    col_ptr.push(0);
    let mut rows = Vec::with_capacity(idx.len() / 2);
    for &j in &groups {
        let start = rows.len();
        for &i in list(j) {
            let g = group_of[i];
            if rows.len() == start || rows[rows.len() - 1] != g {
                rows.push(g);
            }
        }
        col_ptr.push(rows.len());
    }
    let sym = SymbolicSparseColMatRef::new_checked(ng, ng, &col_ptr, None, &rows);
    let mut gperm = vec![0usize; ng];
    let mut gperm_inv = vec![0usize; ng];
    let mut mem = MemBuffer::new(amd::order_scratch::<usize>(ng, rows.len()));
    amd::order(
        &mut gperm,
        &mut gperm_inv,
        sym,
        amd::Control::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| Error::solve(format!("ordering failed: {e:?}")))?;
    let mut perm = Vec::with_capacity(np);
    for &g in &gperm {
        let first = groups[g];
        perm.extend((first..np).take_while(|&j| group_of[j] == g));
    }
    Ok(perm)
}

/// AMD order of the leading `np` unknowns of `a` on their own graph (the other unknowns
/// ignored), for an ordering that places the others last.
pub fn leading_order(a: &SparseMatrix, np: usize) -> Result<Vec<usize>> {
    let mut ptr = Vec::with_capacity(np + 1);
    ptr.push(0);
    let mut idx = Vec::with_capacity(a.col_ptr[np.min(a.n)]);
    for c in 0..np {
        // sorted rows below np, with the diagonal merged in
        let mut diagonal = false;
        for &r in &a.row_idx[a.col_ptr[c]..a.col_ptr[c + 1]] {
            if r >= np {
                continue;
            }
            if !diagonal && r >= c {
                if r != c {
                    idx.push(c);
                }
                diagonal = true;
            }
            idx.push(r);
        }
        if !diagonal {
            idx.push(c);
        }
        ptr.push(idx.len());
    }
    grouped_amd(&ptr, &idx)
}

impl OrderedLdlt {
    /// Analyses the pattern of `a` (structurally symmetric) in the order `fwd`.
    pub fn new(a: &SparseMatrix, fwd: Vec<usize>) -> Result<Self> {
        Self::with_storage(a, fwd, vec![])
    }

    /// As `new`, the factor's values in `storage` (that of an earlier analysis, see
    /// `into_storage`: its pages are mapped already, where fresh ones are faulted in).
    pub fn with_storage(a: &SparseMatrix, fwd: Vec<usize>, storage: Vec<f64>) -> Result<Self> {
        let n = a.n;
        let mut inv = vec![0usize; n];
        for (i, &p) in fwd.iter().enumerate() {
            inv[p] = i;
        }
        // pattern of P A Pᵀ (lower): entry p = (r, c) of A goes to (inv r, inv c) if
        // inv r ≥ inv c, so column j of it holds only entries of A's column fwd[j]: built
        // column by column, each sorted (a few dozen entries)
        let mut origin = Vec::with_capacity(a.nnz() / 2 + n);
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::with_capacity(a.nnz() / 2 + n);
        let mut col = vec![];
        for (j, &c) in fwd.iter().enumerate() {
            col.clear();
            for p in a.col_ptr[c]..a.col_ptr[c + 1] {
                let ir = inv[a.row_idx[p]];
                if ir >= j {
                    col.push((ir, p));
                }
            }
            col.sort_unstable();
            for &(r, p) in &col {
                origin.push(p);
                row_idx.push(r);
            }
            col_ptr.push(row_idx.len());
        }
        // With the identity ordering faer's analysis reads the upper triangle (whatever the
        // side argument), so it gets the transposed pattern (columns visited in order: each
        // transposed column comes out sorted); the numeric phase reads `permuted`.
        let (up_ptr, up_rows) = group_by_key(
            n,
            (0..n).flat_map(|c| {
                row_idx[col_ptr[c]..col_ptr[c + 1]]
                    .iter()
                    .map(move |&r| (r, c))
            }),
        );
        let upper = SymbolicSparseColMatRef::new_checked(n, n, &up_ptr, None, &up_rows);
        let symbolic = factorize_symbolic_cholesky(
            upper,
            Side::Upper,
            SymmetricOrdering::Identity,
            // The simplicial kernel is several times slower at these sizes.
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|e| Error::solve(format!("symbolic LDLT failed: {e:?}")))?;
        let scratch = MemBuffer::new(
            symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
        );
        let solve_scratch = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        let nnz = row_idx.len();
        // checked once here; each factorisation pairs it with its values
        let permuted = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        // (each factorisation overwrites every value: what the storage holds can stay; a
        // storage too small grows to the size needed, not to twice its own as `resize` would)
        let len = symbolic.len_val();
        let mut values = storage;
        values.truncate(len);
        values.reserve_exact(len - values.len());
        values.resize(len, 0.0);
        let mut ldlt = OrderedLdlt {
            fwd,
            permuted,
            permuted_values: vec![0.0; nnz],
            origin,
            values,
            symbolic,
            scratch,
            solve_scratch,
            split: passes::Split::default(),
            tree: None,
            par: Par::Seq,
        };
        ldlt.split = ldlt.split_of();
        if !ldlt.split.is_empty() {
            ldlt.tree = ldlt.tree_of();
        }
        Ok(ldlt)
    }

    /// Factorises the symmetric matrix whose lower triangle (in the factorised order) takes
    /// `value(p, row, col)` at each entry p = (row, col) of the analysed pattern that lands
    /// there (p as relabelled by `relabel_origins`).
    pub fn factor_with(&mut self, value: impl Fn(usize, usize, usize) -> f64) -> Result<()> {
        let permuted = self.permuted.as_ref();
        for j in 0..self.fwd.len() {
            for q in permuted.col_range(j) {
                let row = self.fwd[permuted.row_idx()[q]];
                self.permuted_values[q] = value(self.origin[q], row, self.fwd[j]);
            }
        }
        if let Some(tree) = self.tree.take() {
            let result = self.factor_by_tree(&tree);
            self.tree = Some(tree);
            return result;
        }
        self.symbolic
            .factorize_numeric_ldlt(
                &mut self.values,
                SparseColMatRef::new(self.permuted.as_ref(), &self.permuted_values),
                Side::Lower,
                Default::default(),
                self.par,
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .map_err(singular)?;
        Ok(())
    }

    /// Numeric factorisations with faer's parallel kernels (inside the large supernodes):
    /// for a factor that runs alone while the other core idles, as the largest body's
    /// block of a contact solve once the smaller ones are done (SSNP154 D point-to-segment
    /// at 266k unknowns: a body of 227k unknowns beside one of 40k, factorisation time
    /// −10 %). Two factors in parallel on two cores gain nothing from it.
    pub fn factor_in_parallel(&mut self) {
        let par = Par::rayon(0);
        let SymbolicCholeskyRaw::Supernodal(_) = self.symbolic.raw() else {
            return;
        };
        self.scratch = MemBuffer::new(
            self.symbolic
                .factorize_numeric_ldlt_scratch::<f64>(par, Default::default()),
        );
        self.par = par;
    }

    /// The number of entries of the factor.
    pub fn entries(&self) -> usize {
        self.values.len()
    }

    /// Multiply-adds of one numeric factorisation: over the columns, the square of the
    /// number of entries below the diagonal (a solve's are twice the entries).
    pub fn factor_flops(&self) -> f64 {
        self.supernodes()
            .map(|(begin, end, rows, _)| {
                let (c, r) = (end - begin, rows.len());
                (0..c)
                    .map(|j| ((c - 1 - j + r) as f64).powi(2))
                    .sum::<f64>()
            })
            .sum()
    }

    /// The storage of the factor's values, for a later analysis (`with_storage`).
    pub fn into_storage(self) -> Vec<f64> {
        self.values
    }

    /// The entry of the analysed pattern each factorised entry comes from.
    pub fn origins(&self) -> &[usize] {
        &self.origin
    }

    /// The values the last `factor_with` was given, per factorised entry (as `origins`).
    pub fn factored_values(&self) -> &[f64] {
        &self.permuted_values
    }

    /// Renames the entries of the analysed pattern (what `factor_with` and `origins` give):
    /// a caller that reads its values elsewhere drops its copy of the pattern.
    pub fn relabel_origins(&mut self, new_label: impl Fn(usize) -> usize) {
        for p in &mut self.origin {
            *p = new_label(*p);
        }
    }

    /// Takes a matrix of another pattern as the analysed one when the two are the same
    /// (in the analysed order): `column(j, c, out)` puts into `out` the entries of column j
    /// of its lower triangle in the factorised order (c: the matrix's column there), as
    /// (row, label) in any order. Each entry is then labelled by its label (what
    /// `factor_with` and `origins` give). With `beyond`, entries the analysed pattern does
    /// not hold are passed over (their caller knows them to be zero) instead of refused.
    /// False when an analysed entry is missing, or (without `beyond`) the patterns differ;
    /// the labels are then partly rewritten (the analysis is unusable).
    pub fn rebind_with(
        &mut self,
        beyond: bool,
        mut column: impl FnMut(usize, usize, &mut Vec<(usize, usize)>),
    ) -> bool {
        let mut col = vec![];
        for j in 0..self.fwd.len() {
            col.clear();
            column(j, self.fwd[j], &mut col);
            let range = self.permuted.col_range(j);
            if !beyond && col.len() != range.len() {
                return false;
            }
            col.sort_unstable();
            let rows = &self.permuted.row_idx()[range.clone()];
            let mut q = 0;
            for &(r, label) in &col {
                if q < rows.len() && rows[q] == r {
                    self.origin[range.start + q] = label;
                    q += 1;
                } else if !beyond {
                    return false;
                }
            }
            if q != rows.len() {
                return false;
            }
        }
        true
    }

    /// Whether the analysed pattern holds the entry at row i, column j of the factorised
    /// order (i ≥ j).
    pub fn holds(&self, i: usize, j: usize) -> bool {
        let range = self.permuted.col_range(j);
        self.permuted.row_idx()[range].binary_search(&i).is_ok()
    }

    /// Solves with the last factorisation, in place.
    pub fn solve(&mut self, b: &mut [f64]) {
        let n = b.len();
        let mut y: Vec<f64> = self.fwd.iter().map(|&i| b[i]).collect();
        let ldlt = LdltRef::new(&self.symbolic, &self.values);
        ldlt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut y, n, 1),
            Par::Seq,
            MemStack::new(&mut self.solve_scratch),
        );
        for (&i, &v) in self.fwd.iter().zip(&y) {
            b[i] = v;
        }
    }

    /// Supernode s: (first column, past-the-end column, rows below the diagonal block,
    /// column-major values of the block and the rows below).
    fn supernode(&self, s: usize) -> (usize, usize, &[usize], &[f64]) {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            unreachable!("the analysis forces the supernodal kernel")
        };
        let (begin, end) = (sym.supernode_begin()[s], sym.supernode_end()[s]);
        let rows = &sym.row_idx()[sym.col_ptr_for_row_idx()[s]..sym.col_ptr_for_row_idx()[s + 1]];
        let vals = &self.values[sym.col_ptr_for_val()[s]..sym.col_ptr_for_val()[s + 1]];
        (begin, end, rows, vals)
    }

    fn n_supernodes(&self) -> usize {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            unreachable!("the analysis forces the supernodal kernel")
        };
        sym.n_supernodes()
    }

    /// The supernodes in order (see `supernode`).
    fn supernodes(&self) -> impl Iterator<Item = (usize, usize, &[usize], &[f64])> {
        (0..self.n_supernodes()).map(|s| self.supernode(s))
    }

    /// The pivots D (in the factorised order).
    pub fn pivots(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.fwd.len()];
        for (begin, end, rows, vals) in self.supernodes() {
            let ld = end - begin + rows.len();
            for j in 0..end - begin {
                d[begin + j] = vals[j * ld + j];
            }
        }
        d
    }

    /// Position i of the factorised order is unknown `order()[i]`.
    pub fn order(&self) -> &[usize] {
        &self.fwd
    }

    /// The last `k` columns of the factor: the unit lower triangle L of the trailing k × k
    /// block, written into `l` (whose storage is reused), and the block's pivots D,
    /// returned (L D Lᵀ is the Schur complement of the leading unknowns).
    pub fn trailing_block(&self, k: usize, l: &mut Mat<f64>) -> Vec<f64> {
        let n = self.fwd.len();
        let first = n - k;
        l.resize_with(k, k, |_, _| 0.0);
        l.fill(0.0);
        let mut d = vec![0.0; k];
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            unreachable!("the analysis forces the supernodal kernel")
        };
        let ldlt = SupernodalLdltRef::new(sym, &self.values);
        for s in 0..sym.n_supernodes() {
            let (begin, end) = (sym.supernode_begin()[s], sym.supernode_end()[s]);
            if end <= first {
                continue;
            }
            let node = ldlt.supernode(s);
            let block = node.val();
            let below = node.pattern();
            for j in begin.max(first)..end {
                let cj = j - begin;
                d[j - first] = block[(cj, cj)];
                l[(j - first, j - first)] = 1.0;
                for i in j + 1..end {
                    l[(i - first, j - first)] = block[(i - begin, cj)];
                }
                for (t, &i) in below.iter().enumerate() {
                    l[(i - first, j - first)] = block[(end - begin + t, cj)];
                }
            }
        }
        d
    }
}

/// Σ a_i b_i in four independent partial sums (a single running sum is bound by the
/// latency of each addition; four vectorise).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}
