//! Sparse direct solves with faer: Cholesky (LLᵀ) for symmetric positive definite systems,
//! for contact saddle-point systems the condensation on the contact interface
//! (`interface.rs`) or LDLᵀ with a constrained ordering, LU otherwise. The symbolic
//! factorisation is kept and reused while the pattern is unchanged (compared with a copy
//! of the last pattern).

use super::gmres;
use super::interface::{interface_of, interface_searched, InterfaceSolver, Storage};
use super::ldlt::SaddleLdlt;
use crate::assembly::matrix::SparseMatrix;
use crate::error::{Error, Result};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, Lu, SymbolicLlt, SymbolicLu};
use faer::Side;

/// The factorisation behind the saddle-point solves: the exact one condensed on the
/// contact interface when the interface is small, else the LDLᵀ of a symmetric
/// approximation (GMRES makes either exact).
enum Factorisation {
    Interface(Box<InterfaceSolver>),
    Saddle(Box<SaddleLdlt>),
}

impl Factorisation {
    /// `transpose` is emptied when the interface path is taken: only its choice reads it.
    /// `storage`: that of the last analysis (`Factorisation::into_storage`).
    fn new(
        a: &SparseMatrix,
        np: usize,
        transpose: &mut Vec<usize>,
        storage: Storage,
    ) -> Result<Self> {
        Ok(match interface_of(a, np, transpose) {
            Some(in_gamma) => {
                *transpose = vec![];
                Factorisation::Interface(Box::new(
                    InterfaceSolver::new(a, in_gamma, storage)?.with_multipliers_from(np),
                ))
            }
            None => {
                drop(storage);
                Factorisation::Saddle(Box::new(SaddleLdlt::new(a, np)?))
            }
        })
    }
    fn into_storage(self) -> Storage {
        match self {
            Factorisation::Interface(s) => s.into_storage(),
            Factorisation::Saddle(_) => Storage::default(),
        }
    }
    fn factor(&mut self, a: &SparseMatrix, transpose: &[usize]) -> Result<()> {
        match self {
            Factorisation::Interface(s) => s.factor(a),
            Factorisation::Saddle(s) => s.factor(a, transpose),
        }
    }
    /// GMRES iterations allowed when it preconditions a later matrix: about the cost of
    /// one factorisation (an interface solve costs about a quarter of its factorisation).
    fn reuse_budget(&self) -> usize {
        match self {
            Factorisation::Interface(_) => 3,
            Factorisation::Saddle(_) => REUSE_ITERATIONS,
        }
    }
    fn solve(&mut self, b: &mut [f64]) {
        match self {
            Factorisation::Interface(s) => s.solve(b),
            Factorisation::Saddle(s) => s.solve(b),
        }
    }
}

/// How the last factorised pattern is recognised.
enum Pattern {
    Stamp(u64),
    Copy(Vec<usize>, Vec<usize>),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    Cholesky,
    /// Symmetric saddle point: the first `n_primal` unknowns are displacements.
    SaddleLdlt,
    Lu,
}

