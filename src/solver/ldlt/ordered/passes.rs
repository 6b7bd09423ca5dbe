//! The factor's triangular passes (y ← L⁻¹ y, y ← L⁻ᵀ y) over its supernodes, with the
//! independent subtrees of the elimination tree on both cores. When one body dominates the
//! contact solve (SSNP154's base block: 883k of 960k unknowns), its passes alone set the
//! time of every solve while the other core idles; faer's solve is sequential.
//!
//! The split (`Split::new`): the largest subtrees are cut at their roots, which go to a
//! "top" part, until each remaining subtree holds at most 1/PIECES of the factor's entries.
//! Each subtree is a contiguous range of supernodes and columns (the supernodes are in a
//! postorder of the tree where the ordering gives one; a subtree that is not contiguous is
//! cut further), its ancestors all in the top part and after it.
//!
//! The results are those of the sequential passes bit for bit:
//! - forward: the subtrees run in parallel; an update of a row outside its subtree (a top
//!   row) is recorded, then the top supernodes run in order and each subtree's recorded
//!   updates are subtracted where the subtree stands in that order: every row receives the
//!   same subtractions in the same order as sequentially.
//! - backward: the top supernodes run first (in reverse; their rows are top rows), then the
//!   subtrees in parallel, each reading its own values and the top's final ones.

use super::forest::Forest;
use super::{dot, OrderedLdlt};
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
use rayon::prelude::*;
use std::collections::BinaryHeap;

/// No subtree holds more than 1/PIECES of the entries (work-stealing then balances the
/// two cores).
const PIECES: usize = 8;
/// Factors with fewer entries are passed sequentially (a pass then takes well under a
/// millisecond).
const MIN_PARALLEL_ENTRIES: usize = 1 << 20;

/// One subtree: its supernodes `first..last` and columns `lo..hi`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Subtree {
    first: usize,
    last: usize,
    lo: usize,
    hi: usize,
}

/// The subtrees passed in parallel (sorted by column), the rest of the supernodes being
/// the top part.
#[derive(Default)]
pub(super) struct Split {
    subtrees: Vec<Subtree>,
}

impl Split {
    /// No subtrees: the passes (and the factorisation) run in sequence.
    pub(super) fn is_empty(&self) -> bool {
        self.subtrees.is_empty()
    }

    /// From the supernodes' column ranges (`begin[s]..end[s]`, increasing), their rows
    /// below the diagonal block (`rows(s)`) and their numbers of entries.
    pub(super) fn new<'r>(
        begin: &[usize],
        end: &[usize],
        rows: impl Fn(usize) -> &'r [usize],
        entries: &[usize],
    ) -> Split {
        let ns = begin.len();
        let total: usize = entries.iter().sum();
        if ns < 2 || total < MIN_PARALLEL_ENTRIES {
            return Split::default();
        }
        let tree = Forest::new(begin, end, &rows, entries);
        let Forest {
            node_of,
            parent,
            children,
            first,
            work,
            ..
        } = &tree;
        let contiguous = |s: usize| tree.contiguous(s);
        let limit = total / PIECES;
        let mut heap: BinaryHeap<(usize, usize)> = (0..ns)
            .filter(|&s| parent[s].is_none())
            .map(|s| (work[s], s))
            .collect();
        let mut pieces = vec![];
        while let Some((w, s)) = heap.pop() {
            if (w <= limit && contiguous(s)) || (children[s].is_empty()) {
                pieces.push(s);
            } else {
                heap.extend(children[s].iter().map(|&c| (work[c], c)));
            }
        }
        let mut subtrees: Vec<Subtree> = pieces
            .into_iter()
            .filter(|&s| contiguous(s))
            .map(|s| Subtree {
                first: first[s],
                last: s + 1,
                lo: begin[first[s]],
                hi: end[s],
            })
            .collect();
        subtrees.sort_by_key(|t| t.first);
        // Each subtree must be independent of the rest: no supernode outside it has a row
        // among its columns (the factor's structure gives that; checked, as the passes'
        // results rest on it). Otherwise the passes stay sequential.
        let mut subtree_of = vec![usize::MAX; ns];
        for (i, t) in subtrees.iter().enumerate() {
            subtree_of[t.first..t.last].fill(i);
        }
        let independent = (0..ns).all(|s| {
            rows(s).iter().all(|&r| {
                let owner = subtree_of[node_of[r]];
                owner == usize::MAX || owner == subtree_of[s]
            })
        });
        if !independent {
            return Split::default();
        }
        // (worth it only when the subtrees hold most of the work)
        let parallel: usize = subtrees.iter().map(|t| work[t.last - 1]).sum();
        if subtrees.len() < 2 || 2 * parallel < total {
            return Split::default();
        }
        Split { subtrees }
    }
}

