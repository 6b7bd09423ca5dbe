//! The matrix of a problem with extra unknowns (contact multipliers) beside the free
//! displacements: the solid matrix plus contributions given as triplets over "extended"
//! ids (full displacement dof d < ndof, or extra unknown ndof + k). The combined pattern is
//! rebuilt only when the set of contributed entries changes; contributions therefore list
//! every entry that may become non-zero (explicit zeros included).
//!
//! | file | what |
//! |---|---|
//! | `mod.rs` | `Triplets`, `CoupledMatrix::update`: the contributions added where they go |
//! | `rebuild.rs` | a pattern change: the new entries merged in place |
//! | `groups.rs` | the targets of keyed groups of triplets, kept while the pattern stands |
//! | `tests.rs` | against fresh combinations, through rebuilds, fixed and linked dofs |

use super::dofs::DofMap;
use super::matrix::SparseMatrix;
use crate::error::{Error, Result};

mod groups;
mod rebuild;
#[cfg(test)]
mod tests;

use groups::GroupTargets;

#[derive(Default)]
pub struct Triplets {
    pub entries: Vec<(usize, usize, f64)>,
    /// Where groups of entries start (see `group`): a key, or none for entries that
    /// belong to no group.
    groups: Vec<(Option<u64>, usize)>,
    /// Added to every key from `begin_pair` on (keys of different pairs differ).
    key_base: u64,
}

impl Triplets {
    pub fn clear(&mut self) {
        self.entries.clear();
        self.groups.clear();
    }
    /// The entries added from here on, up to the next `group` or `ungrouped`, form the
    /// group `key` (e.g. one contact point's terms): when its (row, column) sequence is
    /// that of the last group of that key, its targets in the matrix are not searched
    /// again (statuses that change at a few points change the whole sequence, not theirs).
    /// Keys are unique within one evaluation; see `ungrouped` for entries of no group.
    pub fn group(&mut self, key: u64) {
        self.groups
            .push((Some(self.key_base.wrapping_add(key)), self.entries.len()));
    }
    /// The entries from here on are contact pair `pair`'s (its group keys are its own).
    pub fn begin_pair(&mut self, pair: usize) {
        self.key_base = (pair as u64) << 40;
        self.ungrouped();
    }
    /// The entries added from here on belong to no group.
    pub fn ungrouped(&mut self) {
        self.groups.push((None, self.entries.len()));
    }
    /// The segments of the entries: (key, range), in order, covering them all.
    fn segments(&self) -> Vec<(Option<u64>, std::ops::Range<usize>)> {
        let n = self.entries.len();
        let mut out = vec![];
        let first = self.groups.first().map_or(n, |g| g.1);
        if first > 0 {
            out.push((None, 0..first));
        }
        for (i, &(key, start)) in self.groups.iter().enumerate() {
            let end = self.groups.get(i + 1).map_or(n, |g| g.1);
            if end > start {
                out.push((key, start..end));
            }
        }
        out
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
        // (each column's last row marks it seen: rows are distinct, no clearing between
        // them; a hash set per row took 0.1 s per pattern at 93k unknowns, mortar)
        let ids = of_id.last().map_or(0, |l| l.0 + 1);
        let mut seen_in = vec![usize::MAX; ids];
        for run in of_id.chunk_by(|a, b| a.0 == b.0) {
            let row = run[0].0;
            for &(_, s) in run {
                for &col in &sets[s] {
                    if seen_in[col] != row {
                        seen_in[col] = row;
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
    /// The targets of the last keyed groups, valid for the pattern they were found in.
    groups: GroupTargets,
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
        let n = dofs.num_free + n_extra;
        // Status changes usually keep every target inside the current pattern (it holds the
        // explicit zeros of all candidate couplings): then no rebuild, and the groups
        // unchanged since the last search keep their targets.
        self.groups.stand_for(m.pattern_stamp);
        let found = if self.n == n {
            self.groups.targets(m, dofs, extra)
        } else {
            None
        };
        self.targets = match found {
            Some(t) => t,
            None => {
                // (the pattern only grows: the rebuild keeps every entry of the last one,
                // so a pair that sends its explicit zeros only when its candidates change
                // keeps them when another pair's new entries force a rebuild)
                let (_, targets) = expand(dofs, &extra.entries);
                let pairs = targets.iter().map(|t| (t.0, t.1));
                self.rebuild(m, cell_scatter, reserved, n, pairs)?;
                // (searched in the new pattern, and its groups kept for the next update)
                self.groups.stand_for(m.pattern_stamp);
                self.groups
                    .targets(m, dofs, extra)
                    .expect("pattern holds every contributed entry")
            }
        };
        let id = |i: usize| u32::try_from(i).map_err(|_| too_large());
        self.last_triplets = extra
            .entries
            .iter()
            .map(|t| Ok((id(t.0)?, id(t.1)?)))
            .collect::<Result<_>>()?;
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
    /// From triplet t's targets `at[ptr[t]..ptr[t + 1]]` with their `coefficients`; the
    /// usual case, one target of coefficient one per triplet, keeps only `at`.
    fn new(ptr: Vec<usize>, at: Vec<u32>, coefficients: Vec<f64>) -> Targets {
        let plain =
            ptr.windows(2).all(|w| w[1] == w[0] + 1) && coefficients.iter().all(|&c| c == 1.0);
        if plain {
            Targets {
                ptr: vec![],
                at,
                coefficients: vec![],
            }
        } else {
            Targets {
                ptr,
                at,
                coefficients,
            }
        }
    }
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

/// The triplets' targets over the unknowns: (column, row, coefficient) each, triplet t's
/// at `ptr[t]..ptr[t + 1]` (a dof expands to its free dofs, an extra id ndof + k to
/// unknown num_free + k).
fn expand(
    dofs: &DofMap,
    entries: &[(usize, usize, f64)],
) -> (Vec<usize>, Vec<(usize, usize, f64)>) {
    let (nf, ndof) = (dofs.num_free, dofs.num_dofs());
    let (mut ex_r, mut ex_c) = (vec![], vec![]);
    let expand = |id: usize, out: &mut Vec<(usize, f64)>| {
        if id < ndof {
            dofs.expand_dof(id, out);
        } else {
            out.clear();
            out.push((nf + id - ndof, 1.0));
        }
    };
    let mut targets = Vec::with_capacity(entries.len());
    let mut ptr = Vec::with_capacity(entries.len() + 1);
    ptr.push(0);
    for &(r, c, _) in entries {
        expand(r, &mut ex_r);
        expand(c, &mut ex_c);
        for &(i, ci) in &ex_r {
            for &(j, cj) in &ex_c {
                targets.push((j, i, ci * cj));
            }
        }
        ptr.push(targets.len());
    }
    (ptr, targets)
}

fn too_large() -> Error {
    Error::solve("matrix too large for 32-bit scatter positions")
}
