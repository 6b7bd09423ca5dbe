//! LDLᵀ of symmetric saddle-point matrices [K Bᵀ; B C] (displacements, then multipliers)
//! without pivoting, made safe by the ordering: AMD on the displacement graph in which each
//! multiplier's coupled displacements form a clique, then every multiplier placed right
//! after the last of its coupled displacements. With K positive definite each multiplier
//! pivot is then a (negative) Schur complement, never zero (shared/design/dependencies.md).

use crate::assembly::matrix::SparseMatrix;
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SymbolicSparseColMatRef;
use faer::{Conj, MatMut, Par, Side};

pub struct SaddleLdlt {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
}

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
    let mut col_ptr = vec![0usize];
    let mut rows = vec![];
    for (j, list) in adj.iter_mut().enumerate() {
        list.push(j);
        list.sort_unstable();
        list.dedup();
        rows.extend_from_slice(list);
        col_ptr.push(rows.len());
    }
    let sym = SymbolicSparseColMatRef::new_checked(np, np, &col_ptr, None, &rows);
    let mut perm = vec![0usize; np];
    let mut perm_inv = vec![0usize; np];
    let mut mem = MemBuffer::new(amd::order_scratch::<usize>(np, rows.len()));
    amd::order(
        &mut perm,
        &mut perm_inv,
        sym,
        amd::Control::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| Error::solve(format!("ordering failed: {e:?}")))?;
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
    pub fn symbolic(a: &SparseMatrix, np: usize) -> Result<SymbolicCholesky<usize>> {
        let fwd = constrained_order(a, np)?;
        let mut inv = vec![0usize; fwd.len()];
        for (i, &p) in fwd.iter().enumerate() {
            inv[p] = i;
        }
        let perm = PermRef::new_checked(&fwd, &inv, a.n);
        factorize_symbolic_cholesky(
            a.as_faer().symbolic(),
            Side::Lower,
            SymmetricOrdering::Custom(perm),
            // The simplicial kernel is several times slower at these sizes.
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|e| Error::solve(format!("symbolic LDLT failed: {e:?}")))
    }

    pub fn numeric(symbolic: SymbolicCholesky<usize>, a: &SparseMatrix) -> Result<Self> {
        let mut values = vec![0.0; symbolic.len_val()];
        let mut mem = MemBuffer::new(
            symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
        );
        symbolic
            .factorize_numeric_ldlt(
                &mut values,
                a.as_faer(),
                Side::Lower,
                Default::default(),
                Par::Seq,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| {
                Error::solve(format!(
                    "the system matrix is singular ({e:?}): a body may be free (not held by supports or \
                     contact)"
                ))
            })?;
        Ok(SaddleLdlt { symbolic, values })
    }

    pub fn into_symbolic(self) -> SymbolicCholesky<usize> {
        self.symbolic
    }

    pub fn solve(&self, b: &mut [f64]) {
        let n = b.len();
        let ldlt = LdltRef::new(&self.symbolic, &self.values);
        let mut mem = MemBuffer::new(self.symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        ldlt.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(b, n, 1),
            Par::Seq,
            MemStack::new(&mut mem),
        );
    }
}
