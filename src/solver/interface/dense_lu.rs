//! The interface matrix's dense LU (see `mod.rs`).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor as lu_factor, solve as lu_solve};
use faer::perm::PermRef;
use faer::{Mat, Par};

/// Dense LU with partial pivoting, in place in the interface matrix. The factorisation
/// runs on the pool's threads (the blocks are done by then): faer splits the updates of
/// the trailing matrix, not the sums of any entry, so the factors are those of the
/// sequential LU bit for bit (tested), on any machine. On the 2-core machine: 1.3× faster
/// at k = 2000, 1.5× at 3000, 1.8× at 5000; the same below 1000 (sequential there).
/// Solves are sequential (one right-hand side).
pub(super) struct DenseLu {
    lu: Mat<f64>,
    /// The number of rows and columns `lu` has room for (it can hold a smaller matrix).
    pub(super) capacity: usize,
    k: usize,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
}

const DENSE_PAR: Par = Par::Seq;

/// The parallelism of dense work of order k (see `DenseLu`; the reduction's products and
/// solves too).
pub(super) fn factor_par(k: usize) -> Par {
    if k >= 1000 {
        Par::rayon(0)
    } else {
        Par::Seq
    }
}

impl Default for DenseLu {
    fn default() -> Self {
        DenseLu {
            lu: Mat::zeros(0, 0),
            capacity: 0,
            k: 0,
            perm: vec![],
            perm_inv: vec![],
        }
    }
}

impl DenseLu {
    /// A zero k × k matrix in the storage of the last factors. Storage too small is
    /// replaced by one with room for k + k/16 (at most `limit`): the number of coupled
    /// interface unknowns moves by a few with the contact statuses, and each new storage
    /// is fresh pages to fault in.
    pub(super) fn take_storage(&mut self, k: usize, limit: usize) -> Mat<f64> {
        let capacity = self.capacity;
        let mut t = std::mem::take(self).lu;
        if capacity < k {
            // (freed first: the old values are not needed)
            drop(t);
            let room = (k + k / 16).min(limit).max(k);
            self.capacity = room;
            t = Mat::zeros(room, room);
        } else {
            self.capacity = capacity;
        }
        t.resize_with(k, k, |_, _| 0.0);
        t.fill(0.0);
        t
    }

    /// Factorises `t` (square), which it takes.
    pub(super) fn factor(&mut self, t: Mat<f64>) {
        let k = t.nrows();
        self.lu = t;
        self.k = k;
        self.perm.resize(k, 0);
        self.perm_inv.resize(k, 0);
        lu_in_place(
            self.lu.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            factor_par(k),
        );
    }

    /// The smallest over the largest |pivot| (0 when there is none): how near singular.
    pub(super) fn pivot_ratio(&self) -> f64 {
        let (min, max) = (0..self.k)
            .map(|i| self.lu[(i, i)].abs())
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), d| {
                (lo.min(d), hi.max(d))
            });
        if max > 0.0 && min.is_finite() {
            min / max
        } else {
            0.0
        }
    }

    pub(super) fn solve(&self, rhs: &mut Mat<f64>) {
        self.solve_with(rhs, DENSE_PAR);
    }

    /// As `solve`, the columns of `rhs` shared by the pool's threads when they are many.
    pub(super) fn solve_many(&self, rhs: &mut Mat<f64>) {
        let par = if rhs.ncols() >= 16 {
            factor_par(self.k)
        } else {
            DENSE_PAR
        };
        self.solve_with(rhs, par);
    }

    /// As `solve`, with the parallelism `par`.
    pub(super) fn solve_with(&self, rhs: &mut Mat<f64>, par: Par) {
        let k = self.k;
        let lu = self.lu.as_ref();
        debug_assert_eq!(lu.nrows(), k);
        let perm = PermRef::new_checked(&self.perm, &self.perm_inv, k);
        let mut mem = MemBuffer::new(lu_solve::solve_in_place_scratch::<usize, f64>(
            k,
            rhs.ncols(),
            par,
        ));
        lu_solve::solve_in_place(lu, lu, perm, rhs.as_mut(), par, MemStack::new(&mut mem));
    }
}

/// LU with partial pivoting of `m` (square) in place, with `par`.
fn lu_in_place(m: faer::MatMut<'_, f64>, perm: &mut [usize], perm_inv: &mut [usize], par: Par) {
    let k = m.nrows();
    let mut mem = MemBuffer::new(lu_factor::lu_in_place_scratch::<usize, f64>(
        k,
        k,
        par,
        Default::default(),
    ));
    lu_factor::lu_in_place(
        m,
        perm,
        perm_inv,
        par,
        MemStack::new(&mut mem),
        Default::default(),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parallel_dense_lu_is_the_sequential_one_bit_for_bit() {
        // (what makes the interface solve's results independent of the machine)
        for k in [1000, 1537] {
            let a = Mat::<f64>::from_fn(k, k, |i, j| {
                let x = ((i * 7919 + j * 104_729) % 10_007) as f64 / 10_007.0 - 0.5;
                if i == j {
                    x + 0.1
                } else {
                    x / (1.0 + (i as f64 - j as f64).abs()).sqrt()
                }
            });
            let factor = |par: Par| {
                let mut m = a.clone();
                let (mut perm, mut inv) = (vec![0; k], vec![0; k]);
                lu_in_place(m.as_mut(), &mut perm, &mut inv, par);
                (m, perm)
            };
            let (seq, seq_perm) = factor(Par::Seq);
            for threads in [2, 3, 4] {
                let (par, par_perm) = factor(Par::rayon(threads));
                assert_eq!(par_perm, seq_perm, "k = {k}, {threads} threads: pivots");
                for j in 0..k {
                    let same = seq
                        .col_as_slice(j)
                        .iter()
                        .zip(par.col_as_slice(j))
                        .all(|(x, y)| x.to_bits() == y.to_bits());
                    assert!(same, "k = {k}, {threads} threads: column {j} differs");
                }
            }
        }
    }
}
