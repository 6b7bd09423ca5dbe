//! The LU of the reduction's live matrix (`reduced.rs`), its decoupled unknowns apart.
//! The live part keeps the multipliers of open points next to the contact zone (so that
//! one that closes changes the live part only); their rows and columns then hold the
//! diagonal alone, and each is solved by itself, as the whole interface's are in
//! `InterfaceSolver::factor`. The dense LU, l³, gets the others only (SSNP154 D
//! point-to-segment at 93k unknowns: 206 of the 834 live unknowns at the first step's
//! start, 45–170 of 736–1204 later; the LU's flops fall to 0.42–0.75 of the whole's).

use super::dense_lu::DenseLu;
use faer::Mat;

#[derive(Default)]
pub(super) struct LiveLu {
    lu: DenseLu,
    /// the live unknowns in the LU (all when none is decoupled: then empty)
    coupled: Vec<usize>,
    /// the decoupled ones, by their diagonal
    decoupled: Vec<(usize, f64)>,
}

impl LiveLu {
    /// A zero l × l matrix in the storage of the last factors (`DenseLu::take_storage`).
    pub(super) fn take_storage(&mut self, l: usize) -> Mat<f64> {
        self.lu.take_storage(l, l)
    }

    /// Factorises `m` (square), which it takes: its decoupled unknowns (a nonzero diagonal
    /// alone in their row and column) apart, the LU of the others made in place.
    pub(super) fn factor(&mut self, mut m: Mat<f64>) {
        let l = m.nrows();
        // off-diagonal nonzeros by row and by column, in one pass over the columns
        let mut linked = vec![false; l];
        for j in 0..l {
            for (i, &v) in m.col_as_slice(j).iter().enumerate() {
                if i != j && v != 0.0 {
                    linked[i] = true;
                    linked[j] = true;
                }
            }
        }
        self.coupled.clear();
        self.decoupled.clear();
        for (i, &link) in linked.iter().enumerate() {
            if !link && m[(i, i)] != 0.0 {
                self.decoupled.push((i, m[(i, i)]));
            } else {
                self.coupled.push(i);
            }
        }
        if self.decoupled.is_empty() {
            self.coupled.clear();
            self.lu.factor(m);
            return;
        }
        // The coupled rows and columns moved to the leading c × c block in place: entry
        // (i, j) goes to (i', j') with i' ≤ i and j' ≤ j, so visiting the sources by
        // column, then row, never overwrites one not yet read.
        let c = self.coupled.len();
        for (jn, &j) in self.coupled.iter().enumerate() {
            for (inew, &i) in self.coupled.iter().enumerate() {
                m[(inew, jn)] = m[(i, j)];
            }
        }
        m.resize_with(c, c, |_, _| 0.0);
        self.lu.factor(m);
    }

    /// Solves in place for the columns of `rhs` (rows: the live unknowns), shared by the
    /// pool's threads when they are many (`DenseLu::solve_many`).
    pub(super) fn solve(&self, rhs: &mut Mat<f64>) {
        if self.decoupled.is_empty() {
            self.lu.solve_many(rhs);
            return;
        }
        let nc = rhs.ncols();
        for &(i, d) in &self.decoupled {
            for j in 0..nc {
                rhs[(i, j)] /= d;
            }
        }
        if self.coupled.is_empty() {
            return;
        }
        let mut part = Mat::from_fn(self.coupled.len(), nc, |r, j| rhs[(self.coupled[r], j)]);
        self.lu.solve_many(&mut part);
        for (r, &i) in self.coupled.iter().enumerate() {
            for j in 0..nc {
                rhs[(i, j)] = part[(r, j)];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::LiveLu;
    use faer::Mat;

    /// max |A x − b| over the columns of b.
    fn residual(a: &Mat<f64>, x: &Mat<f64>, b: &Mat<f64>) -> f64 {
        let r = a * x - b;
        (0..r.nrows())
            .flat_map(|i| (0..r.ncols()).map(move |j| (i, j)))
            .fold(0.0f64, |m, (i, j)| m.max(r[(i, j)].abs()))
    }

    /// A non-symmetric matrix whose unknowns 1, 4 and 6 are decoupled (diagonal alone),
    /// 3 has a zero diagonal (a closed point's multiplier: coupled), and 5 a zero row but
    /// for an entry in its column (coupled).
    fn matrix(n: usize) -> Mat<f64> {
        let decoupled = |i: usize| [1, 4, 6].contains(&i);
        Mat::from_fn(n, n, |i, j| {
            if i == j {
                return if i == 3 { 0.0 } else { 3.0 + i as f64 };
            }
            if decoupled(i) || decoupled(j) || i == 5 {
                return 0.0;
            }
            0.4 / (1.0 + i as f64 + 2.0 * j as f64) - 0.05 * (i as f64 - j as f64)
        })
    }

    #[test]
    fn decoupled_unknowns_are_solved_apart_and_the_rest_by_lu() {
        let n = 8;
        let a = matrix(n);
        let mut lu = LiveLu::default();
        let mut m = lu.take_storage(n);
        m.copy_from(&a);
        lu.factor(m);
        assert_eq!(
            lu.decoupled.iter().map(|d| d.0).collect::<Vec<_>>(),
            vec![1, 4, 6]
        );
        assert_eq!(lu.coupled, vec![0, 2, 3, 5, 7]);
        // (20 columns: shared by the pool's threads)
        for c in [1, 3, 20] {
            let b = Mat::from_fn(n, c, |i, j| (0.7 * i as f64 + j as f64).cos());
            let mut x = b.clone();
            lu.solve(&mut x);
            let res = residual(&a, &x, &b);
            assert!(res < 1e-14, "{c} right-hand sides: residual {res}");
        }
        // refactorised in the same storage, with every unknown coupled
        let full = Mat::from_fn(n, n, |i, j| {
            if i == j {
                4.0
            } else {
                0.1 * (i + 2 * j) as f64 / n as f64
            }
        });
        let mut m = lu.take_storage(n);
        m.copy_from(&full);
        lu.factor(m);
        assert!(lu.decoupled.is_empty() && lu.coupled.is_empty());
        let b = Mat::from_fn(n, 1, |i, _| i as f64 - 2.5);
        let mut x = b.clone();
        lu.solve(&mut x);
        let res = residual(&full, &x, &b);
        assert!(res < 1e-14, "residual {res}");
    }

    #[test]
    fn a_live_matrix_of_decoupled_unknowns_alone_is_solved_by_its_diagonal() {
        let a = Mat::from_fn(3, 3, |i, j| if i == j { 2.0 + i as f64 } else { 0.0 });
        let mut lu = LiveLu::default();
        let mut m = lu.take_storage(3);
        m.copy_from(&a);
        lu.factor(m);
        let mut x = Mat::from_fn(3, 1, |i, _| 1.0 + i as f64);
        lu.solve(&mut x);
        for i in 0..3 {
            assert_eq!(x[(i, 0)], (1.0 + i as f64) / (2.0 + i as f64));
        }
    }
}
