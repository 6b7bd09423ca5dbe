//! The matrix of a problem with extra unknowns (contact multipliers) beside the free
//! displacements: the solid matrix plus contributions given as triplets over "extended"
//! ids (full displacement dof d < ndof, or extra unknown ndof + k). The combined pattern is
//! rebuilt only when the set of contributed entries changes; contributions therefore list
//! every entry that may become non-zero (explicit zeros included).

use super::dofs::DofMap;
use super::matrix::SparseMatrix;
use crate::error::{Error, Result};

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

/// The contact part of a problem's matrix. The matrix itself is the assembler's: on the
/// first contact pattern its pattern is extended to the extra unknowns and the contributed
/// entries, and the assembler's scatter goes on writing the solid values in place (one
/// matrix, not a solid one and a combined copy of it: SSNP154 D at 93k unknowns, 3M
/// entries of 16 bytes). An assembly zeroes every value; `update` then adds the
/// contributions.
#[derive(Default)]
pub struct CoupledMatrix {
    /// The order of the extended matrix (0: not extended yet).
    n: usize,
    /// Positions of the entries no solid value lands on (sorted).
    non_solid: Vec<usize>,
    /// Entries contributed by the triplets, in unknown numbering (sorted by column, row).
    key: Vec<(usize, usize)>,
    /// The (row, col) sequence of the last triplets and, for each triplet, its targets.
    /// Contact terms emit the same sequence from one iteration to the next, so the
    /// expansion, sort and searches run only when it changes.
    last_triplets: Vec<(u32, u32)>,
    targets: Targets,
    /// The assembler's `matrix_generation` of the solid values in the matrix, and the
    /// solid part of the values at the targets (as `targets.at`) when the triplets were
    /// added: with the same solid values only those are reset and the triplets added
    /// again.
    solid_generation: Option<u64>,
    solid_at_targets: Vec<f64>,
    /// Number of pattern rebuilds (for reports).
    pub rebuilds: usize,
}

/// Where the assembler writes: its matrix and, per cell entry, the position of its value
/// (or a value from `reserved` up, no position: a rebuild leaves it as it is).
pub struct SolidTarget<'a> {
    pub matrix: &'a mut SparseMatrix,
    /// Counts the assemblies of the solid values (they are fresh when it moved).
    pub generation: u64,
    pub cell_scatter: &'a mut [u32],
    /// The smallest scatter value that is no position.
    pub reserved: u32,
}

impl CoupledMatrix {
    /// Makes `solid.matrix` (over the free dofs, its solid values assembled at
    /// `solid.generation`) the combined matrix over nf + n_extra unknowns: the solid values
    /// plus `extra` (extended ids).
    pub fn update(
        &mut self,
        solid: SolidTarget,
        dofs: &DofMap,
        n_extra: usize,
        extra: &Triplets,
    ) -> Result<()> {
        let m = solid.matrix;
        // the solid values alone: freshly assembled (every other value zeroed), or the
        // last triplets' positions reset
        if self.solid_generation == Some(solid.generation) {
            for (&q, &v) in self.targets.at.iter().zip(&self.solid_at_targets) {
                m.values[q as usize] = v;
            }
        }
        self.solid_generation = Some(solid.generation);
        let n = dofs.num_free + n_extra;
        let same = self.n == n
            && self.last_triplets.len() == extra.entries.len()
            && extra
                .entries
                .iter()
                .zip(&self.last_triplets)
                .all(|(t, k)| t.0 == k.0 as usize && t.1 == k.1 as usize);
        if !same {
            self.prepare(m, solid.cell_scatter, solid.reserved, dofs, n_extra, extra)?;
        }
        self.solid_at_targets.clear();
        let at = &self.targets.at;
        self.solid_at_targets
            .extend(at.iter().map(|&q| m.values[q as usize]));
        for (t, &(_, _, v)) in extra.entries.iter().enumerate() {
            for s in self.targets.of(t) {
                m.values[at[s] as usize] += self.targets.coefficient(s) * v;
            }
        }
        Ok(())
    }