impl OrderedLdlt {
    /// The split of this factor's supernodes (see `Split::new`).
    pub(super) fn split_of(&self) -> Split {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            unreachable!("the analysis forces the supernodal kernel")
        };
        let ns = sym.n_supernodes();
        let (begin, end) = (&sym.supernode_begin()[..ns], &sym.supernode_end()[..ns]);
        let rows = |s: usize| self.supernode(s).2;
        let entries: Vec<usize> = (0..ns)
            .map(|s| sym.col_ptr_for_val()[s + 1] - sym.col_ptr_for_val()[s])
            .collect();
        Split::new(begin, end, rows, &entries)
    }

    /// y ← L⁻¹ y, y in the factorised order.
    pub fn forward(&self, y: &mut [f64]) {
        let n = y.len();
        let subtrees = &self.split.subtrees;
        let mut tmp = vec![];
        if subtrees.is_empty() {
            for s in 0..self.n_supernodes() {
                self.forward_node(s, y, 0, n, &mut tmp, &mut vec![]);
            }
            return;
        }
        // the subtrees in parallel, their updates of top rows recorded
        let recorded: Vec<Vec<f64>> = pieces(y, subtrees)
            .into_par_iter()
            .zip(subtrees)
            .map(|(piece, t)| {
                let (mut tmp, mut out) = (vec![], vec![]);
                for s in t.first..t.last {
                    self.forward_node(s, piece, t.lo, t.hi, &mut tmp, &mut out);
                }
                out
            })
            .collect();
        // the top supernodes in order, each subtree's updates where it stands
        let mut s = 0;
        let mut next = 0;
        while s < self.n_supernodes() {
            if next < subtrees.len() && subtrees[next].first == s {
                let t = subtrees[next];
                let mut k = 0;
                for q in t.first..t.last {
                    for &r in self.supernode(q).2.iter().filter(|&&r| r >= t.hi) {
                        y[r] -= recorded[next][k];
                        k += 1;
                    }
                }
                s = t.last;
                next += 1;
            } else {
                self.forward_node(s, y, 0, n, &mut tmp, &mut vec![]);
                s += 1;
            }
        }
    }

    /// Supernode s of the forward pass on `y`, the columns `lo..hi` (`y[0]` is column lo);
    /// the updates of rows from `hi` on are pushed to `out` (in the supernode's row order).
    fn forward_node(
        &self,
        s: usize,
        y: &mut [f64],
        lo: usize,
        hi: usize,
        tmp: &mut Vec<f64>,
        out: &mut Vec<f64>,
    ) {
        let (begin, end, rows, vals) = self.supernode(s);
        let (c, ld) = (end - begin, end - begin + rows.len());
        let yb = &mut y[begin - lo..end - lo];
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
            let xj = y[begin - lo + j];
            let col = &vals[j * ld + c..(j + 1) * ld];
            for (t, l) in tmp.iter_mut().zip(col) {
                *t += l * xj;
            }
        }
        for (&r, &t) in rows.iter().zip(tmp.iter()) {
            if r < hi {
                y[r - lo] -= t;
            } else {
                out.push(t);
            }
        }
    }

    /// y ← L⁻ᵀ y, y in the factorised order.
    pub fn backward(&self, y: &mut [f64]) {
        let n = y.len();
        let subtrees = &self.split.subtrees;
        let mut tmp = vec![];
        let ns = self.n_supernodes();
        if subtrees.is_empty() {
            for s in (0..ns).rev() {
                self.backward_node(s, y, 0, n, &[], &mut tmp);
            }
            return;
        }
        // the top supernodes (their rows are top rows), then the subtrees in parallel
        let mut in_subtree = vec![false; ns];
        for t in subtrees {
            in_subtree[t.first..t.last].fill(true);
        }
        for s in (0..ns).rev().filter(|&s| !in_subtree[s]) {
            self.backward_node(s, y, 0, n, &[], &mut tmp);
        }
        let top = y.to_vec();
        pieces(y, subtrees)
            .into_par_iter()
            .zip(subtrees)
            .for_each(|(piece, t)| {
                let mut tmp = vec![];
                for s in (t.first..t.last).rev() {
                    self.backward_node(s, piece, t.lo, t.hi, &top, &mut tmp);
                }
            });
    }

    /// Supernode s of the backward pass on `y`, the columns `lo..hi` (`y[0]` is column lo);
    /// rows from `hi` on are read from `top`.
    fn backward_node(
        &self,
        s: usize,
        y: &mut [f64],
        lo: usize,
        hi: usize,
        top: &[f64],
        tmp: &mut Vec<f64>,
    ) {
        let (begin, end, rows, vals) = self.supernode(s);
        let (c, ld) = (end - begin, end - begin + rows.len());
        tmp.clear();
        tmp.extend(
            rows.iter()
                .map(|&r| if r < hi { y[r - lo] } else { top[r] }),
        );
        for j in 0..c {
            y[begin - lo + j] -= dot(&vals[j * ld + c..(j + 1) * ld], tmp);
        }
        let yb = &mut y[begin - lo..end - lo];
        for j in (0..c).rev() {
            let below = dot(&vals[j * ld + j + 1..j * ld + c], &yb[j + 1..]);
            yb[j] -= below;
        }
    }
}