pub struct LinearSolver {
    pub method: Method,
    /// The pattern of the last factorised matrix, if valid: its stamp when it has one
    /// (see `SparseMatrix::pattern_stamp`), else a copy (column pointers, row indices).
    pattern: Option<Pattern>,
    /// For `SaddleLdlt`: number of leading primal (displacement) unknowns.
    pub n_primal: usize,
    ldlt: Option<Factorisation>,
    /// The large buffers of the last analysis, while the next one is not made.
    storage: Storage,
    sym_llt: Option<SymbolicLlt<usize>>,
    sym_lu: Option<SymbolicLu<usize>>,
    llt: Option<Llt<usize, f64>>,
    lu: Option<Lu<usize, f64>>,
    /// Number of symbolic factorisations done (for reports and tests of reuse).
    pub symbolic_count: usize,
    /// SaddleLdlt: the position of each entry's transpose.
    transpose: Vec<usize>,
    /// GMRES iterations done in the last solve (SaddleLdlt).
    pub gmres_iterations: usize,
    /// SaddleLdlt: the symmetric part could not serve (not structurally symmetric, a zero
    /// pivot at a fresh factorisation); LU of the exact matrix is used from then on.
    lu_fallback: bool,
    /// GMRES stalled on the current matrix: its solves use LU.
    stalled: bool,
    /// How many times GMRES stalled (each time LU solved instead).
    pub gmres_stalls: usize,
    /// SaddleLdlt: keep the last numeric factorisation as the preconditioner of the next
    /// matrices while GMRES converges fast with it (set by the caller).
    pub reuse_factor: bool,
    /// The numeric LDLᵀ is of the matrix last given to `factor` (not of an earlier one).
    factor_current: bool,
    /// The next `factor` must factorise (GMRES was slow with the old factorisation).
    refresh: bool,
    /// Numeric factorisations done (deferred ones not counted).
    pub numeric_count: usize,
    /// Failed reuses in a row, and how many factorisations to do before trying again.
    failed_reuses: u32,
    skip_reuse: usize,
}

impl LinearSolver {
    pub fn new(method: Method) -> Self {
        faer::set_global_parallelism(faer::Par::Seq);
        LinearSolver {
            method,
            pattern: None,
            n_primal: 0,
            ldlt: None,
            storage: Storage::default(),
            sym_llt: None,
            sym_lu: None,
            llt: None,
            lu: None,
            symbolic_count: 0,
            transpose: vec![],
            gmres_iterations: 0,
            lu_fallback: false,
            stalled: false,
            gmres_stalls: 0,
            reuse_factor: false,
            factor_current: false,
            refresh: true,
            numeric_count: 0,
            failed_reuses: 0,
            skip_reuse: 0,
        }
    }

    /// Whether saddle-point tangents are condensed on the contact interface (a tangent
    /// that differs from the last one in its contact terms only then costs the interface
    /// factorisation alone).
    pub fn condenses_contact(&self) -> bool {
        matches!(self.ldlt, Some(Factorisation::Interface(_))) && !self.lu_fallback
    }

    /// Where tangents are condensed on the contact interface: how many solves one
    /// factorisation of the bodies costs (`InterfaceSolver::solves_per_factorisation`).
    pub fn solves_per_factorisation(&self) -> Option<f64> {
        match &self.ldlt {
            Some(Factorisation::Interface(s)) if self.condenses_contact() => {
                Some(s.solves_per_factorisation())
            }
            _ => None,
        }
    }