    /// Expands the triplets to unknowns, rebuilds the pattern if its set of entries changed,
    /// and records where each triplet's value goes.
    fn prepare(
        &mut self,
        m: &mut SparseMatrix,
        cell_scatter: &mut [u32],
        reserved: u32,
        dofs: &DofMap,
        n_extra: usize,
        extra: &Triplets,
    ) -> Result<()> {
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
        let mut ptr = Vec::with_capacity(extra.entries.len() + 1);
        ptr.push(0);
        for &(r, c, _) in &extra.entries {
            expand(r, &mut ex_r);
            expand(c, &mut ex_c);
            for &(i, ci) in &ex_r {
                for &(j, cj) in &ex_c {
                    targets.push((j, i, ci * cj));
                }
            }
            ptr.push(targets.len());
        }
        // Status changes usually keep every target inside the current pattern (it holds the
        // explicit zeros of all candidate couplings): then no sort and no rebuild.
        let fits = self.n == n;
        // (positions fit in 32 bits: the assembler and `rebuild` refuse larger matrices)
        let mut at = Vec::with_capacity(targets.len());
        if fits {
            for &(col, row, _) in &targets {
                match m.position(row, col) {
                    Some(q) => at.push(q as u32),
                    None => break,
                }
            }
        }
        if at.len() < targets.len() {
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
                self.rebuild(m, cell_scatter, reserved, n, &key)?;
                self.key = key;
            }
            at = targets
                .iter()
                .map(|&(col, row, _)| {
                    let q = m
                        .position(row, col)
                        .expect("pattern holds every contributed entry");
                    q as u32
                })
                .collect();
        }
        // one target of coefficient one per triplet (no linked dof among them): no
        // pointers, no coefficients
        let plain = ptr.windows(2).all(|w| w[1] == w[0] + 1) && targets.iter().all(|t| t.2 == 1.0);
        self.targets = Targets {
            ptr: if plain { vec![] } else { ptr },
            at,
            coefficients: if plain {
                vec![]
            } else {
                targets.iter().map(|t| t.2).collect()
            },
        };
        let id = |i: usize| u32::try_from(i).map_err(|_| too_large());
        self.last_triplets = extra
            .entries
            .iter()
            .map(|t| Ok((id(t.0)?, id(t.1)?)))
            .collect::<Result<_>>()?;
        Ok(())
    }

    /// The pattern: the last one (the solid's at first), the contributed entries and
    /// their transposes (structurally symmetric, as the saddle-point LDLᵀ of the symmetric
    /// part needs), and the diagonal. It only grows, so it is rebuilt in place: each
    /// column's new length counted first, then the columns merged from the last entry
    /// backwards, every entry moving to a position at or after its own: no second copy of
    /// the matrix (SSNP154 D point-to-segment at 93k unknowns: heap peak 634 MB with a new
    /// pattern and values beside the old ones, 612 MB in place). The values (the solid
    /// ones alone, zero elsewhere) move with their entries, and the assembler's scatter
    /// with them.
    fn rebuild(
        &mut self,
        m: &mut SparseMatrix,
        cell_scatter: &mut [u32],
        reserved: u32,
        n: usize,
        key: &[(usize, usize)],
    ) -> Result<()> {
        if n < m.n {
            return Err(Error::solve(format!(
                "internal: the contact unknowns went from {} to {}",
                m.n, n
            )));
        }
        // (by column: a row index each, where (column, row) pairs took twice the room)
        let (extra_ptr, extra) =
            sorted_unique_columns(n, key.iter().flat_map(|&(c, r)| [(c, r), (r, c)]));
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
        m.pattern_stamp = super::matrix::new_pattern_stamp();
        self.non_solid = non_solid;
        self.n = n;
        self.rebuilds += 1;
        Ok(())
    }
}

/// Where each triplet's value goes: triplet t's targets are `at[s]` with coefficient
/// `coefficient(s)` for s in `of(t)`. The usual case, one target of coefficient one per
/// triplet, keeps neither pointers nor coefficients (`ptr` and `coefficients` empty).
#[derive(Default)]
struct Targets {
    ptr: Vec<usize>,
    at: Vec<u32>,
    coefficients: Vec<f64>,
}

impl Targets {
    fn of(&self, t: usize) -> std::ops::Range<usize> {
        if self.ptr.is_empty() {
            t..t + 1
        } else {
            self.ptr[t]..self.ptr[t + 1]
        }
    }
    fn coefficient(&self, s: usize) -> f64 {
        if self.coefficients.is_empty() {
            1.0
        } else {
            self.coefficients[s]
        }
    }
}

fn too_large() -> Error {
    Error::solve("matrix too large for 32-bit scatter positions")
}

/// No row (the merges' end marker; rows are below it).
const NO_ROW: usize = usize::MAX;

