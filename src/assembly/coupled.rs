//! The matrix of a problem with extra unknowns (contact multipliers) beside the free
//! displacements: the solid matrix plus contributions given as triplets over "extended"
//! ids (full displacement dof d < ndof, or extra unknown ndof + k). The combined pattern is
//! rebuilt only when the set of contributed entries changes; contributions therefore list
//! every entry that may become non-zero (explicit zeros included).

use super::dofs::DofMap;
use super::matrix::SparseMatrix;

#[derive(Default)]
pub struct Triplets {
    pub entries: Vec<(usize, usize, f64)>,
}

impl Triplets {
    pub fn clear(&mut self) {
        self.entries.clear();
    }
    pub fn add(&mut self, row: usize, col: usize, v: f64) {
        self.entries.push((row, col, v));
    }

    /// Explicit zeros on the union of the cliques `sets` (each a list of extended ids),
    /// every entry once: a contact pattern's cliques overlap many times over (each master
    /// dof is in the clique of every slave cell within reach), and sending each clique
    /// whole took gigabytes on fine meshes (SSNP154 A with mortar at 31k unknowns).
    /// Rows in increasing order, each row's columns in first-seen order.
    pub fn add_clique_union(&mut self, sets: &[Vec<usize>]) {
        let mut of_id: Vec<(usize, usize)> = sets
            .iter()
            .enumerate()
            .flat_map(|(s, set)| set.iter().map(move |&id| (id, s)))
            .collect();
        of_id.sort_unstable();
        of_id.dedup();
        let mut seen: std::collections::HashSet<usize> = std::collections::HashSet::new();
        for run in of_id.chunk_by(|a, b| a.0 == b.0) {
            let row = run[0].0;
            seen.clear();
            for &(_, s) in run {
                for &col in &sets[s] {
                    if seen.insert(col) {
                        self.entries.push((row, col, 0.0));
                    }
                }
            }
        }
    }
}

#[derive(Default)]
pub struct CoupledMatrix {
    pub matrix: SparseMatrix,
    /// Where the solid values go in `matrix.values` (one solid value per position), as runs
    /// of consecutive positions (solid start, position start, length): copied run by run.
    /// `solid_nnz` solid values in all, and the positions no solid value lands on.
    solid_runs: Vec<(usize, usize, usize)>,
    solid_nnz: usize,
    non_solid: Vec<usize>,
    /// Entries contributed by the triplets, in unknown numbering (sorted by column, row).
    key: Vec<(usize, usize)>,
    /// The (row, col) sequence of the last triplets and, for each triplet, its targets
    /// (`scatter[scatter_ptr[t]..scatter_ptr[t + 1]]`: value position, coefficient). Contact
    /// terms emit the same sequence from one iteration to the next, so the expansion, sort
    /// and searches run only when it changes.
    last_triplets: Vec<(usize, usize)>,
    scatter_ptr: Vec<usize>,
    scatter: Vec<(usize, f64)>,
    /// The `matrix_generation` of the solid matrix last combined, and the solid part of
    /// the values at the positions the triplets wrote then: with the same solid matrix
    /// only those are reset and the triplets added again.
    solid_generation: Option<u64>,
    solid_at_scatter: Vec<(usize, f64)>,
    /// Number of pattern rebuilds (for reports).
    pub rebuilds: usize,
}

impl CoupledMatrix {
    /// Combines `solid` (over the free dofs; `generation` changes whenever its values do)
    /// with `extra` (extended ids) into `self.matrix` over nf + n_extra unknowns.
    pub fn update(
        &mut self,
        solid: &SparseMatrix,
        generation: u64,
        dofs: &DofMap,
        n_extra: usize,
        extra: &Triplets,
    ) {
        let n = dofs.num_free + n_extra;
        let same = self.matrix.n == n
            && self.solid_nnz == solid.nnz()
            && self.last_triplets.len() == extra.entries.len()
            && extra
                .entries
                .iter()
                .zip(&self.last_triplets)
                .all(|(t, k)| t.0 == k.0 && t.1 == k.1);
        let rebuilds = self.rebuilds;
        if !same {
            self.prepare(solid, dofs, n_extra, extra);
        }
        let m = &mut self.matrix;
        if self.solid_generation == Some(generation) && self.rebuilds == rebuilds {
            // same solid values and pattern (an active-set re-solve): every value is the
            // solid one again once the last triplets' positions are reset
            for &(q, v) in &self.solid_at_scatter {
                m.values[q] = v;
            }
        } else {
            for &q in &self.non_solid {
                m.values[q] = 0.0;
            }
            for &(p, q, len) in &self.solid_runs {
                m.values[q..q + len].copy_from_slice(&solid.values[p..p + len]);
            }
            self.solid_generation = Some(generation);
        }
        self.solid_at_scatter.clear();
        self.solid_at_scatter
            .extend(self.scatter.iter().map(|&(q, _)| (q, m.values[q])));
        for (t, &(_, _, v)) in extra.entries.iter().enumerate() {
            for &(q, coef) in &self.scatter[self.scatter_ptr[t]..self.scatter_ptr[t + 1]] {
                m.values[q] += coef * v;
            }
        }
    }