    /// Numeric factorisation of `a`, reusing the symbolic one when the pattern is unchanged.
    pub fn factor(&mut self, a: &SparseMatrix) -> Result<()> {
        self.stalled = false;
        let unchanged = self.pattern.as_ref().is_some_and(|p| match p {
            Pattern::Stamp(s) => *s == a.pattern_stamp,
            Pattern::Copy(c, r) => a.pattern_stamp == 0 && *c == a.col_ptr && *r == a.row_idx,
        });
        if !unchanged {
            self.sym_llt = None;
            self.sym_lu = None;
            if !self.rebind(a) {
                self.drop_analysis();
            }
            self.pattern = Some(if a.pattern_stamp != 0 {
                Pattern::Stamp(a.pattern_stamp)
            } else {
                Pattern::Copy(a.col_ptr.clone(), a.row_idx.clone())
            });
        }
        // a grown pattern taken while its new entries were zero: one of them no longer is,
        // or the bodies are to be factorised anyway
        if let Some(Factorisation::Interface(s)) = &self.ldlt {
            if !s.stands(a) {
                self.drop_analysis();
            }
        }
        match self.method {
            Method::Cholesky => {
                let mat = a.as_faer();
                if self.sym_llt.is_none() {
                    self.sym_llt = Some(
                        SymbolicLlt::try_new(mat.symbolic(), Side::Lower).map_err(|e| {
                            memory_error(&e, mat.nrows()).unwrap_or_else(|| {
                                Error::solve(format!("symbolic Cholesky failed: {e:?}"))
                            })
                        })?,
                    );
                    self.symbolic_count += 1;
                }
                let sym = self.sym_llt.clone().unwrap();
                self.llt = Some(Llt::try_new_with_symbolic(sym, mat, Side::Lower).map_err(|e| {
                    if let Some(oom) = memory_error(&e, mat.nrows()) {
                        return oom;
                    }
                    Error::solve(format!(
                        "the stiffness matrix is not positive definite ({e:?}): the model probably has a \
                         rigid-body mode (a body not held by imposed displacements or contact) or an \
                         unstable state"
                    ))
                })?);
            }
            Method::SaddleLdlt if self.lu_fallback => self.factor_lu(a)?,
            Method::SaddleLdlt => {
                // Factorise the symmetric part; `solve` refines with the exact matrix, so a
                // slightly non-symmetric tangent (contact geometry terms) is solved exactly.
                let fresh = self.ldlt.is_none();
                if fresh {
                    // (taken here: the LU fallback below has no use for it)
                    let storage = std::mem::take(&mut self.storage);
                    self.transpose = transpose_positions(a);
                    if self.transpose.contains(&usize::MAX) {
                        // not structurally symmetric: no symmetric part to factorise
                        drop(storage);
                        self.lu_fallback = true;
                        return self.factor_lu(a);
                    }
                    self.ldlt = Some(Factorisation::new(
                        a,
                        self.n_primal,
                        &mut self.transpose,
                        storage,
                    )?);
                    self.symbolic_count += 1;
                }
                if self.skip_reuse > 0 {
                    self.skip_reuse -= 1;
                    self.refresh = true;
                }
                if !fresh && self.reuse_factor && !self.refresh {
                    // deferred: `solve` tries the previous factorisation first
                    self.factor_current = false;
                    return Ok(());
                }
                self.refresh = false;
                self.factor_current = true;
                self.numeric_count += 1;
                let f = self.ldlt.as_mut().expect("analysed above");
                if f.factor(a, &self.transpose).is_err() {
                    // A zero pivot of the symmetric part (possible when the tangent is not
                    // symmetric): LU of the exact matrix decides whether it is singular.
                    self.lu_fallback = true;
                    self.ldlt = None;
                    return self.factor_lu(a);
                }
            }
            Method::Lu => self.factor_lu(a)?,
        }
        Ok(())
    }

    /// Drops the analysis at hand (the next `factor` makes a new one); its large buffers
    /// go to the next analysis.
    fn drop_analysis(&mut self) {
        self.storage = self
            .ldlt
            .take()
            .map(Factorisation::into_storage)
            .unwrap_or_default();
    }

    /// A changed pattern that the interface condensation in hand takes as its own (see
    /// `InterfaceSolver::rebind`, and `rebind_grown` for a grown one whose new entries are
    /// zero): no new analysis. (A condensation exists only on the
    /// saddle-point path without LU fallback.)
    fn rebind(&mut self, a: &SparseMatrix) -> bool {
        let Some(Factorisation::Interface(s)) = self.ldlt.as_mut() else {
            return false;
        };
        interface_searched(a, self.n_primal)
            .is_some_and(|in_gamma| s.rebind(a, &in_gamma) || s.rebind_grown(a, &in_gamma))
    }

    fn factor_lu(&mut self, a: &SparseMatrix) -> Result<()> {
        if self.sym_lu.is_none() {
            self.sym_lu = Some(SymbolicLu::try_new(a.as_faer().symbolic()).map_err(|e| {
                memory_error(&e, a.n)
                    .unwrap_or_else(|| Error::solve(format!("symbolic LU failed: {e:?}")))
            })?);
            self.symbolic_count += 1;
        }
        let sym = self.sym_lu.clone().unwrap();
        self.lu = Some(Lu::try_new_with_symbolic(sym, a.as_faer()).map_err(|e| {
            memory_error(&e, a.n)
                .unwrap_or_else(|| Error::solve(format!("the system matrix is singular ({e:?})")))
        })?);
        Ok(())
    }

