//! LDLᵀ without pivoting in a fixed order (`OrderedLdlt`), and its use for symmetric
//! saddle-point matrices [K Bᵀ; B C] (displacements, then multipliers), made safe by the
//! ordering: AMD on the displacement graph in which each multiplier's coupled
//! displacements form a clique, then every multiplier placed right after the last of its
//! coupled displacements. With K positive definite each multiplier pivot is then a
//! (negative) Schur complement, never zero (shared/design/dependencies.md).

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
}

/// AMD on the graph whose vertex j has the sorted neighbours `idx[ptr[j]..ptr[j + 1]]`
/// (itself included). Unknowns with the same adjacency (the two dofs of a node) are
/// ordered together: AMD runs on the graph of these groups, about four times smaller.
/// Returns the elimination order.
fn grouped_amd(ptr: &[usize], idx: &[usize]) -> Result<Vec<usize>> {
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

/// The constrained ordering (forward permutation) of `a` whose first `np` unknowns are
/// primal: AMD on the displacement graph in which each multiplier's coupled displacements
/// form a clique, then every multiplier placed right after the last of its coupled
/// displacements.
pub fn constrained_order(a: &SparseMatrix, np: usize) -> Result<Vec<usize>> {
    let n = a.n;
    let mut adj: Vec<Vec<usize>> = vec![vec![]; np];
    let mut coupled: Vec<Vec<usize>> = vec![vec![]; n - np];
    for c in 0..n {
        for &r in &a.row_idx[a.col_ptr[c]..a.col_ptr[c + 1]] {
            if c < np && r < np {
                adj[c].push(r);
            } else if c >= np && r < np {
                coupled[c - np].push(r);
            }
        }
    }
    // each primal unknown's multipliers, then its neighbours merged with theirs through a
    // marker (not by appending every clique and deduplicating: a multiplier couples with
    // about a hundred unknowns on a quadratic interface, and the appended cliques took
    // 240 MB on SSNP154 D at 92k unknowns)
    let mut mults_of: Vec<Vec<usize>> = vec![vec![]; np];
    for (m, list) in coupled.iter_mut().enumerate() {
        list.sort_unstable();
        list.dedup();
        for &i in list.iter() {
            mults_of[i].push(m);
        }
    }
    let mut mark = vec![usize::MAX; np];
    for (j, list) in adj.iter_mut().enumerate() {
        list.push(j);
        for &i in list.iter() {
            mark[i] = j;
        }
        for &m in &mults_of[j] {
            for &i in &coupled[m] {
                if mark[i] != j {
                    mark[i] = j;
                    list.push(i);
                }
            }
        }
        list.sort_unstable();
        list.dedup();
    }
    let mut ptr = vec![0];
    for list in &adj {
        ptr.push(ptr.last().unwrap() + list.len());
    }
    let perm = grouped_amd(&ptr, &adj.concat())?;
    let mut perm_inv = vec![0usize; np];
    for (i, &j) in perm.iter().enumerate() {
        perm_inv[j] = i;
    }
    // bucket each multiplier after the last of its coupled primal unknowns
    let mut after: Vec<Vec<usize>> = vec![vec![]; np + 1];
    for (m, list) in coupled.iter().enumerate() {
        let last = list.iter().map(|&i| perm_inv[i] + 1).max().unwrap_or(np);
        after[last.min(np)].push(np + m);
    }
    let mut order = Vec::with_capacity(n);
    order.extend_from_slice(&after[0]);
    for pos in 0..np {
        order.push(perm[pos]);
        order.extend_from_slice(&after[pos + 1]);
    }
    order.dedup();
    debug_assert_eq!(order.len(), n);
    Ok(order)
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
        Ok(OrderedLdlt {
            fwd,
            permuted,
            permuted_values: vec![0.0; nnz],
            origin,
            values,
            symbolic,
            scratch,
            solve_scratch,
        })
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
        self.symbolic
            .factorize_numeric_ldlt(
                &mut self.values,
                SparseColMatRef::new(self.permuted.as_ref(), &self.permuted_values),
                Side::Lower,
                Default::default(),
                Par::Seq,
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .map_err(|e| {
                Error::solve(format!(
                    "the system matrix is singular ({e:?}): a body may be free (not held by supports or \
                     contact)"
                ))
            })?;
        Ok(())
    }

    /// The storage of the factor's values, for a later analysis (`with_storage`).
    pub fn into_storage(self) -> Vec<f64> {
        self.values
    }

    /// The entry of the analysed pattern each factorised entry comes from.
    pub fn origins(&self) -> &[usize] {
        &self.origin
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
    /// (row, label) in any order. Each entry
    /// is then labelled by its label (what `factor_with` and `origins` give). False when
    /// the patterns differ; the labels are then partly rewritten (the analysis is
    /// unusable).
    pub fn rebind_with(
        &mut self,
        mut column: impl FnMut(usize, usize, &mut Vec<(usize, usize)>),
    ) -> bool {
        let mut col = vec![];
        for j in 0..self.fwd.len() {
            col.clear();
            column(j, self.fwd[j], &mut col);
            let range = self.permuted.col_range(j);
            if col.len() != range.len() {
                return false;
            }
            col.sort_unstable();
            for (q, &(r, label)) in range.zip(&col) {
                if self.permuted.row_idx()[q] != r {
                    return false;
                }
                self.origin[q] = label;
            }
        }
        true
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

    /// The supernodes of the factor: (first column, past-the-end column, rows below the
    /// diagonal block, column-major values of the block and the rows below).
    fn supernodes(&self) -> impl DoubleEndedIterator<Item = (usize, usize, &[usize], &[f64])> {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            unreachable!("the analysis forces the supernodal kernel")
        };
        (0..sym.n_supernodes()).map(move |s| {
            let (begin, end) = (sym.supernode_begin()[s], sym.supernode_end()[s]);
            let rows =
                &sym.row_idx()[sym.col_ptr_for_row_idx()[s]..sym.col_ptr_for_row_idx()[s + 1]];
            let vals = &self.values[sym.col_ptr_for_val()[s]..sym.col_ptr_for_val()[s + 1]];
            (begin, end, rows, vals)
        })
    }

    /// y ← L⁻¹ y, y in the factorised order.
    pub fn forward(&self, y: &mut [f64]) {
        let mut tmp = vec![];
        for (begin, end, rows, vals) in self.supernodes() {
            let (c, ld) = (end - begin, end - begin + rows.len());
            let yb = &mut y[begin..end];
            for j in 0..c {
                let xj = yb[j];
                let col = &vals[j * ld + j + 1..j * ld + c];
                for (yi, l) in yb[j + 1..].iter_mut().zip(col) {
                    *yi -= l * xj;
                }
            }
            tmp.clear();
            tmp.resize(rows.len(), 0.0);
            for j in 0..c {
                let xj = y[begin + j];
                let col = &vals[j * ld + c..(j + 1) * ld];
                for (t, l) in tmp.iter_mut().zip(col) {
                    *t += l * xj;
                }
            }
            for (&r, t) in rows.iter().zip(&tmp) {
                y[r] -= t;
            }
        }
    }

    /// y ← L⁻ᵀ y, y in the factorised order.
    pub fn backward(&self, y: &mut [f64]) {
        let mut tmp = vec![];
        for (begin, end, rows, vals) in self.supernodes().rev() {
            let (c, ld) = (end - begin, end - begin + rows.len());
            tmp.clear();
            tmp.extend(rows.iter().map(|&r| y[r]));
            for j in 0..c {
                y[begin + j] -= dot(&vals[j * ld + c..(j + 1) * ld], &tmp);
            }
            let yb = &mut y[begin..end];
            for j in (0..c).rev() {
                let below = dot(&vals[j * ld + j + 1..j * ld + c], &yb[j + 1..]);
                yb[j] -= below;
            }
        }
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

/// LDLᵀ of symmetric saddle-point matrices [K Bᵀ; B C] (displacements, then multipliers)
/// in the constrained order (`constrained_order`), of a symmetric approximation of the
/// matrix (see `factor`).
pub struct SaddleLdlt {
    ldlt: OrderedLdlt,
    /// Number of displacement unknowns (the multipliers follow).
    np: usize,
}

impl SaddleLdlt {
    /// Orders and analyses `a` (first `np` unknowns primal).
    pub fn new(a: &SparseMatrix, np: usize) -> Result<Self> {
        let fwd = constrained_order(a, np)?;
        Ok(SaddleLdlt {
            ldlt: OrderedLdlt::new(a, fwd)?,
            np,
        })
    }

    /// Factorises a symmetric matrix equal to `a` when `a` is symmetric (the pattern given
    /// to `new`); `transpose[p]` is the position in `a` of the transpose of entry p.
    pub fn factor(&mut self, a: &SparseMatrix, transpose: &[usize]) -> Result<()> {
        // The symmetric matrix factorised: the displacement block's symmetric part, and
        // for the multiplier couplings the displacement rows (the contact forces), mirrored
        // onto the constraint rows. With friction this is a better preconditioner for GMRES
        // on the exact matrix than the symmetric part (SSNP154 D: 213 -> 108 iterations).
        let np = self.np;
        self.ldlt.factor_with(|p, row, col| {
            if row < np && col < np {
                0.5 * (a.values[p] + a.values[transpose[p]])
            } else if row <= col {
                a.values[p]
            } else {
                a.values[transpose[p]]
            }
        })
    }

    /// Solves with the last factorisation, in place.
    pub fn solve(&mut self, b: &mut [f64]) {
        self.ldlt.solve(b);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [K Bᵀ; B 0] with K a 1D Laplacian plus a shift (SPD) and B picking pairs of
    /// unknowns far apart (so that the constrained order moves the multipliers).
    fn saddle(n: usize, m: usize) -> SparseMatrix {
        let mut entries: Vec<(usize, usize, f64)> = vec![];
        for i in 0..n {
            entries.push((i, i, 2.5));
            if i + 1 < n {
                entries.push((i, i + 1, -1.0));
                entries.push((i + 1, i, -1.0));
            }
        }
        for k in 0..m {
            let (a, b) = (k, n - 1 - 2 * k);
            entries.push((n + k, a, 1.0));
            entries.push((a, n + k, 1.0));
            entries.push((n + k, b, -0.5));
            entries.push((b, n + k, -0.5));
            entries.push((n + k, n + k, 0.0));
        }
        SparseMatrix::from_entries(n + m, &entries)
    }

    #[test]
    fn saddle_point_system_is_solved_exactly_and_refactorised() {
        let (n, m) = (40, 5);
        let mut a = saddle(n, m);
        let transpose = crate::solver::linear::transpose_positions(&a);
        let mut f = SaddleLdlt::new(&a, n).unwrap();
        for shift in [0.0, 1.0] {
            for c in 0..n {
                let q = a.position(c, c).unwrap();
                a.values[q] = 2.5 + shift;
            }
            f.factor(&a, &transpose).unwrap();
            let x: Vec<f64> = (0..n + m).map(|i| (0.3 * i as f64).cos()).collect();
            let mut b = vec![0.0; n + m];
            a.mul_vec(&x, &mut b);
            f.solve(&mut b);
            let err = b
                .iter()
                .zip(&x)
                .fold(0.0f64, |e, (u, v)| e.max((u - v).abs()));
            assert!(err < 1e-12, "shift {shift}: error {err}");
        }
    }

    /// The trailing block of the factor, L D Lᵀ, is the Schur complement of the leading
    /// unknowns: checked against a dense elimination.
    #[test]
    fn trailing_block_is_the_schur_complement() {
        let (n, m) = (40, 5);
        let a = saddle(n, m);
        let total = n + m;
        let k = 8; // the multipliers and three primal unknowns last
        let lead = total - k;
        let fwd: Vec<usize> = (0..total)
            .filter(|&i| i != 10 && i != 20 && i != 30 && i < n)
            .chain([10, 20, 30])
            .chain(n..total)
            .collect();
        let mut f = OrderedLdlt::new(&a, fwd.clone()).unwrap();
        f.factor_with(|p, _, _| a.values[p]).unwrap();
        let mut l = Mat::zeros(0, 0);
        let d = f.trailing_block(k, &mut l);
        // dense P A Pᵀ and its Schur complement on the last k unknowns
        let mut dense = Mat::<f64>::zeros(total, total);
        for c in 0..total {
            for p in a.col_ptr[c]..a.col_ptr[c + 1] {
                let (i, j) = (
                    fwd.iter().position(|&x| x == a.row_idx[p]).unwrap(),
                    fwd.iter().position(|&x| x == c).unwrap(),
                );
                dense[(i, j)] = a.values[p];
            }
        }
        let a11 = dense.submatrix(0, 0, lead, lead).to_owned();
        let a12 = dense.submatrix(0, lead, lead, k).to_owned();
        let a21 = dense.submatrix(lead, 0, k, lead).to_owned();
        let a22 = dense.submatrix(lead, lead, k, k).to_owned();
        let lu = a11.partial_piv_lu();
        let x = faer::linalg::solvers::Solve::solve(&lu, &a12);
        let schur = &a22 - &a21 * &x;
        let mut ld = l.clone();
        for (j, &dj) in d.iter().enumerate() {
            for i in 0..k {
                ld[(i, j)] *= dj;
            }
        }
        let from_factor = &ld * l.transpose();
        let mut err = 0.0f64;
        for i in 0..k {
            for j in 0..k {
                err = err.max((from_factor[(i, j)] - schur[(i, j)]).abs());
            }
        }
        assert!(err < 1e-12, "Schur complement error {err}");
    }

    /// L⁻ᵀ D⁻¹ L⁻¹ by the passes over the supernodes is faer's solve.
    #[test]
    fn forward_and_backward_passes_make_the_solve() {
        let (n, m) = (40, 5);
        let a = saddle(n, m);
        let transpose = crate::solver::linear::transpose_positions(&a);
        let mut f = SaddleLdlt::new(&a, n).unwrap();
        f.factor(&a, &transpose).unwrap();
        let b: Vec<f64> = (0..n + m).map(|i| (0.7 * i as f64).cos()).collect();
        let mut by_faer = b.clone();
        f.solve(&mut by_faer);
        let l = &f.ldlt;
        let mut y: Vec<f64> = l.order().iter().map(|&i| b[i]).collect();
        l.forward(&mut y);
        for (v, d) in y.iter_mut().zip(l.pivots()) {
            *v /= d;
        }
        l.backward(&mut y);
        let mut err = 0.0f64;
        for (pos, &i) in l.order().iter().enumerate() {
            err = err.max((y[pos] - by_faer[i]).abs());
        }
        assert!(err < 1e-13, "passes differ from the solve by {err}");
    }
}
