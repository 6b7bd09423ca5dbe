//! The numeric LDLᵀ with the elimination tree's independent subtrees on both cores.
//! faer's supernodal factorisation runs its supernodes in sequence (its parallelism is
//! inside the dense kernels of large supernodes), so while a contact solve factorises its
//! largest body the other core idles once the smaller bodies are done (SSNP154 A at 98k
//! unknowns: a body of 80k unknowns, 0.20 s, beside one of 18k, 0.03 s).
//!
//! Left-looking, as faer's: supernode s gathers A's columns, subtracts the update
//! L_d D_d L_dᵀ of every supernode d with rows in its columns (its descendants), factorises
//! its diagonal block and scales the rows below. With the supernodes in a postorder of the
//! tree, a subtree is a contiguous range of them and of the factor's storage, and reads
//! nothing outside it: the children's subtrees of a supernode run in parallel, each in its
//! own range, then the supernode itself (`Factor::subtree`). The last ones (a body's last
//! separator and its interface unknowns) are wide and have no sibling: their updates are
//! shared by the cores by ranges of columns, their dense LDLᵀ is faer's parallel one.
//!
//! The storage is faer's (each supernode's columns, diagonal block then the rows below; D
//! on the diagonal, L strictly below), so the passes and faer's solves read it as before.
//! The result is faer's up to the rounding of the updates' sums; it is the same in every
//! run (each entry's updates are subtracted in one order).

use super::forest::Forest;
use super::{singular, OrderedLdlt};
use crate::error::Result;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::{
    cholesky_in_place, cholesky_in_place_scratch, LdltError,
};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::solve_unit_lower_triangular_in_place;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
use faer::{Accum, MatMut, MatRef, Par};
use rayon::prelude::*;

/// The elimination tree of the supernodes, in postorder (each subtree a contiguous range
/// of supernodes, its root last), and each supernode's updates: the supernodes with rows
/// in its columns (its descendants), ascending, `updates[ptr[s]..ptr[s + 1]]`.
pub(super) struct Tree {
    forest: Forest,
    roots: Vec<usize>,
    ptr: Vec<usize>,
    updates: Vec<usize>,
}

/// A subtree with at most 1/GRAIN of the factor's entries runs as one task.
const GRAIN: usize = 64;

/// The supernodal structure, borrowed from the symbolic factorisation.
struct Structure<'a> {
    begin: &'a [usize],
    end: &'a [usize],
    row_ptr: &'a [usize],
    rows: &'a [usize],
    val_ptr: &'a [usize],
}

impl Structure<'_> {
    fn pattern(&self, s: usize) -> &[usize] {
        &self.rows[self.row_ptr[s]..self.row_ptr[s + 1]]
    }
}

/// Per task: the updates' products and the dense LDLᵀ's scratch.
struct Work {
    update: UpdateWork,
    stack: MemBuffer,
}

#[derive(Default)]
struct UpdateWork {
    product: Vec<f64>,
    scaled: Vec<f64>,
    at: Vec<usize>,
}

impl Work {
    fn new(widest: usize, par: Par) -> Work {
        Work {
            update: UpdateWork::default(),
            stack: MemBuffer::new(cholesky_in_place_scratch::<f64>(
                widest,
                par,
                Default::default(),
            )),
        }
    }
}

/// A supernode this wide or wider, above the subtrees run as one task, has its updates
/// shared by both cores (each a range of its columns) and its dense LDLᵀ on faer's parallel
/// kernels: the root of a body's block (its last separator and its interface unknowns,
/// SSNP154 A at 98k unknowns: 1314 columns, a third of the block's factorisation) would
/// run alone while the other core idles.
const WIDE: usize = 256;