/// The distinct (column, row) pairs (both < n), sorted.
fn sorted_unique(
    n: usize,
    pairs: impl Iterator<Item = (usize, usize)> + Clone,
) -> Vec<(usize, usize)> {
    let (ptr, rows) = sorted_unique_columns(n, pairs);
    (0..n)
        .flat_map(|c| rows[ptr[c]..ptr[c + 1]].iter().map(move |&r| (c, r)))
        .collect()
}

/// The distinct (column, row) pairs (both < n) by column: each column's rows are
/// `rows[ptr[c]..ptr[c + 1]]`, increasing. Bucketed by column (counting), then each
/// column's rows sorted and deduplicated in place.
fn sorted_unique_columns(
    n: usize,
    pairs: impl Iterator<Item = (usize, usize)> + Clone,
) -> (Vec<usize>, Vec<usize>) {
    let (mut ptr, mut rows) = super::matrix::group_by_key(n, pairs);
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

    /// A tridiagonal solid matrix over 6 free dofs (3 nodes), as assembled (`scale` on its
    /// values), and a cell scatter naming each of its entries once.
    fn solid(scale: f64) -> (SparseMatrix, Vec<u32>) {
        let mut entries = vec![];
        for i in 0..6 {
            entries.push((i, i, (4.0 + i as f64 * 0.1) * scale));
            if i > 0 {
                let v = (-1.0 - i as f64 * 0.01) * scale;
                entries.push((i, i - 1, v));
                entries.push((i - 1, i, v));
            }
        }
        let m = SparseMatrix::from_entries(6, &entries);
        let scatter = (0..m.nnz() as u32).chain([RESERVED]).collect();
        (m, scatter)
    }

    const RESERVED: u32 = u32::MAX - 1;

    fn target<'a>(
        m: &'a mut SparseMatrix,
        cells: &'a mut [u32],
        generation: u64,
    ) -> SolidTarget<'a> {
        SolidTarget {
            matrix: m,
            generation,
            cell_scatter: cells,
            reserved: RESERVED,
        }
    }

    /// The combined matrix of `solid(scale)` and the triplets, built in one update.
    fn fresh(history: &[fn(&mut Triplets)], scale: f64) -> SparseMatrix {
        let dofs = DofMap::new(&[true; 6], &[], &[]).unwrap();
        let (mut m, mut cells) = solid(scale);
        let mut c = CoupledMatrix::default();
        let mut t = Triplets::default();
        for (g, fill) in history.iter().enumerate() {
            t.clear();
            fill(&mut t);
            if g > 0 {
                // a new assembly: every value zeroed, the solid ones written again
                let (s, _) = solid(scale);
                m.values.iter_mut().for_each(|v| *v = 0.0);
                for (k, &q) in cells.iter().enumerate().take(s.nnz()) {
                    m.values[q as usize] = s.values[k];
                }
            }
            c.update(target(&mut m, &mut cells, g as u64), &dofs, 1, &t)
                .unwrap();
        }
        m
    }

    fn first(t: &mut Triplets) {
        t.add(1, 6, 1.0);
        t.add(6, 1, 1.0);
        t.add(4, 6, -0.5);
        t.add(6, 4, -0.5);
        t.add(1, 4, 0.3);
    }
    /// The same entries with other values.
    fn second(t: &mut Triplets) {
        t.add(1, 6, 0.7);
        t.add(6, 1, 0.7);
        t.add(4, 6, 0.0);
        t.add(6, 4, 0.0);
        t.add(1, 4, -0.2);
    }
    /// Another set inside the same pattern.
    fn third(t: &mut Triplets) {
        t.add(6, 6, 2.5);
        t.add(1, 4, 0.9);
    }
    /// An entry outside it (a rebuild).
    fn fourth(t: &mut Triplets) {
        t.add(0, 6, 0.4);
        t.add(6, 0, 0.4);
        t.add(5, 2, 0.1);
    }

    /// Re-combining the same solid values with other triplets (an active-set re-solve),
    /// with or without a rebuild, gives exactly the values of a fresh combination, and the
    /// assembler's scatter follows the solid entries into the extended pattern.
    #[test]
    fn update_with_unchanged_solid_equals_fresh_combination() {
        let dofs = DofMap::new(&[true; 6], &[], &[]).unwrap();
        let (mut m, mut cells) = solid(1.0);
        let (solid0, _) = solid(1.0);
        let mut reused = CoupledMatrix::default();
        let mut t = Triplets::default();
        let mut history: Vec<fn(&mut Triplets)> = vec![first];
        first(&mut t);
        reused
            .update(target(&mut m, &mut cells, 7), &dofs, 1, &t)
            .unwrap();
        for fill in [second as fn(&mut Triplets), third, fourth] {
            t.clear();
            fill(&mut t);
            reused
                .update(target(&mut m, &mut cells, 7), &dofs, 1, &t)
                .unwrap();
            history.push(fill);
            // the fresh one sees the same pattern history, each with a new assembly
            let fresh = fresh(&history, 1.0);
            assert_eq!(m.col_ptr, fresh.col_ptr);
            assert_eq!(m.row_idx, fresh.row_idx);
            assert_eq!(m.values, fresh.values);
            // each cell entry lands where its solid entry now is
            for (k, &q) in cells.iter().enumerate().take(solid0.nnz()) {
                let (c, r) = (0..6)
                    .flat_map(|c| (solid0.col_ptr[c]..solid0.col_ptr[c + 1]).map(move |p| (c, p)))
                    .find(|&(_, p)| p == k)
                    .map(|(c, p)| (c, solid0.row_idx[p]))
                    .unwrap();
                assert_eq!(Some(q as usize), m.position(r, c));
            }
            assert_eq!(cells.last(), Some(&RESERVED), "a reserved value stays");
        }
        assert_eq!(
            reused.rebuilds, 2,
            "the fourth set alone leaves the pattern"
        );
    }

    /// New solid values (a new assembly) in the extended matrix: the contact terms are
    /// added to them, not to the old ones.
    #[test]
    fn a_new_assembly_in_the_extended_matrix_takes_the_new_solid_values() {
        let history: [fn(&mut Triplets); 2] = [first, second];
        let reassembled = fresh(&history, 2.0);
        let dofs = DofMap::new(&[true; 6], &[], &[]).unwrap();
        let (mut m, mut cells) = solid(2.0);
        let mut c = CoupledMatrix::default();
        let mut t = Triplets::default();
        second(&mut t);
        c.update(target(&mut m, &mut cells, 0), &dofs, 1, &t)
            .unwrap();
        // same pattern (the first triplets' entries are the second's)
        assert_eq!(m.row_idx, reassembled.row_idx);
        assert_eq!(m.values, reassembled.values);
    }

    /// Triplets on a fixed dof (no target) and on a linked one (a target per term, with
    /// its coefficient) land as an explicit expansion puts them.
    #[test]
    fn triplets_on_fixed_and_linked_dofs_expand_to_their_targets() {
        use crate::assembly::dofs::Relation;
        // 8 dofs: dof 6 fixed, 2 u7 − u4 − u5 = 0 (one of the three eliminated): 6 free
        let link = Relation {
            terms: vec![(7, 2.0), (4, -1.0), (5, -1.0)],
            rhs: 0.0,
            name: "mean".into(),
        };
        let dofs = DofMap::new(&[true; 8], &[(6, 0.0)], &[link]).unwrap();
        assert_eq!(dofs.num_free, 6);
        let (mut m, mut cells) = solid(1.0);
        let (solid0, _) = solid(1.0);
        let mut t = Triplets::default();
        // extended ids: dofs 0–7, the extra unknown 8
        for (r, c, v) in [
            (6, 8, 0.5),
            (8, 6, 0.5),
            (7, 8, 1.5),
            (8, 7, 1.5),
            (4, 7, 0.25),
        ] {
            t.add(r, c, v);
        }
        t.add(8, 8, -2.0);
        let mut c = CoupledMatrix::default();
        c.update(target(&mut m, &mut cells, 0), &dofs, 1, &t)
            .unwrap();
        assert!(!c.targets.ptr.is_empty(), "not one target per triplet");
        let mut expected = vec![vec![0.0; 7]; 7];
        for j in 0..6 {
            for p in solid0.col_ptr[j]..solid0.col_ptr[j + 1] {
                expected[solid0.row_idx[p]][j] = solid0.values[p];
            }
        }
        let expand = |id: usize| {
            let mut out = vec![];
            if id < 8 {
                dofs.expand_dof(id, &mut out);
            } else {
                out.push((6, 1.0));
            }
            out
        };
        for &(r, c, v) in &t.entries {
            for (i, ci) in expand(r) {
                for (j, cj) in expand(c) {
                    expected[i][j] += ci * cj * v;
                }
            }
        }
        for (i, row) in expected.iter().enumerate() {
            for (j, &e) in row.iter().enumerate() {
                let got = m.position(i, j).map_or(0.0, |q| m.values[q]);
                assert_eq!(got, e, "entry ({i}, {j})");
            }
        }
    }
}