    /// Expands the triplets to unknowns, rebuilds the pattern if its set of entries changed,
    /// and records where each triplet's value goes.
    fn prepare(&mut self, solid: &SparseMatrix, dofs: &DofMap, n_extra: usize, extra: &Triplets) {
        let nf = dofs.num_free;
        let ndof = dofs.num_dofs();
        let n = nf + n_extra;
        let mut ex_r = vec![];
        let mut ex_c = vec![];
        let expand = |id: usize, out: &mut Vec<(usize, f64)>| {
            if id < ndof {
                dofs.expand_dof(id, out);
            } else {
                out.clear();
                out.push((nf + id - ndof, 1.0));
            }
        };
        // (column, row, coefficient) per target, grouped by triplet
        let mut targets: Vec<(usize, usize, f64)> = Vec::with_capacity(extra.entries.len());
        self.scatter_ptr.clear();
        self.scatter_ptr.push(0);
        for &(r, c, _) in &extra.entries {
            expand(r, &mut ex_r);
            expand(c, &mut ex_c);
            for &(i, ci) in &ex_r {
                for &(j, cj) in &ex_c {
                    targets.push((j, i, ci * cj));
                }
            }
            self.scatter_ptr.push(targets.len());
        }
        // Status changes usually keep every target inside the current pattern (it holds the
        // explicit zeros of all candidate couplings): then no sort and no rebuild.
        let fits = self.matrix.n == n && self.solid_nnz == solid.nnz();
        let mut scatter = Vec::with_capacity(targets.len());
        if fits {
            for &(col, row, coef) in &targets {
                match self.matrix.position(row, col) {
                    Some(q) => scatter.push((q, coef)),
                    None => break,
                }
            }
        }
        if scatter.len() < targets.len() {
            // the pattern only grows (a pair that sends its explicit zeros only when its
            // candidates change keeps them when another pair's new entries force a rebuild)
            let old: &[(usize, usize)] = if fits { &self.key } else { &[] };
            let key = sorted_unique(
                n,
                targets
                    .iter()
                    .map(|t| (t.0, t.1))
                    .chain(old.iter().copied()),
            );
            if key != self.key || !fits {
                self.rebuild(solid, n, &key);
                self.key = key;
            }
            let m = &self.matrix;
            scatter = targets
                .iter()
                .map(|&(col, row, coef)| {
                    let q = m
                        .position(row, col)
                        .expect("pattern holds every contributed entry");
                    (q, coef)
                })
                .collect();
        }
        self.scatter = scatter;
        self.last_triplets = extra.entries.iter().map(|t| (t.0, t.1)).collect();
    }

    /// The pattern: the solid's, the contributed entries and their transposes (structurally
    /// symmetric, as the saddle-point LDLᵀ of the symmetric part needs), and the diagonal.
    /// Each column merges the solid's sorted rows, the sorted contributed rows and the
    /// diagonal, recording where each solid entry lands.
    fn rebuild(&mut self, solid: &SparseMatrix, n: usize, key: &[(usize, usize)]) {
        // the old pattern and values go before the new ones come
        self.matrix = SparseMatrix::default();
        let extra = sorted_unique(n, key.iter().flat_map(|&(c, r)| [(c, r), (r, c)]));
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::with_capacity(solid.nnz() + extra.len() + n);
        self.solid_runs.clear();
        self.non_solid.clear();
        let mut e = 0;
        for c in 0..n {
            let (mut p, end) = if c < solid.n {
                (solid.col_ptr[c], solid.col_ptr[c + 1])
            } else {
                (0, 0)
            };
            let mut diagonal = true;
            loop {
                let rs = if p < end {
                    solid.row_idx[p]
                } else {
                    usize::MAX
                };
                let rx = if e < extra.len() && extra[e].0 == c {
                    extra[e].1
                } else {
                    usize::MAX
                };
                let rd = if diagonal { c } else { usize::MAX };
                let r = rs.min(rx).min(rd);
                if r == usize::MAX {
                    break;
                }
                let q = row_idx.len();
                if rs == r {
                    match self.solid_runs.last_mut() {
                        Some((p0, q0, len)) if *p0 + *len == p && *q0 + *len == q => *len += 1,
                        _ => self.solid_runs.push((p, q, 1)),
                    }
                    p += 1;
                } else {
                    self.non_solid.push(q);
                }
                if rx == r {
                    e += 1;
                }
                if rd == r {
                    diagonal = false;
                }
                row_idx.push(r);
            }
            col_ptr.push(row_idx.len());
        }
        self.matrix = SparseMatrix {
            n,
            values: vec![0.0; row_idx.len()],
            col_ptr,
            row_idx,
            pattern_stamp: super::matrix::new_pattern_stamp(),
        };
        self.solid_nnz = solid.nnz();
        self.rebuilds += 1;
    }
}