    fn solve_lu(&self, b: &mut [f64]) {
        let n = b.len();
        self.lu
            .as_ref()
            .expect("factor before solve")
            .solve_in_place(faer::MatMut::from_column_major_slice_mut(b, n, 1));
    }

    /// Solves a x = b in place, `a` the matrix last given to `factor`; fails on a
    /// non-finite result. An exact factorisation solves alone (the interface condensation
    /// of the current matrix too: a GMRES check there never iterated on SSNP154, and
    /// Newton's residual, always the true one, judges the step anyway); the LDLᵀ of a
    /// symmetric approximation, or an earlier factorisation, goes through GMRES.
    pub fn solve(&mut self, a: &SparseMatrix, b: &mut [f64]) -> Result<()> {
        if self.factorisation_is_exact() {
            self.solve_with_factorisation(b)
        } else {
            self.solve_iterative(a, b)?
        }
        finite(b)
    }

    /// SaddleLdlt: solves go through LU (no usable symmetric part, or GMRES stalled on
    /// the current matrix).
    fn lu_solves(&self) -> bool {
        self.lu_fallback || self.stalled
    }

    /// Whether the last factorisation is of the matrix last given to `factor` and solves it
    /// exactly by itself (Cholesky, LU, the condensation on the contact interface; not the
    /// LDLᵀ of a symmetric approximation).
    pub fn factorisation_is_exact(&self) -> bool {
        match self.method {
            Method::Cholesky | Method::Lu => true,
            Method::SaddleLdlt => {
                self.lu_solves()
                    || (self.factor_current
                        && matches!(self.ldlt, Some(Factorisation::Interface(_))))
            }
        }
    }

    /// Solves in place with the last factorisation alone (for a chord step: a correction
    /// with the matrix it was made of, while the system has moved on).
    pub fn solve_factored(&mut self, b: &mut [f64]) -> Result<()> {
        self.solve_with_factorisation(b);
        finite(b)
    }

    fn solve_with_factorisation(&mut self, b: &mut [f64]) {
        let n = b.len();
        match self.method {
            Method::Cholesky => self
                .llt
                .as_ref()
                .expect("factor before solve")
                .solve_in_place(faer::MatMut::from_column_major_slice_mut(b, n, 1)),
            Method::SaddleLdlt if !self.lu_solves() => {
                self.ldlt.as_mut().expect("factor before solve").solve(b)
            }
            _ => self.solve_lu(b),
        }
    }
}

fn finite(b: &[f64]) -> Result<()> {
    if b.iter().any(|v| !v.is_finite()) {
        return Err(Error::solve(
            "the linear solve produced non-finite values (singular system)",
        ));
    }
    Ok(())
}

/// GMRES iterations allowed with a reused saddle-point LDLᵀ (about the cost of one
/// factorisation on the SSNP154 meshes).
const REUSE_ITERATIONS: usize = 8;