impl OrderedLdlt {
    /// The supernodes' tree (see `Tree`); None when the supernodes are not in a postorder
    /// of it (then faer's factorisation serves).
    pub(super) fn tree_of(&self) -> Option<Tree> {
        let st = self.structure();
        let ns = st.begin.len();
        let entries: Vec<usize> = (0..ns).map(|s| st.val_ptr[s + 1] - st.val_ptr[s]).collect();
        let forest = Forest::new(st.begin, st.end, |s| st.pattern(s), &entries);
        if !(0..ns).all(|s| forest.contiguous(s)) {
            return None;
        }
        let mut lists: Vec<Vec<usize>> = vec![vec![]; ns];
        for d in 0..ns {
            let mut last = usize::MAX;
            for &r in st.pattern(d) {
                let s = forest.node_of[r];
                if s != last {
                    lists[s].push(d);
                    last = s;
                }
            }
        }
        let mut ptr = vec![0];
        for l in &lists {
            ptr.push(ptr.last().unwrap() + l.len());
        }
        Some(Tree {
            roots: (0..ns).filter(|&s| forest.parent[s].is_none()).collect(),
            forest,
            ptr,
            updates: lists.concat(),
        })
    }

    fn structure(&self) -> Structure<'_> {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            unreachable!("the analysis forces the supernodal kernel")
        };
        let ns = sym.n_supernodes();
        Structure {
            begin: &sym.supernode_begin()[..ns],
            end: &sym.supernode_end()[..ns],
            row_ptr: sym.col_ptr_for_row_idx(),
            rows: sym.row_idx(),
            val_ptr: sym.col_ptr_for_val(),
        }
    }

    /// The numeric factorisation of `permuted_values` into `values` by the tree: the
    /// children's subtrees in parallel, then their parent.
    pub(super) fn factor_by_tree(&mut self, tree: &Tree) -> Result<()> {
        // (taken out while the structure borrows the rest; put back whatever happens)
        let mut values = std::mem::take(&mut self.values);
        let result = self.factor_tree_into(tree, &mut values);
        self.values = values;
        result
    }

    fn factor_tree_into(&self, tree: &Tree, values: &mut [f64]) -> Result<()> {
        let st = self.structure();
        let ns = st.begin.len();
        let factor = Factor {
            st: &st,
            tree,
            a: (
                self.permuted.col_ptr(),
                self.permuted.row_idx(),
                &self.permuted_values,
            ),
            widest: (0..ns).map(|s| st.end[s] - st.begin[s]).max().unwrap_or(0),
            grain: values.len() / GRAIN,
            par: self.par,
        };
        factor.forest(&tree.roots, values)
    }
}

/// What a factorisation by the tree reads.
struct Factor<'a> {
    st: &'a Structure<'a>,
    tree: &'a Tree,
    a: (&'a [usize], &'a [usize], &'a [f64]),
    widest: usize,
    grain: usize,
    par: Par,
}

impl Factor<'_> {
    /// The subtrees of `roots` (consecutive, ascending; `values` their factor): in
    /// parallel.
    fn forest(&self, roots: &[usize], values: &mut [f64]) -> Result<()> {
        let (st, tree) = (self.st, self.tree);
        let mut pieces = Vec::with_capacity(roots.len());
        let mut rest = values;
        for &r in roots {
            let len = st.val_ptr[r + 1] - st.val_ptr[tree.forest.first[r]];
            let (piece, tail) = rest.split_at_mut(len);
            pieces.push((r, piece));
            rest = tail;
        }
        pieces
            .into_par_iter()
            .map(|(r, piece)| self.subtree(r, piece))
            .collect()
    }

    /// The subtree of `r`, its factor in `values` (from its first supernode's on).
    fn subtree(&self, r: usize, values: &mut [f64]) -> Result<()> {
        let (st, tree) = (self.st, self.tree);
        let offset = st.val_ptr[tree.forest.first[r]];
        if tree.forest.work[r] <= self.grain {
            let mut work = Work::new(self.widest, Par::Seq);
            return (tree.forest.first[r]..=r).try_for_each(|s| {
                factor_node(st, tree, self.a, values, offset, s, &mut work, Par::Seq)
            });
        }
        let children = &tree.forest.children[r];
        if !children.is_empty() {
            let below = st.val_ptr[r] - offset;
            self.forest(children, &mut values[..below])?;
        }
        let width = st.end[r] - st.begin[r];
        let par = if width >= WIDE {
            Par::rayon(0)
        } else {
            self.par
        };
        let mut work = Work::new(width, par);
        factor_node(st, tree, self.a, values, offset, r, &mut work, par)
    }
}