/// The distinct (column, row) pairs (both < n), sorted: bucketed by column (counting), then
/// each column's rows sorted and deduplicated in place.
fn sorted_unique(
    n: usize,
    pairs: impl Iterator<Item = (usize, usize)> + Clone,
) -> Vec<(usize, usize)> {
    let (ptr, mut rows) = super::matrix::group_by_key(n, pairs);
    let mut out = Vec::with_capacity(rows.len());
    for c in 0..n {
        let col = &mut rows[ptr[c]..ptr[c + 1]];
        col.sort_unstable();
        let mut last = usize::MAX;
        for &r in col.iter() {
            if r != last {
                out.push((c, r));
                last = r;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clique_union_sends_each_entry_once() {
        let sets = vec![vec![0, 2, 5], vec![2, 5, 7], vec![9], vec![5, 0]];
        let mut t = Triplets::default();
        t.add_clique_union(&sets);
        let mut got: Vec<(usize, usize)> = t.entries.iter().map(|e| (e.0, e.1)).collect();
        assert!(t.entries.iter().all(|e| e.2 == 0.0));
        let n = got.len();
        got.sort_unstable();
        got.dedup();
        assert_eq!(got.len(), n, "no entry twice");
        let mut expected: Vec<(usize, usize)> = sets
            .iter()
            .flat_map(|s| s.iter().flat_map(move |&r| s.iter().map(move |&c| (r, c))))
            .collect();
        expected.sort_unstable();
        expected.dedup();
        assert_eq!(got, expected);
    }

    #[test]
    fn sorted_unique_equals_sort_and_dedup() {
        let pairs: Vec<(usize, usize)> = (0..500u64)
            .map(|i| {
                let h = i.wrapping_mul(2654435761) ^ (i >> 3);
                ((h % 37) as usize, ((h / 37) % 41) as usize)
            })
            .collect();
        let mut expected = pairs.clone();
        expected.sort_unstable();
        expected.dedup();
        assert!(
            expected.len() < pairs.len(),
            "the sample has repeated pairs"
        );
        assert_eq!(sorted_unique(41, pairs.iter().copied()), expected);
    }

    /// Re-combining the same solid matrix with other triplets (the fast path of an
    /// active-set re-solve) gives exactly the values of a fresh combination.
    #[test]
    fn update_with_unchanged_solid_equals_fresh_combination() {
        // 3 nodes, 6 free dofs; a tridiagonal solid matrix
        let dofs = DofMap::new(&[true; 6], &[], &[]).unwrap();
        let mut entries = vec![];
        for i in 0..6 {
            entries.push((i, i, 4.0 + i as f64 * 0.1));
            if i > 0 {
                entries.push((i, i - 1, -1.0 - i as f64 * 0.01));
                entries.push((i - 1, i, -1.0 - i as f64 * 0.01));
            }
        }
        let solid = SparseMatrix::from_entries(6, &entries);
        let first = |t: &mut Triplets| {
            t.add(1, 6, 1.0);
            t.add(6, 1, 1.0);
            t.add(4, 6, -0.5);
            t.add(6, 4, -0.5);
            t.add(1, 4, 0.3);
        };
        // same entries with other values, then another set inside the same pattern
        let second = |t: &mut Triplets| {
            t.add(1, 6, 0.7);
            t.add(6, 1, 0.7);
            t.add(4, 6, 0.0);
            t.add(6, 4, 0.0);
            t.add(1, 4, -0.2);
        };
        let third = |t: &mut Triplets| {
            t.add(6, 6, 2.5);
            t.add(1, 4, 0.9);
        };
        let mut reused = CoupledMatrix::default();
        let mut t = Triplets::default();
        first(&mut t);
        reused.update(&solid, 7, &dofs, 1, &t);
        for fill in [second as fn(&mut Triplets), third] {
            t.clear();
            fill(&mut t);
            reused.update(&solid, 7, &dofs, 1, &t);
            let mut fresh = CoupledMatrix::default();
            // the fresh one sees the same pattern history (first triplets, then these)
            let mut t0 = Triplets::default();
            first(&mut t0);
            fresh.update(&solid, 1, &dofs, 1, &t0);
            fresh.update(&solid, 2, &dofs, 1, &t);
            assert_eq!(reused.matrix.col_ptr, fresh.matrix.col_ptr);
            assert_eq!(reused.matrix.row_idx, fresh.matrix.row_idx);
            assert_eq!(reused.matrix.values, fresh.matrix.values);
        }
        assert_eq!(
            reused.rebuilds, 1,
            "status changes stay inside the first pattern"
        );
    }
}
