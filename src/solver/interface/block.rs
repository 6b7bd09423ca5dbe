//! One body's block of the interface solve: its matrix (interior, then the interface
//! unknowns it couples to, with a shifted diagonal there), its LDLᵀ, and the Schur
//! complement onto its interface read off the factor's trailing block (see `mod.rs`).

use super::NONE;
use crate::assembly::matrix::SparseMatrix;
use crate::error::Result;
use crate::solver::ldlt::{leading_order, OrderedLdlt};
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::Accum;
use faer::{Mat, Par};

/// One block of displacements with the interface unknowns it couples to.
pub(super) struct Block {
    /// Global unknowns of the block's matrix: its interior, then its interface unknowns.
    pub(super) unknowns: Vec<usize>,
    /// Number of interior unknowns (the interface ones follow).
    pub(super) interior: usize,
    /// Position in the interface of each of the block's interface unknowns.
    pub(super) gamma: Vec<usize>,
    /// The last factorisation succeeded: it is of the values `ldlt.factored_values()` (no
    /// copy of them here: SSNP154 D at 93k unknowns, 13 MB).
    pub(super) factored: bool,
    /// Positions in A of the interior unknowns' diagonal entries (they set the shift).
    pub(super) diagonal: Vec<usize>,
    pub(super) ldlt: OrderedLdlt,
    pub(super) shift: f64,
    /// Of the last factorisation: the pivots of the interior (in the factorised order),
    /// and in one k × k matrix the trailing unit lower triangle L_ΓΓ (below the diagonal;
    /// its ones implied) and S'_b − σI = L_ΓΓ D_Γ L_ΓΓᵀ − σI (symmetric: on and above the
    /// diagonal; see `schur_column`). S' is kept: an active-set re-solve changes T's
    /// contact terms only, and assembles T again. (One matrix, not two: SSNP154 D with
    /// mortar at 93k unknowns, 13 MB.)
    pub(super) pivots: Vec<f64>,
    pub(super) trailing: Mat<f64>,
    /// The last forward pass with this factorisation: its interior right-hand side and
    /// result (an active-set re-solve repeats it: the contact terms live in Γ).
    pub(super) last_forward: Option<(Vec<f64>, Vec<f64>)>,
}

impl Block {
    pub(super) fn new(
        a: &SparseMatrix,
        unknowns: Vec<usize>,
        interior: usize,
        gamma: Vec<usize>,
        storage: Vec<f64>,
    ) -> Result<Block> {
        let m = unknowns.len();
        let mut local_of = vec![NONE; a.n];
        for (l, &g) in unknowns.iter().enumerate() {
            local_of[g] = l;
        }
        // Entries of A in the block (not between two interface unknowns), plus the
        // interface diagonal. The local numbering keeps the global order within the
        // interior and within the interface, so each column comes out sorted as its
        // interior rows, then its interface rows (of an interior column) or its diagonal
        // (of an interface column).
        // (at most the entries of the block's columns: no more reserved than that)
        let bound: usize = unknowns
            .iter()
            .map(|&c| a.col_ptr[c + 1] - a.col_ptr[c] + 1)
            .sum();
        let mut source = Vec::with_capacity(bound);
        let mut row_idx = Vec::with_capacity(bound);
        let mut col_ptr = Vec::with_capacity(m + 1);
        col_ptr.push(0);
        for (lc, &c) in unknowns.iter().enumerate() {
            let rows = a.col_ptr[c]..a.col_ptr[c + 1];
            for p in rows.clone() {
                let lr = local_of[a.row_idx[p]];
                if lr < interior {
                    row_idx.push(lr);
                    source.push(p);
                }
            }
            if lc >= interior {
                row_idx.push(lc);
                source.push(NONE);
            } else {
                for p in rows {
                    let lr = local_of[a.row_idx[p]];
                    if lr != NONE && lr >= interior {
                        row_idx.push(lr);
                        source.push(p);
                    }
                }
            }
            col_ptr.push(row_idx.len());
        }
        let diagonal = (0..interior)
            .filter_map(|l| {
                let q = (col_ptr[l]..col_ptr[l + 1]).find(|&q| row_idx[q] == l)?;
                Some(source[q])
            })
            .collect();
        // (pattern only: each factorisation reads the values of A, the factor's entries
        // labelled by their positions there)
        let local = SparseMatrix {
            n: m,
            values: vec![],
            col_ptr,
            row_idx,
            pattern_stamp: 0,
        };
        let mut fwd = leading_order(&local, interior)?;
        fwd.extend(interior..m);
        let mut ldlt = OrderedLdlt::with_storage(&local, fwd, storage)?;
        ldlt.relabel_origins(|p| source[p]);
        let k = m - interior;
        Ok(Block {
            unknowns,
            interior,
            gamma,
            factored: false,
            diagonal,
            ldlt,
            shift: -1.0,
            pivots: vec![],
            trailing: Mat::zeros(k, k),
            last_forward: None,
        })
    }