/// The disjoint pieces of `y` that are the subtrees' columns (sorted, disjoint).
fn pieces<'a>(y: &'a mut [f64], subtrees: &[Subtree]) -> Vec<&'a mut [f64]> {
    let mut out = Vec::with_capacity(subtrees.len());
    let mut rest = y;
    let mut at = 0;
    for t in subtrees {
        let (_, tail) = rest.split_at_mut(t.lo - at);
        let (piece, tail) = tail.split_at_mut(t.hi - t.lo);
        out.push(piece);
        rest = tail;
        at = t.hi;
    }
    out
}

#[cfg(test)]
pub(super) mod tests {
    use super::super::{leading_order, OrderedLdlt};
    use super::{Split, Subtree};
    use crate::assembly::matrix::SparseMatrix;

    /// The supernodes of a complete binary tree of the given height in postorder, one
    /// column each: (first row below the diagonal per supernode, its parent's column).
    fn binary_tree(height: u32) -> Vec<Option<usize>> {
        fn build(lo: usize, height: u32, parent: Option<usize>, out: &mut Vec<Option<usize>>) {
            let size = (1usize << (height + 1)) - 1;
            let root = lo + size - 1;
            if height > 0 {
                let half = (size - 1) / 2;
                build(lo, height - 1, Some(root), out);
                build(lo + half, height - 1, Some(root), out);
            }
            out[root] = parent;
        }
        let mut out = vec![None; (1 << (height + 1)) - 1];
        build(0, height, None, &mut out);
        out
    }

    /// Each supernode's rows: its parent's column alone.
    fn as_rows(first_row: &[Option<usize>]) -> Vec<Vec<usize>> {
        first_row
            .iter()
            .map(|r| r.iter().copied().collect())
            .collect()
    }

    #[test]
    fn a_tree_is_cut_into_contiguous_subtrees_below_its_top() {
        // 16 leaves of 2^16 entries under 15 nodes of one: each subtree of two leaves and
        // their parent holds an eighth of the entries
        let first_row = binary_tree(4);
        let ns = first_row.len();
        let (begin, end): (Vec<usize>, Vec<usize>) = (0..ns).map(|s| (s, s + 1)).unzip();
        let leaf = |s: usize| first_row.iter().all(|&r| r != Some(s));
        let entries: Vec<usize> = (0..ns).map(|s| if leaf(s) { 1 << 16 } else { 1 }).collect();
        let rows = as_rows(&first_row);
        let split = Split::new(&begin, &end, |s| &rows[s], &entries);
        assert_eq!(split.subtrees.len(), 8, "{:?}", split.subtrees);
        for (i, t) in split.subtrees.iter().enumerate() {
            // two leaves, then their parent
            assert_eq!(t.last - t.first, 3, "{t:?}");
            assert!(leaf(t.first) && leaf(t.first + 1) && !leaf(t.first + 2));
            assert_eq!((t.lo, t.hi), (t.first, t.last));
            assert!(i == 0 || split.subtrees[i - 1].last <= t.first);
        }
        // a factor too small is passed sequentially
        let small = Split::new(&begin, &end, |s| &rows[s], &vec![1; ns]);
        assert_eq!(small.subtrees, Vec::<Subtree>::new());
        // a subtree out of postorder is cut further: leaves 0 and 2 under 3, 1 and 3 under
        // the root 4 (the subtree of 3 is not contiguous)
        let first_row = vec![Some(3), Some(4), Some(3), Some(4), None];
        let (begin, end): (Vec<usize>, Vec<usize>) = (0..5).map(|s| (s, s + 1)).unzip();
        let entries = vec![1, 1 << 20, 1, 1, 1];
        let rows = as_rows(&first_row);
        let split = Split::new(&begin, &end, |s| &rows[s], &entries);
        let single: Vec<(usize, usize)> =
            split.subtrees.iter().map(|t| (t.first, t.last)).collect();
        assert_eq!(single, vec![(0, 1), (1, 2), (2, 3)]);
        // a supernode with a row in another subtree's columns (not the structure of a
        // factor): the passes stay sequential
        let first_row = binary_tree(4);
        let (begin, end): (Vec<usize>, Vec<usize>) = (0..ns).map(|s| (s, s + 1)).unzip();
        let mut rows = as_rows(&first_row);
        let entries: Vec<usize> = (0..ns).map(|s| if leaf(s) { 1 << 16 } else { 1 }).collect();
        rows[0].push(5);
        let split = Split::new(&begin, &end, |s| &rows[s], &entries);
        assert_eq!(split.subtrees, Vec::<Subtree>::new());
    }

