//! Sparse matrix over the free unknowns, stored by columns (CSC) with the full pattern
//! (both triangles: the same storage serves Cholesky, which reads the lower half, and LU).
//! The pattern is built once; assembly refills `values`.

use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};

/// Items grouped by their key in 0..n, in their order within each key (a counting sort):
/// the start of each key's run (n + 1 entries, as a column pointer) and the items. The
/// iterator is walked twice (counting, then filling).
pub fn group_by_key<T: Copy + Default>(
    n: usize,
    items: impl Iterator<Item = (usize, T)> + Clone,
) -> (Vec<usize>, Vec<T>) {
    let mut start = vec![0usize; n + 1];
    for (k, _) in items.clone() {
        start[k + 1] += 1;
    }
    for k in 0..n {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut grouped = vec![T::default(); start[n]];
    for (k, v) in items {
        grouped[fill[k]] = v;
        fill[k] += 1;
    }
    (start, grouped)
}

#[derive(Clone, Debug, Default)]
pub struct SparseMatrix {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    pub values: Vec<f64>,
    /// Nonzero: an identity of the pattern (`col_ptr`, `row_idx`) from `new_pattern_stamp`,
    /// so that a solver can tell an unchanged pattern without comparing it. Code that
    /// changes the pattern must give it a new stamp (or 0: unknown, compared).
    pub pattern_stamp: u64,
}

/// A stamp no pattern had before (see `SparseMatrix::pattern_stamp`).
pub fn new_pattern_stamp() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

impl SparseMatrix {
    /// Builds the pattern from, for each column, its sorted unique row indices.
    pub fn from_columns(n: usize, columns: impl Iterator<Item = Vec<usize>>) -> Self {
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx = vec![];
        for col in columns {
            row_idx.extend_from_slice(&col);
            col_ptr.push(row_idx.len());
        }
        assert_eq!(col_ptr.len(), n + 1);
        let nnz = row_idx.len();
        SparseMatrix {
            n,
            col_ptr,
            row_idx,
            values: vec![0.0; nnz],
            pattern_stamp: 0,
        }
    }

    /// The n × n matrix of the given (row, column, value) entries, repeated ones summed.
    pub fn from_entries(n: usize, entries: &[(usize, usize, f64)]) -> Self {
        let mut cols: Vec<Vec<usize>> = vec![vec![]; n];
        for &(r, c, _) in entries {
            cols[c].push(r);
        }
        for rows in &mut cols {
            rows.sort_unstable();
            rows.dedup();
        }
        let mut a = SparseMatrix::from_columns(n, cols.into_iter());
        for &(r, c, v) in entries {
            let q = a.position(r, c).expect("entry in the pattern");
            a.values[q] += v;
        }
        a
    }

    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Position of entry (row, col) in `values`, if it is in the pattern.
    pub fn position(&self, row: usize, col: usize) -> Option<usize> {
        let range = self.col_ptr[col]..self.col_ptr[col + 1];
        self.row_idx[range.clone()]
            .binary_search(&row)
            .ok()
            .map(|p| range.start + p)
    }

    /// y = A x (for a matrix storing both triangles)
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        self.add_columns_times(0..self.n, x, y);
    }

    /// y = A x on two threads when A is large: each half of the columns into its own
    /// vector, then summed.
    pub fn mul_vec_par(&self, x: &[f64], y: &mut [f64]) {
        if self.nnz() < 100_000 {
            return self.mul_vec(x, y);
        }
        let mid = self.n / 2;
        y.fill(0.0);
        let mut y2 = vec![0.0; y.len()];
        rayon::join(
            || self.add_columns_times(0..mid, x, y),
            || self.add_columns_times(mid..self.n, x, &mut y2),
        );
        for (a, b) in y.iter_mut().zip(&y2) {
            *a += b;
        }
    }

    /// y += A[:, columns] x[columns].
    fn add_columns_times(&self, columns: std::ops::Range<usize>, x: &[f64], y: &mut [f64]) {
        for c in columns {
            for p in self.col_ptr[c]..self.col_ptr[c + 1] {
                y[self.row_idx[p]] += self.values[p] * x[c];
            }
        }
    }

    /// faer's view of the matrix; the checked constructor validates the pattern (a pass
    /// over it) at each call, so hot loops keep a checked pattern of their own.
    pub fn as_faer(&self) -> SparseColMatRef<'_, usize, f64> {
        let sym = SymbolicSparseColMatRef::new_checked(
            self.n,
            self.n,
            &self.col_ptr,
            None,
            &self.row_idx,
        );
        SparseColMatRef::new(sym, &self.values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn group_by_key_keeps_the_order_within_each_key() {
        let items = [(2, 'a'), (0, 'b'), (2, 'c'), (1, 'd'), (0, 'e')];
        let (start, grouped) = group_by_key(4, items.iter().copied());
        assert_eq!(start, vec![0, 2, 3, 5, 5]);
        assert_eq!(grouped, vec!['b', 'e', 'd', 'a', 'c']);
    }

    #[test]
    fn two_thread_product_equals_the_serial_one() {
        // a banded non-symmetric matrix large enough for the two-thread path
        let n: usize = 20_000;
        let cols = (0..n).map(|c| (c.saturating_sub(3)..(c + 4).min(n)).collect());
        let mut a = SparseMatrix::from_columns(n, cols);
        for c in 0..n {
            for p in a.col_ptr[c]..a.col_ptr[c + 1] {
                a.values[p] = ((7 * a.row_idx[p] + 3 * c) % 11) as f64 - 5.0;
            }
        }
        assert!(a.nnz() >= 100_000);
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let (mut y1, mut y2) = (vec![1.0; n], vec![2.0; n]);
        a.mul_vec(&x, &mut y1);
        a.mul_vec_par(&x, &mut y2);
        for (u, v) in y1.iter().zip(&y2) {
            // at most two partial sums per entry: equal to round-off
            assert!((u - v).abs() <= 1e-13 * u.abs().max(1.0), "{u} vs {v}");
        }
    }
}