impl LinearSolver {
    /// A x = b by GMRES on the exact matrix, preconditioned by the factorisation: that of
    /// an earlier tangent (see `reuse_factor`), or the LDLᵀ of a symmetric approximation
    /// (`SaddleLdlt::factor`), which is exact for a symmetric tangent and needs a few
    /// iterations for the contact tangents that are not. If GMRES stalls (a tangent
    /// far from symmetric), LU of the exact matrix takes over for the solves with this
    /// matrix (the next tangent tries GMRES again: a stall is usually one friction state,
    /// and LU costs several LDLᵀ factorisations).
    fn solve_iterative(&mut self, exact: &SparseMatrix, b: &mut [f64]) -> Result<()> {
        let rhs = b.to_vec();
        if !self.factor_current {
            // The factorisation of an earlier tangent as preconditioner: a few GMRES
            // iterations when the tangent changed little (small steps, few status changes).
            // A fixed budget (not a timed one) keeps the results reproducible bit for bit;
            // past half of it the next matrix is factorised.
            let f = self.ldlt.as_mut().expect("factor before solve");
            let budget = f.reuse_budget();
            f.solve(b);
            let reused = gmres::solve(
                &mut |v, out| exact.mul_vec_par(v, out),
                &mut |v| f.solve(v),
                &rhs,
                b,
                1e-12,
                budget,
                budget,
            );
            match reused {
                Ok(its) => {
                    self.gmres_iterations = its;
                    self.refresh = 2 * its > budget;
                    self.failed_reuses = 0;
                    return Ok(());
                }
                Err(_) => {
                    // factorise this matrix after all, and the next ones for a while
                    // (doubling after each failure in a row: big steps change the tangent)
                    self.failed_reuses += 1;
                    self.skip_reuse = 1 << self.failed_reuses.min(6);
                    self.numeric_count += 1;
                    self.factor_current = true;
                    let f = self.ldlt.as_mut().expect("factor before solve");
                    if f.factor(exact, &self.transpose).is_err() {
                        return self.solve_by_lu(exact, &rhs, b);
                    }
                    b.copy_from_slice(&rhs);
                }
            }
        }
        let f = self.ldlt.as_mut().expect("factor before solve");
        f.solve(b); // start from M⁻¹ b: enough when the tangent is symmetric
        let result = gmres::solve(
            &mut |v, out| exact.mul_vec_par(v, out),
            &mut |v| f.solve(v),
            &rhs,
            b,
            1e-12,
            30,
            60,
        );
        match result {
            Ok(its) => {
                self.gmres_iterations = its;
                Ok(())
            }
            Err(_) => self.solve_by_lu(exact, &rhs, b),
        }
    }

    /// LU of the current matrix solves `rhs` into `b` (GMRES stalled or the symmetric part
    /// has a zero pivot); the next matrix tries LDLᵀ and GMRES again.
    fn solve_by_lu(&mut self, exact: &SparseMatrix, rhs: &[f64], b: &mut [f64]) -> Result<()> {
        self.stalled = true;
        self.gmres_stalls += 1;
        self.factor_lu(exact)?;
        b.copy_from_slice(rhs);
        self.solve_lu(b);
        Ok(())
    }
}

/// For each entry (r, c) of `a`, the position of (c, r), or usize::MAX if not in the pattern.
/// Columns are visited in order, so the cursor in each column only moves forward; the two
/// halves of the columns in parallel (the second half's cursors start past the rows of the
/// first).
pub fn transpose_positions(a: &SparseMatrix) -> Vec<usize> {
    let mut out = vec![usize::MAX; a.nnz()];
    let mid = a.n / 2;
    let (lo, hi) = out.split_at_mut(a.col_ptr[mid]);
    rayon::join(
        || transpose_columns(a, 0..mid, lo),
        || transpose_columns(a, mid..a.n, hi),
    );
    out
}

/// `transpose_positions` for the columns `cols`, into `out` (their entries).
fn transpose_columns(a: &SparseMatrix, cols: std::ops::Range<usize>, out: &mut [usize]) {
    let first = cols.start;
    let offset = a.col_ptr[first];
    // in each column, the first row not before column `first`
    let mut cursor: Vec<usize> = (0..a.n)
        .map(|r| {
            let rows = &a.row_idx[a.col_ptr[r]..a.col_ptr[r + 1]];
            a.col_ptr[r] + rows.partition_point(|&x| x < first)
        })
        .collect();
    for c in cols {
        for p in a.col_ptr[c]..a.col_ptr[c + 1] {
            let r = a.row_idx[p];
            let end = a.col_ptr[r + 1];
            while cursor[r] < end && a.row_idx[cursor[r]] < c {
                cursor[r] += 1;
            }
            if cursor[r] < end && a.row_idx[cursor[r]] == c {
                out[p - offset] = cursor[r];
            }
        }
    }
}