    /// Takes `a`, a matrix of another pattern, as this block's: true when the block's
    /// entries in it are those analysed (the pattern changed elsewhere, between interface
    /// unknowns: a contact pattern change), the factor's entries then labelled by their
    /// positions in `a`. With `beyond`, entries of `a` the analysis does not hold are
    /// passed over: their caller has found them zero (`growth.rs`). The last factorisation
    /// and its values are kept: when the block's values in `a` are the same, the next
    /// `factor` keeps them. False leaves the block unusable (its caller analyses `a`
    /// anew). `at`: the block's `positions`. (No copy of the block's pattern is made:
    /// fresh pages cost more than the comparison at 350k unknowns.)
    pub(super) fn rebind(&mut self, a: &SparseMatrix, at: &[usize], beyond: bool) -> bool {
        let interior = self.interior;
        let unknowns = &self.unknowns;
        let mut diagonal = vec![NONE; interior];
        // The block's matrix (see `local_pattern`): in an interior column, its interior rows
        // and its interface rows; in an interface column, its interior rows and its
        // diagonal (NONE). The interface unknowns are ordered last, so the lower triangle of
        // an interface column holds its diagonal alone.
        let rebound = self.ldlt.rebind_with(beyond, |j, l, out| {
            if l >= interior {
                out.push((j, NONE));
                return;
            }
            let c = unknowns[l];
            for p in a.col_ptr[c]..a.col_ptr[c + 1] {
                let r = at[a.row_idx[p]];
                if r != NONE && r >= j {
                    out.push((r, p));
                    if r == j {
                        diagonal[l] = p;
                    }
                }
            }
        });
        if !rebound {
            return false;
        }
        // (the same pattern: the same interior unknowns have a diagonal entry)
        diagonal.retain(|&p| p != NONE);
        self.diagonal = diagonal;
        true
    }

    /// Position in the factorised order of each global unknown of the block (NONE for the
    /// others), `n` unknowns in all.
    pub(super) fn positions(&self, n: usize) -> Vec<usize> {
        let mut at = vec![NONE; n];
        for (j, &l) in self.ldlt.order().iter().enumerate() {
            at[self.unknowns[l]] = j;
        }
        at
    }

    /// Whether the analysed pattern holds the entry between the unknowns at positions i
    /// and j of the factorised order (`positions`).
    pub(super) fn holds(&self, i: usize, j: usize) -> bool {
        self.ldlt.holds(i.max(j), i.min(j))
    }

    /// Whether the block's values in `a` are those of its last factorisation (which then
    /// stands). Each factorised entry is labelled by its position in A (NONE: the shifted
    /// diagonal of an interface unknown).
    pub(super) fn values_unchanged(&self, a: &SparseMatrix) -> bool {
        self.factored
            && self
                .ldlt
                .origins()
                .iter()
                .zip(self.ldlt.factored_values())
                .all(|(&p, &v)| p == NONE || a.values[p] == v)
    }

    /// Factorises the block's matrix in `a`; false when its values are those factorised
    /// last (nothing to do).
    pub(super) fn factor(&mut self, a: &SparseMatrix) -> Result<bool> {
        // Unchanged values (a Newton iteration that updated the contact terms only, which
        // live in Γ × Γ): the factorisation stands.
        if self.values_unchanged(a) {
            return Ok(false);
        }
        self.factored = false; // until this factorisation succeeds
        self.last_forward = None;
        // σ of the size of the block's largest diagonal entry: the trailing pivots are
        // then σ − (a positive semi-definite term), negative and well scaled.
        let diag = self
            .diagonal
            .iter()
            .map(|&p| a.values[p].abs())
            .fold(0.0f64, f64::max);
        self.shift = -diag.max(f64::MIN_POSITIVE);
        let shift = self.shift;
        self.ldlt
            .factor_with(|p, _, _| if p == NONE { shift } else { a.values[p] })?;
        let k = self.unknowns.len() - self.interior;
        // (L_ΓΓ and S' overwrite the last factorisation's in `trailing`'s storage; the
        // product's work matrices, like `ld`, are the allocator's to recycle)
        let d = self.ldlt.trailing_block(k, &mut self.trailing);
        let l = &self.trailing;
        let ld = Mat::from_fn(k, k, |i, j| if i >= j { l[(i, j)] * d[j] } else { 0.0 });
        // S' = L (D Lᵀ), symmetric: its lower half from the two triangles (a sixth of the
        // flops of the full product, every entry of it written), then moved above L
        let mut schur = Mat::<f64>::zeros(k, k);
        triangular::matmul(
            schur.as_mut(),
            BlockStructure::TriangularLower,
            Accum::Replace,
            l.as_ref(),
            BlockStructure::UnitTriangularLower,
            ld.transpose(),
            BlockStructure::TriangularUpper,
            1.0,
            Par::Seq,
        );
        for j in 0..k {
            for i in j..k {
                self.trailing[(j, i)] = schur[(i, j)];
            }
            self.trailing[(j, j)] -= self.shift;
        }
        let mut pivots = self.ldlt.pivots();
        pivots.truncate(self.interior);
        self.pivots = pivots;
        self.factored = true;
        Ok(true)
    }

    /// Column j of S'_b − σI (over the block's interface unknowns), from the upper half
    /// of `trailing` (its lower half holds L_ΓΓ).
    pub(super) fn schur_column(&self, j: usize) -> impl Iterator<Item = f64> + '_ {
        let t = &self.trailing;
        (0..t.nrows()).map(move |i| if i <= j { t[(i, j)] } else { t[(j, i)] })
    }
}