    /// A 5-point Laplacian on an m × m grid plus a shift (symmetric positive definite).
    pub(in crate::solver::ldlt) fn grid(m: usize) -> SparseMatrix {
        let mut entries = vec![];
        let id = |i: usize, j: usize| i * m + j;
        for i in 0..m {
            for j in 0..m {
                entries.push((id(i, j), id(i, j), 4.1));
                if i + 1 < m {
                    entries.push((id(i, j), id(i + 1, j), -1.0));
                    entries.push((id(i + 1, j), id(i, j), -1.0));
                }
                if j + 1 < m {
                    entries.push((id(i, j), id(i, j + 1), -1.0));
                    entries.push((id(i, j + 1), id(i, j), -1.0));
                }
            }
        }
        SparseMatrix::from_entries(m * m, &entries)
    }

    /// max |A x − b|.
    pub(in crate::solver::ldlt) fn residual(a: &SparseMatrix, x: &[f64], b: &[f64]) -> f64 {
        let mut ax = vec![0.0; a.n];
        a.mul_vec(x, &mut ax);
        ax.iter()
            .zip(b)
            .fold(0.0f64, |e, (u, v)| e.max((u - v).abs()))
    }

    /// Runs `pass` on `y` with the factor's split (the result left in `y`) and without it,
    /// and checks that the two give the same bits.
    fn same_bits_both_ways(f: &mut OrderedLdlt, y: &mut [f64], pass: fn(&OrderedLdlt, &mut [f64])) {
        let split = std::mem::take(&mut f.split);
        let mut sequential = y.to_vec();
        pass(f, &mut sequential);
        f.split = split;
        pass(f, y);
        assert!(y
            .iter()
            .zip(&sequential)
            .all(|(u, v)| u.to_bits() == v.to_bits()));
    }

    /// The passes with subtrees in parallel give the sequential passes' results bit for
    /// bit, and solve the system.
    #[test]
    fn parallel_passes_are_the_sequential_ones_bit_for_bit() {
        let a = grid(300);
        let n = a.n;
        let fwd = leading_order(&a, n).unwrap();
        let mut f = OrderedLdlt::new(&a, fwd).unwrap();
        f.factor_with(|p, _, _| a.values[p]).unwrap();
        assert!(f.split.subtrees.len() >= 2, "the factor is split");
        let b: Vec<f64> = (0..n).map(|i| (0.37 * i as f64).sin()).collect();
        let mut y: Vec<f64> = f.order().iter().map(|&i| b[i]).collect();
        same_bits_both_ways(&mut f, &mut y, OrderedLdlt::forward);
        for (v, d) in y.iter_mut().zip(f.pivots()) {
            *v /= d;
        }
        same_bits_both_ways(&mut f, &mut y, OrderedLdlt::backward);
        // and it is the solution
        let mut x = vec![0.0; n];
        for (pos, &i) in f.order().iter().enumerate() {
            x[i] = y[pos];
        }
        let err = residual(&a, &x, &b);
        assert!(err < 1e-12, "residual {err}");
    }

    /// A factorisation with faer's parallel kernels solves as the sequential one does.
    #[test]
    fn a_factorisation_in_parallel_solves_the_system() {
        let a = grid(200);
        let n = a.n;
        let b: Vec<f64> = (0..n).map(|i| (0.61 * i as f64).cos()).collect();
        let mut solutions = vec![];
        for parallel in [false, true] {
            let mut f = OrderedLdlt::new(&a, leading_order(&a, n).unwrap()).unwrap();
            if parallel {
                f.factor_in_parallel();
            }
            f.factor_with(|p, _, _| a.values[p]).unwrap();
            let mut x = b.clone();
            f.solve(&mut x);
            let err = residual(&a, &x, &b);
            assert!(err < 1e-12, "parallel {parallel}: residual {err}");
            solutions.push(x);
        }
        let diff = solutions[0]
            .iter()
            .zip(&solutions[1])
            .fold(0.0f64, |e, (u, v)| e.max((u - v).abs()));
        assert!(diff < 1e-12, "the two solutions differ by {diff}");
    }
}
