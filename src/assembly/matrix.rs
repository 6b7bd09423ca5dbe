//! Sparse matrix over the free unknowns, stored by columns (CSC) with the full pattern
//! (both triangles: the same storage serves Cholesky, which reads the lower half, and LU).
//! The pattern is built once; assembly refills `values`.

use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};

#[derive(Clone, Debug, Default)]
pub struct SparseMatrix {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    pub values: Vec<f64>,
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
        for c in 0..self.n {
            for p in self.col_ptr[c]..self.col_ptr[c + 1] {
                y[self.row_idx[p]] += self.values[p] * x[c];
            }
        }
    }

    pub fn as_faer(&self) -> SparseColMatRef<'_, usize, f64> {
        // SAFETY-free construction: the checked constructor validates the pattern once.
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
