//! LDLᵀ without pivoting in a fixed order (`OrderedLdlt`), and its use for symmetric
//! saddle-point matrices [K Bᵀ; B C] (displacements, then multipliers), made safe by the
//! ordering: AMD on the displacement graph in which each multiplier's coupled
//! displacements form a clique, then every multiplier placed right after the last of its
//! coupled displacements. With K positive definite each multiplier pivot is then a
//! (negative) Schur complement, never zero (shared/design/dependencies.md).
//!
//! | file | what |
//! |---|---|
//! | `mod.rs` | the constrained ordering and `SaddleLdlt` |
//! | `ordered.rs` | `OrderedLdlt`: analysis, factorisation, solves; AMD orders |
//! | `ordered/passes.rs` | the supernodal passes (L⁻¹, L⁻ᵀ), subtrees on both cores |
//! | `ordered/numeric.rs` | the numeric factorisation, subtrees on both cores |
//! | `ordered/forest.rs` | the supernodes' elimination tree both are cut along |

mod ordered;

pub use ordered::{leading_order, OrderedLdlt};

use crate::assembly::matrix::SparseMatrix;
use crate::error::Result;
use ordered::grouped_amd;

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
    use faer::Mat;

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