/// The first column of each of `pieces` ranges of a supernode's c columns (then c), of
/// about equal numbers of entries on and below the diagonal (m rows).
fn column_bounds(c: usize, m: usize, pieces: usize) -> Vec<usize> {
    let below = |j: usize| m - j;
    let total: usize = (0..c).map(below).sum();
    let mut bounds = vec![0];
    let mut sum = 0;
    for j in 0..c {
        sum += below(j);
        if bounds.len() < pieces && sum * pieces >= total * bounds.len() {
            bounds.push(j + 1);
        }
    }
    bounds.truncate(pieces);
    bounds.push(c);
    bounds.dedup();
    bounds
}

/// A supernode s receiving its updates: the factor before it (`head`, from position
/// `offset`), its rows m.
struct Node<'a> {
    st: &'a Structure<'a>,
    tree: &'a Tree,
    head: &'a [f64],
    offset: usize,
    s: usize,
    m: usize,
}

impl Node<'_> {
    /// Subtracts from the supernode's columns j0..j1 (`cols`) the updates of its
    /// descendants that reach them.
    fn update(&self, j0: usize, j1: usize, cols: &mut [f64], work: &mut UpdateWork) {
        let (st, m) = (self.st, self.m);
        let (s_begin, s_end) = (st.begin[self.s], st.end[self.s]);
        let c = s_end - s_begin;
        let s_pattern = st.pattern(self.s);
        let tree = self.tree;
        for &d in &tree.updates[tree.ptr[self.s]..tree.ptr[self.s + 1]] {
            let d_pattern = st.pattern(d);
            let dc = st.end[d] - st.begin[d];
            let dm = dc + d_pattern.len();
            let ld = &self.head[st.val_ptr[d] - self.offset..st.val_ptr[d + 1] - self.offset];
            let ld = MatRef::from_column_major_slice(ld, dm, dc);
            // its rows from the range's first column on, and those within the range
            let first = d_pattern.partition_point(|&r| r < s_begin + j0);
            let mid = d_pattern[first..].partition_point(|&r| r < s_begin + j1);
            if mid == 0 {
                continue;
            }
            let rows = &d_pattern[first..];
            let nr = rows.len();
            // W = L_d[rows] D_d L_d[mid rows]ᵀ
            work.scaled.clear();
            work.scaled.resize(mid * dc, 0.0);
            let mut scaled = MatMut::from_column_major_slice_mut(&mut work.scaled, mid, dc);
            for k in 0..dc {
                let dk = ld[(k, k)];
                for i in 0..mid {
                    scaled[(i, k)] = ld[(dc + first + i, k)] * dk;
                }
            }
            work.product.clear();
            work.product.resize(nr * mid, 0.0);
            let mut w = MatMut::from_column_major_slice_mut(&mut work.product, nr, mid);
            matmul(
                w.as_mut(),
                Accum::Replace,
                ld.subrows(dc + first, nr),
                scaled.as_ref().transpose(),
                1.0,
                Par::Seq,
            );
            // each row's place in the supernode (its pattern holds the rows below)
            work.at.clear();
            let mut k = 0;
            for &r in rows {
                if r < s_end {
                    work.at.push(r - s_begin);
                } else {
                    while s_pattern[k] != r {
                        k += 1;
                    }
                    work.at.push(c + k);
                }
            }
            for jj in 0..mid {
                let j = rows[jj] - s_begin - j0;
                let col = &mut cols[j * m..(j + 1) * m];
                for ii in jj..nr {
                    col[work.at[ii]] -= w[(ii, jj)];
                }
            }
        }
    }
}

