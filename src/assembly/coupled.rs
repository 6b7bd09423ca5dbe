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
}

#[derive(Default)]
pub struct CoupledMatrix {
    pub matrix: SparseMatrix,
    /// Position in `matrix.values` of each value of the solid matrix.
    solid_map: Vec<usize>,
    /// Entries contributed by the triplets, in unknown numbering (sorted by column, row).
    key: Vec<(usize, usize)>,
    /// The (row, col) sequence of the last triplets and, for each triplet, its targets
    /// (`scatter[scatter_ptr[t]..scatter_ptr[t + 1]]`: value position, coefficient). Contact
    /// terms emit the same sequence from one iteration to the next, so the expansion, sort
    /// and searches run only when it changes.
    last_triplets: Vec<(usize, usize)>,
    scatter_ptr: Vec<usize>,
    scatter: Vec<(usize, f64)>,
    /// Number of pattern rebuilds (for reports).
    pub rebuilds: usize,
}

impl CoupledMatrix {
    /// Combines `solid` (over the free dofs) with `extra` (extended ids) into `self.matrix`
    /// over nf + n_extra unknowns.
    pub fn update(
        &mut self,
        solid: &SparseMatrix,
        dofs: &DofMap,
        n_extra: usize,
        extra: &Triplets,
    ) {
        let n = dofs.num_free + n_extra;
        let same = self.matrix.n == n
            && self.solid_map.len() == solid.nnz()
            && self.last_triplets.len() == extra.entries.len()
            && extra
                .entries
                .iter()
                .zip(&self.last_triplets)
                .all(|(t, k)| t.0 == k.0 && t.1 == k.1);
        if !same {
            self.prepare(solid, dofs, n_extra, extra);
        }
        let m = &mut self.matrix;
        m.values.fill(0.0);
        for (p, &q) in self.solid_map.iter().enumerate() {
            m.values[q] += solid.values[p];
        }
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
        let fits = self.matrix.n == n && self.solid_map.len() == solid.nnz();
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
            let mut key: Vec<(usize, usize)> = targets.iter().map(|t| (t.0, t.1)).collect();
            key.sort_unstable();
            key.dedup();
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
        let mut extra: Vec<(usize, usize)> = Vec::with_capacity(2 * key.len());
        for &(c, r) in key {
            extra.push((c, r));
            extra.push((r, c));
        }
        extra.sort_unstable();
        extra.dedup();
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::with_capacity(solid.nnz() + extra.len() + n);
        let mut solid_map = vec![0usize; solid.nnz()];
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
                if rs == r {
                    solid_map[p] = row_idx.len();
                    p += 1;
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
        };
        self.solid_map = solid_map;
        self.rebuilds += 1;
    }
}
