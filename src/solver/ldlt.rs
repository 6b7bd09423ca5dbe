//! LDLᵀ of symmetric saddle-point matrices [K Bᵀ; B C] (displacements, then multipliers)
//! without pivoting, made safe by the ordering: AMD on the displacement graph in which each
//! multiplier's coupled displacements form a clique, then every multiplier placed right
//! after the last of its coupled displacements. With K positive definite each multiplier
//! pivot is then a (negative) Schur complement, never zero (shared/design/dependencies.md).

use crate::assembly::matrix::SparseMatrix;
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SymbolicSparseColMatRef;
use faer::{Conj, MatMut, Par, Side};

/// The analysis (ordering, permuted pattern, symbolic factorisation) is done once per
/// pattern; each numeric factorisation writes a symmetric approximation of the matrix (see
/// `factor`) straight into the permuted lower triangle, so faer has nothing to permute, and
/// reuses its storage.
pub struct SaddleLdlt {
    /// Constrained order: position i of the factorised matrix is unknown `fwd[i]`.
    fwd: Vec<usize>,
    /// P A Pᵀ, lower triangle.
    permuted: SparseMatrix,
    /// For each entry of A, its position in `permuted` (NONE if it lands above the diagonal).
    map: Vec<usize>,
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// Factorisation and solve workspaces, kept between factorisations.
    scratch: MemBuffer,
    solve_scratch: MemBuffer,
    /// Number of displacement unknowns (the multipliers follow).
    np: usize,
}

const NONE: usize = usize::MAX;

/// The constrained ordering (forward permutation) of `a` whose first `np` unknowns are primal.
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
    for list in &mut coupled {
        list.sort_unstable();
        list.dedup();
        for &i in list.iter() {
            adj[i].extend_from_slice(list);
        }
    }
    for (j, list) in adj.iter_mut().enumerate() {
        list.push(j);
        list.sort_unstable();
        list.dedup();
    }
    // Unknowns with the same adjacency (the two dofs of a node) are ordered together: AMD
    // runs on the graph of these groups, about four times smaller.
    let mut group_of = vec![0usize; np];
    let mut groups: Vec<usize> = vec![]; // first unknown of each group
    for j in 0..np {
        if j > 0 && adj[j] == adj[j - 1] {
            group_of[j] = group_of[j - 1];
        } else {
            group_of[j] = groups.len();
            groups.push(j);
        }
    }
    let ng = groups.len();
    let mut col_ptr = vec![0usize];
    let mut rows = vec![];
    for &j in &groups {
        let start = rows.len();
        rows.extend(adj[j].iter().map(|&i| group_of[i]));
        rows[start..].sort_unstable();
        let mut k = start;
        for q in start..rows.len() {
            if q == start || rows[q] != rows[k - 1] {
                rows[k] = rows[q];
                k += 1;
            }
        }
        rows.truncate(k);
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

impl SaddleLdlt {
    /// Orders and analyses `a` (first `np` unknowns primal).
    pub fn new(a: &SparseMatrix, np: usize) -> Result<Self> {
        let n = a.n;
        let fwd = constrained_order(a, np)?;
        let mut inv = vec![0usize; n];
        for (i, &p) in fwd.iter().enumerate() {
            inv[p] = i;
        }
        // pattern of P A Pᵀ (lower): entry (r, c) of A goes to (inv r, inv c) if inv r ≥ inv c
        let mut cols: Vec<Vec<(usize, usize)>> = vec![vec![]; n];
        for c in 0..n {
            for p in a.col_ptr[c]..a.col_ptr[c + 1] {
                let (ir, ic) = (inv[a.row_idx[p]], inv[c]);
                if ir >= ic {
                    cols[ic].push((ir, p));
                }
            }
        }
        let mut map = vec![NONE; a.nnz()];
        let mut next = 0;
        let permuted = SparseMatrix::from_columns(
            n,
            cols.into_iter().map(|mut col| {
                col.sort_unstable();
                for &(_, p) in &col {
                    map[p] = next;
                    next += 1;
                }
                col.into_iter().map(|(r, _)| r).collect()
            }),
        );
        // With the identity ordering faer's analysis reads the upper triangle (whatever the
        // side argument), so it gets the transposed pattern; the numeric phase reads `permuted`.
        let mut upper: Vec<Vec<usize>> = vec![vec![]; n];
        for c in 0..n {
            for &r in &permuted.row_idx[permuted.col_ptr[c]..permuted.col_ptr[c + 1]] {
                upper[r].push(c);
            }
        }
        let upper = SparseMatrix::from_columns(n, upper.into_iter());
        let symbolic = factorize_symbolic_cholesky(
            upper.as_faer().symbolic(),
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
        Ok(SaddleLdlt {
            fwd,
            permuted,
            map,
            values: vec![0.0; symbolic.len_val()],
            symbolic,
            scratch,
            solve_scratch,
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
        for col in 0..a.n {
            for p in a.col_ptr[col]..a.col_ptr[col + 1] {
                let q = self.map[p];
                if q == NONE {
                    continue;
                }
                let row = a.row_idx[p];
                self.permuted.values[q] = if row < self.np && col < self.np {
                    0.5 * (a.values[p] + a.values[transpose[p]])
                } else if row <= col {
                    a.values[p]
                } else {
                    a.values[transpose[p]]
                };
            }
        }
        self.symbolic
            .factorize_numeric_ldlt(
                &mut self.values,
                self.permuted.as_faer(),
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
        let t = n + m;
        let cols = (0..t).map(|c| {
            let mut rows: Vec<usize> = entries.iter().filter(|e| e.1 == c).map(|e| e.0).collect();
            rows.sort_unstable();
            rows
        });
        let mut a = SparseMatrix::from_columns(t, cols);
        for &(r, c, v) in &entries {
            let q = a.position(r, c).unwrap();
            a.values[q] = v;
        }
        a
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
}