/// Factorises supernode s, its descendants done: `values` holds the factor from position
/// `offset` on (a subtree's range, or the whole factor).
#[allow(clippy::too_many_arguments)]
fn factor_node(
    st: &Structure,
    tree: &Tree,
    (a_ptr, a_rows, a_vals): (&[usize], &[usize], &[f64]),
    values: &mut [f64],
    offset: usize,
    s: usize,
    work: &mut Work,
    par: Par,
) -> Result<()> {
    let (s_begin, s_end) = (st.begin[s], st.end[s]);
    let s_pattern = st.pattern(s);
    let c = s_end - s_begin;
    let m = c + s_pattern.len();
    let (head, tail) = values.split_at_mut(st.val_ptr[s] - offset);
    let ls = &mut tail[..st.val_ptr[s + 1] - st.val_ptr[s]];
    ls.fill(0.0);
    // A's lower triangle in the supernode's columns (its rows below the diagonal block
    // are among the pattern's, both increasing)
    for j in s_begin..s_end {
        let col = &mut ls[(j - s_begin) * m..(j - s_begin + 1) * m];
        let mut k = 0;
        for q in a_ptr[j]..a_ptr[j + 1] {
            let i = a_rows[q];
            if i < j {
                continue;
            }
            if i < s_end {
                col[i - s_begin] += a_vals[q];
            } else {
                while s_pattern[k] != i {
                    k += 1;
                }
                col[c + k] += a_vals[q];
            }
        }
    }
    // the descendants' updates, by ranges of columns on both cores when wide
    let pieces = if c >= WIDE && par != Par::Seq { 4 } else { 1 };
    let bounds = column_bounds(c, m, pieces);
    let mut ranges = Vec::with_capacity(pieces);
    let mut rest = &mut ls[..];
    for w in bounds.windows(2) {
        let (cols, tail) = std::mem::take(&mut rest).split_at_mut((w[1] - w[0]) * m);
        ranges.push((w[0], w[1], cols));
        rest = tail;
    }
    let node = Node {
        st,
        tree,
        head,
        offset,
        s,
        m,
    };
    if pieces == 1 {
        let (j0, j1, cols) = ranges.pop().unwrap();
        node.update(j0, j1, cols, &mut work.update);
    } else {
        ranges
            .into_par_iter()
            .for_each(|(j0, j1, cols)| node.update(j0, j1, cols, &mut UpdateWork::default()));
    }
    // the diagonal block's LDLᵀ, then the rows below: L_b ← L_b L⁻ᵀ D⁻¹
    let mut lsm = MatMut::from_column_major_slice_mut(ls, m, c);
    let (mut top, mut bottom) = lsm.as_mut().split_at_row_mut(c);
    cholesky_in_place(
        top.as_mut(),
        Default::default(),
        par,
        MemStack::new(&mut work.stack),
        Default::default(),
    )
    // (the pivot's position in the whole factor, as faer's factorisation names it)
    .map_err(|LdltError::ZeroPivot { index }| {
        singular(LdltError::ZeroPivot {
            index: index + s_begin,
        })
    })?;
    for j in 0..c {
        for i in 0..j {
            top[(i, j)] = 0.0;
        }
    }
    solve_unit_lower_triangular_in_place(top.as_ref(), bottom.as_mut().transpose_mut(), par);
    for j in 0..c {
        let dj = top[(j, j)].recip();
        for i in 0..bottom.nrows() {
            bottom[(i, j)] *= dj;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::passes::tests::{grid, residual};
    use super::super::{leading_order, OrderedLdlt};
    use crate::assembly::matrix::SparseMatrix;

    /// Factorises `a` (its first `interior` unknowns ordered by AMD, the others last, each
    /// entry's value `value(p)`) by the tree and by faer: the two factors agree to
    /// rounding, and the tree's solves `a x = b`. Returns the last supernode's width.
    fn tree_against_faer(a: &SparseMatrix, interior: usize, value: impl Fn(usize) -> f64) -> usize {
        let n = a.n;
        let mut fwd = leading_order(a, interior).unwrap();
        fwd.extend(interior..n);
        let mut f = OrderedLdlt::new(a, fwd).unwrap();
        assert!(f.tree.is_some(), "the factor is split and in postorder");
        f.factor_with(|p, _, _| value(p)).unwrap();
        let by_tree = f.values.clone();
        let tree = f.tree.take();
        f.factor_with(|p, _, _| value(p)).unwrap();
        let scale = f.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = by_tree
            .iter()
            .zip(&f.values)
            .fold(0.0f64, |m, (u, v)| m.max((u - v).abs()));
        assert!(
            diff <= 1e-12 * scale,
            "factors differ by {diff} (scale {scale})"
        );
        f.tree = tree;
        f.values = by_tree;
        let b: Vec<f64> = (0..n).map(|i| (0.29 * i as f64).sin()).collect();
        let mut x = b.clone();
        f.solve(&mut x);
        let mut signed = a.clone();
        for (p, v) in signed.values.iter_mut().enumerate() {
            *v = value(p);
        }
        let err = residual(&signed, &x, &b);
        assert!(err < 1e-10, "residual {err}");
        let st = f.structure();
        let last = st.begin.len() - 1;
        st.end[last] - st.begin[last]
    }

    /// A factorisation's multiply-adds, counted on a dense matrix (one supernode, no
    /// relaxation): column j has n − 1 − j entries below its pivot, Σ (n − 1 − j)² =
    /// (n − 1) n (2n − 1) / 6; the factor stores its supernode's diagonal block whole.
    #[test]
    fn a_dense_factorisation_counts_its_multiply_adds() {
        let n = 40;
        let mut entries = vec![];
        for i in 0..n {
            for j in 0..n {
                entries.push((i, j, if i == j { n as f64 } else { 0.5 }));
            }
        }
        let a = SparseMatrix::from_entries(n, &entries);
        let f = OrderedLdlt::new(&a, (0..n).collect()).unwrap();
        assert_eq!(f.entries(), n * n);
        assert_eq!(f.factor_flops(), ((n - 1) * n * (2 * n - 1) / 6) as f64);
    }

    #[test]
    fn the_factorisation_by_the_tree_is_faers_up_to_rounding() {
        let a = grid(300);
        tree_against_faer(&a, a.n, |p| a.values[p]);
    }

    /// As a body's block of the contact solve: its last unknowns (a grid line) ordered
    /// last with a negative diagonal, so that the trailing pivots are negative; the last
    /// supernode is wide (its updates shared by the cores by ranges of columns).
    #[test]
    fn a_trailing_block_of_negative_pivots_is_factorised_by_the_tree_as_by_faer() {
        let a = grid(300);
        let interior = a.n - 300;
        let negative: Vec<bool> = (0..a.values.len())
            .map(|p| {
                let c = a.col_ptr.partition_point(|&q| q <= p) - 1;
                c >= interior && a.row_idx[p] == c
            })
            .collect();
        let last_width =
            tree_against_faer(
                &a,
                interior,
                |p| {
                    if negative[p] {
                        -1.0e3
                    } else {
                        a.values[p]
                    }
                },
            );
        assert!(
            last_width >= super::WIDE,
            "the last supernode's width {last_width}"
        );
    }

    /// A zero pivot (an unknown whose row and column are zero) is named by its position in
    /// the factorised order, as faer's factorisation names it.
    #[test]
    fn a_zero_pivot_is_named_where_faer_names_it() {
        let a = grid(300);
        let mut f = OrderedLdlt::new(&a, leading_order(&a, a.n).unwrap()).unwrap();
        assert!(f.tree.is_some());
        let zero = f.order()[a.n / 2];
        let value = |p: usize| {
            let c = a.col_ptr.partition_point(|&q| q <= p) - 1;
            if c == zero || a.row_idx[p] == zero {
                0.0
            } else {
                a.values[p]
            }
        };
        let values: Vec<f64> = (0..a.values.len()).map(value).collect();
        let by_tree = f.factor_with(|p, _, _| values[p]).unwrap_err().to_string();
        f.tree = None;
        let by_faer = f.factor_with(|p, _, _| values[p]).unwrap_err().to_string();
        assert_eq!(by_tree, by_faer);
        assert!(by_tree.contains("ZeroPivot"), "{by_tree}");
    }
}
