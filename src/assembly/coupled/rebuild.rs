//! A contact pattern change: the pattern merged in place, the solid values and the
//! assembler's scatter moved with their entries (see `CoupledMatrix::rebuild`).

use super::{too_large, CoupledMatrix};
use crate::assembly::matrix::SparseMatrix;
use crate::error::{Error, Result};

impl CoupledMatrix {
    /// The pattern: the last one (the solid's at first), the contributed entries and
    /// their transposes (structurally symmetric, as the saddle-point LDLᵀ of the symmetric
    /// part needs), and the diagonal. It only grows, so it is rebuilt in place: each
    /// column's new length counted first, then the columns merged from the last entry
    /// backwards, every entry moving to a position at or after its own: no second copy of
    /// the matrix (SSNP154 D point-to-segment at 93k unknowns: heap peak 634 MB with a new
    /// pattern and values beside the old ones, 612 MB in place). The values (the solid
    /// ones alone, zero elsewhere) move with their entries, and the assembler's scatter
    /// with them.
    pub(super) fn rebuild(
        &mut self,
        m: &mut SparseMatrix,
        cell_scatter: &mut [u32],
        reserved: u32,
        n: usize,
        contributed: impl Iterator<Item = (usize, usize)> + Clone,
    ) -> Result<()> {
        if n < m.n {
            return Err(Error::solve(format!(
                "internal: the contact unknowns went from {} to {}",
                m.n, n
            )));
        }
        // (by column: a row index each, where (column, row) pairs took twice the room)
        let (extra_ptr, extra) =
            sorted_unique_columns(n, contributed.flat_map(|(c, r)| [(c, r), (r, c)]));
        let old_n = m.n;
        let old_rows = |c: usize| {
            if c < old_n {
                m.col_ptr[c]..m.col_ptr[c + 1]
            } else {
                0..0
            }
        };
        // each column's length: its old rows, its contributed rows and its diagonal, merged
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0usize);
        for c in 0..n {
            let (old, new) = (
                &m.row_idx[old_rows(c)],
                &extra[extra_ptr[c]..extra_ptr[c + 1]],
            );
            let (mut i, mut j, mut len) = (0, 0, 0);
            let mut diagonal = true;
            loop {
                let ro = old.get(i).copied().unwrap_or(usize::MAX);
                let rx = new.get(j).copied().unwrap_or(usize::MAX);
                let rd = if diagonal { c } else { usize::MAX };
                let r = ro.min(rx).min(rd);
                if r == usize::MAX {
                    break;
                }
                i += usize::from(ro == r);
                j += usize::from(rx == r);
                diagonal &= rd != r;
                len += 1;
            }
            col_ptr.push(col_ptr[c] + len);
        }
        let nnz = col_ptr[n];
        if nnz >= reserved as usize {
            return Err(too_large());
        }
        // new position of each old entry
        let old_nnz = m.nnz();
        let mut moved = vec![0u32; old_nnz];
        // Room for as many contact entries again: a contact zone that grows by a few
        // segments per iteration then grows the arrays in place, where each reallocation
        // copied both and left their old blocks to the allocator (SSNP154 D
        // point-to-segment at 93k unknowns: a rebuild that added 15k entries took 63 MB
        // more resident memory, 16 MB with the room). (Not `resize` alone: it would
        // double them.)
        if m.row_idx.capacity() < nnz {
            let solid = old_nnz - self.non_solid.len();
            let room = nnz - old_nnz + (nnz - solid);
            m.row_idx.reserve_exact(room);
            m.values.reserve_exact(room);
        }
        m.row_idx.resize(nnz, 0);
        m.values.resize(nnz, 0.0);
        let mut non_solid = vec![];
        // the old non-solid positions not above the next old entry read (they are read in
        // decreasing order)
        let mut below = self.non_solid.len();
        for c in (0..n).rev() {
            let rows = old_rows(c);
            let (mut i, mut j) = (rows.end, extra_ptr[c + 1]);
            let mut w = col_ptr[c + 1];
            let mut diagonal = true;
            // (largest row first; an old entry is read before its position is written)
            loop {
                let ro = if i > rows.start {
                    m.row_idx[i - 1]
                } else {
                    NO_ROW
                };
                let rx = if j > extra_ptr[c] {
                    extra[j - 1]
                } else {
                    NO_ROW
                };
                let rd = if diagonal { c } else { NO_ROW };
                let r = [ro, rx, rd].into_iter().filter(|&r| r != NO_ROW).max();
                let Some(r) = r else { break };
                w -= 1;
                if ro == r {
                    i -= 1;
                    let v = m.values[i];
                    moved[i] = w as u32;
                    while below > 0 && self.non_solid[below - 1] > i {
                        below -= 1;
                    }
                    if below > 0 && self.non_solid[below - 1] == i {
                        non_solid.push(w);
                    }
                    m.values[w] = v;
                } else {
                    non_solid.push(w);
                    m.values[w] = 0.0;
                }
                m.row_idx[w] = r;
                if rx == r {
                    j -= 1;
                }
                if rd == r {
                    diagonal = false;
                }
            }
        }
        for s in cell_scatter.iter_mut().filter(|s| **s < reserved) {
            *s = moved[*s as usize];
        }
        non_solid.reverse();
        m.n = n;
        m.col_ptr = col_ptr;
        m.pattern_stamp = crate::assembly::matrix::new_pattern_stamp();
        self.non_solid = non_solid;
        self.n = n;
        self.rebuilds += 1;
        Ok(())
    }
}

/// No row (the merges' end marker; rows are below it).
const NO_ROW: usize = usize::MAX;

/// The distinct (column, row) pairs (both < n) by column: each column's rows are
/// `rows[ptr[c]..ptr[c + 1]]`, increasing. Bucketed by column (counting), then each
/// column's rows sorted and deduplicated in place.
pub(super) fn sorted_unique_columns(
    n: usize,
    pairs: impl Iterator<Item = (usize, usize)> + Clone,
) -> (Vec<usize>, Vec<usize>) {
    let (mut ptr, mut rows) = crate::assembly::matrix::group_by_key(n, pairs);
    let mut w = 0;
    for c in 0..n {
        let (start, end) = (ptr[c], ptr[c + 1]);
        rows[start..end].sort_unstable();
        ptr[c] = w;
        let mut last = usize::MAX;
        for q in start..end {
            let r = rows[q];
            if r != last {
                rows[w] = r;
                w += 1;
                last = r;
            }
        }
    }
    ptr[n] = w;
    rows.truncate(w);
    (ptr, rows)
}