/// A faer failure that is a failed allocation, reported as such (it is no singular
/// matrix, and cutting the load step will not help): `n` unknowns.
pub fn memory_error(e: &impl std::fmt::Debug, n: usize) -> Option<Error> {
    format!("{e:?}").contains("OutOfMemory").then(|| {
        let (avail, source) = crate::memory::available().unwrap_or((0, "unknown"));
        Error::Memory(format!(
            "out of memory factorising the stiffness matrix ({n} unknowns; {} available, \
             {source}): use a coarser mesh or a machine with more memory",
            crate::memory::show(avail)
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn laplacian(n: usize, shift: f64) -> SparseMatrix {
        let cols = (0..n).map(|j| {
            let mut c = vec![];
            if j > 0 {
                c.push(j - 1);
            }
            c.push(j);
            if j + 1 < n {
                c.push(j + 1);
            }
            c
        });
        let mut a = SparseMatrix::from_columns(n, cols);
        for j in 0..n {
            for p in a.col_ptr[j]..a.col_ptr[j + 1] {
                a.values[p] = if a.row_idx[p] == j { 2.0 + shift } else { -1.0 };
            }
        }
        a
    }

    #[test]
    fn a_stamped_pattern_is_recognised_without_a_copy() {
        let mut s = LinearSolver::new(Method::Cholesky);
        let mut a = laplacian(30, 0.1);
        a.pattern_stamp = crate::assembly::matrix::new_pattern_stamp();
        s.factor(&a).unwrap();
        assert!(matches!(s.pattern, Some(Pattern::Stamp(_))));
        a.values.iter_mut().for_each(|v| *v *= 2.0);
        s.factor(&a).unwrap();
        assert_eq!(s.symbolic_count, 1);
        // a new stamp is a new pattern (analysed again), as is an unstamped matrix
        a.pattern_stamp = crate::assembly::matrix::new_pattern_stamp();
        s.factor(&a).unwrap();
        assert_eq!(s.symbolic_count, 2);
        a.pattern_stamp = 0;
        s.factor(&a).unwrap();
        s.factor(&a).unwrap();
        assert_eq!(s.symbolic_count, 3);
    }

    #[test]
    fn cholesky_and_lu_solve_and_reuse_symbolic() {
        for method in [Method::Cholesky, Method::Lu] {
            let mut s = LinearSolver::new(method);
            for shift in [0.1, 0.5] {
                let a = laplacian(50, shift);
                s.factor(&a).unwrap();
                let x: Vec<f64> = (0..50).map(|i| (i as f64).sin()).collect();
                let mut b = vec![0.0; 50];
                a.mul_vec(&x, &mut b);
                s.solve(&a, &mut b).unwrap();
                for i in 0..50 {
                    assert!((b[i] - x[i]).abs() < 1e-12);
                }
            }
            assert_eq!(s.symbolic_count, 1);
        }
    }

    #[test]
    fn transpose_positions_match_a_search() {
        let cols = (0..6).map(|c| match c {
            0 => vec![0, 2, 5],
            1 => vec![1, 3],
            2 => vec![0, 2],
            3 => vec![3, 4],
            4 => vec![1, 4],
            _ => vec![0, 5],
        });
        let a = SparseMatrix::from_columns(6, cols);
        let t = transpose_positions(&a);
        for c in 0..6 {
            for p in a.col_ptr[c]..a.col_ptr[c + 1] {
                assert_eq!(t[p], a.position(c, a.row_idx[p]).unwrap_or(usize::MAX));
            }
        }
        assert!(t.contains(&usize::MAX)); // (3, 1) has no (1, 3) partner... and so on
    }

    #[test]
    fn singular_matrix_is_reported() {
        let a = laplacian(10, -2.0); // -1 on the off-diagonals, 0 on the diagonal: indefinite
        let mut s = LinearSolver::new(Method::Cholesky);
        let err = s.factor(&a).unwrap_err().to_string();
        assert!(
            err.starts_with("the stiffness matrix is not positive definite"),
            "{err}"
        );
    }
}
