//! An active-set re-solve's interface matrix as a low-rank change of the one last
//! factorised (Sherman–Morrison–Woodbury). Between two factorisations at one Newton point
//! the blocks are unchanged and only A's entries in Γ × Γ move, in the rows of the points
//! whose contact status changed (SSNP154 A point-to-segment at 98k unknowns: 10–350 rows
//! of about 1900). With T the matrix factorised (its LU at hand), E the unit columns of the
//! changed rows R and W = (T' − T)[R, :] (sparse), T' = T + E W and
//!   T'⁻¹ b = y − Z C⁻¹ W y,   y = T⁻¹ b,   Z = T⁻¹ E,   C = I + W Z   (r × r, r = |R|).
//! Z costs r solves with the LU (2k² flops each, against (2/3)k³ for a new LU), kept by
//! row until the next LU (the re-solves at one point share it); C's LU costs r³. A new LU
//! is made instead when R passes k / `MAX_ROWS_FRACTION` or C is near singular.

use super::dense_lu::DenseLu;
use super::reduced::Reduction;
use super::NONE;
use faer::Mat;

/// Changed rows allowed, as a fraction of the LU's order: Z's columns then cost at most
/// half a new LU.
pub(super) const MAX_ROWS_FRACTION: usize = 6;
/// C's smallest over largest pivot below which a new LU is made instead (the formula
/// loses about as many digits as C is near singular).
const MIN_PIVOT_RATIO: f64 = 1e-8;

/// The interface matrix as last factorised: the coupled unknowns `kept` (position
/// `at[i]` among them, NONE for a decoupled one) by `lu`, or by `reduction` when it is
/// reduced onto its live unknowns (`reduced.rs`), each decoupled unknown alone by its
/// `diagonal`.
#[derive(Default)]
pub(super) struct Factorised {
    pub lu: DenseLu,
    pub reduction: Option<Reduction>,
    pub kept: Vec<usize>,
    pub at: Vec<usize>,
    pub diagonal: Vec<f64>,
}

impl Factorised {
    /// x ← T⁻¹ x (x over the interface).
    pub(super) fn solve(&self, x: &mut [f64]) {
        let mut xr = Mat::<f64>::from_fn(self.kept.len(), 1, |i, _| x[self.kept[i]]);
        self.solve_coupled(&mut xr);
        for (i, v) in x.iter_mut().enumerate() {
            *v = match self.at[i] {
                NONE => *v / self.diagonal[i],
                p => xr[(p, 0)],
            };
        }
    }

    /// m ← T⁻¹ m over the coupled unknowns (rows: their positions in `kept`).
    pub(super) fn solve_coupled(&self, m: &mut Mat<f64>) {
        match &self.reduction {
            Some(r) => r.solve(m),
            None if m.ncols() > 1 => self.lu.solve_many(m),
            None => self.lu.solve(m),
        }
    }
}

/// The columns of Z = T⁻¹ E computed since the last LU, by interface row.
#[derive(Default)]
pub(super) struct ZColumns {
    of: Vec<usize>,
    columns: Vec<Vec<f64>>,
}

impl ZColumns {
    /// Forgets every column (a new LU), for an interface of k unknowns.
    pub(super) fn clear(&mut self, k: usize) {
        self.of.clear();
        self.of.resize(k, NONE);
        self.columns.clear();
    }

    /// Computes the columns of the rows that have none yet (T⁻¹ of their unit vectors, all
    /// the LU's ones in one multi-column solve).
    fn extend(&mut self, rows: &[usize], t: &Factorised) {
        let k = self.of.len();
        let new: Vec<usize> = rows
            .iter()
            .copied()
            .filter(|&r| self.of[r] == NONE)
            .collect();
        let coupled: Vec<usize> = new.iter().copied().filter(|&r| t.at[r] != NONE).collect();
        let mut m = Mat::<f64>::zeros(t.kept.len(), coupled.len());
        for (c, &r) in coupled.iter().enumerate() {
            m[(t.at[r], c)] = 1.0;
        }
        if !coupled.is_empty() {
            t.solve_coupled(&mut m);
        }
        let mut next = 0;
        for r in new {
            let mut column = vec![0.0; k];
            if t.at[r] == NONE {
                column[r] = 1.0 / t.diagonal[r];
            } else {
                for (i, &g) in t.kept.iter().enumerate() {
                    column[g] = m[(i, next)];
                }
                next += 1;
            }
            self.of[r] = self.columns.len();
            self.columns.push(column);
        }
    }

    fn column(&self, row: usize) -> &[f64] {
        &self.columns[self.of[row]]
    }
}

/// The change since the last LU, ready to solve with.
pub(super) struct Update {
    rows: Vec<usize>,
    /// (index in `rows`, interface column, new − factorised value)
    delta: Vec<(usize, usize, f64)>,
    /// C's equilibration: its LU is of diag(rows_scale) C diag(columns_scale).
    rows_scale: Vec<f64>,
    columns_scale: Vec<f64>,
    c: DenseLu,
}

impl Update {
    /// The update for the changed entries `changes` (interface row, column, new −
    /// factorised value) of the matrix `t` solves; None when a new LU should be made
    /// instead (too many rows, or C near singular).
    pub(super) fn new(
        changes: Vec<(usize, usize, f64)>,
        t: &Factorised,
        z: &mut ZColumns,
    ) -> Option<Update> {
        let mut rows: Vec<usize> = changes.iter().map(|c| c.0).collect();
        rows.sort_unstable();
        rows.dedup();
        // (Z's columns are kept for every row seen since the LU, also rows changed back:
        // at most twice as many as one update may use, so they never approach the LU's
        // own k² values)
        let unseen = rows.iter().filter(|&&r| z.of[r] == NONE).count();
        if rows.len() * MAX_ROWS_FRACTION > t.kept.len()
            || (z.columns.len() + unseen) * MAX_ROWS_FRACTION > 2 * t.kept.len()
        {
            return None;
        }
        z.extend(&rows, t);
        let delta: Vec<(usize, usize, f64)> = changes
            .into_iter()
            .map(|(i, j, d)| (rows.binary_search(&i).expect("a changed row"), j, d))
            .collect();
        let r = rows.len();
        // C = I + W Z, row by row of W (its entries are the changes)
        let mut c = Mat::<f64>::identity(r, r);
        for &(ri, j, d) in &delta {
            for (rc, &row) in rows.iter().enumerate() {
                c[(ri, rc)] += d * z.column(row)[j];
            }
        }
        // C equilibrated (rows, then columns, to a largest entry of one): W's rows and Z's
        // columns mix the sizes of contact and body terms, and the pivots (and the
        // near-singularity test on them) should see C's conditioning, not its units (the
        // solution is the same).
        let largest = |v: f64, m: f64| m.max(v.abs());
        let inverse = |m: f64| {
            if m > 0.0 && m.is_finite() {
                1.0 / m
            } else {
                1.0
            }
        };
        let rows_scale: Vec<f64> = (0..r)
            .map(|i| inverse((0..r).fold(0.0, |m, j| largest(c[(i, j)], m))))
            .collect();
        for j in 0..r {
            for (i, s) in rows_scale.iter().enumerate() {
                c[(i, j)] *= s;
            }
        }
        let columns_scale: Vec<f64> = (0..r)
            .map(|j| inverse((0..r).fold(0.0, |m, i| largest(c[(i, j)], m))))
            .collect();
        for (j, s) in columns_scale.iter().enumerate() {
            for i in 0..r {
                c[(i, j)] *= s;
            }
        }
        let mut lu = DenseLu::default();
        lu.factor(c);
        (lu.pivot_ratio() >= MIN_PIVOT_RATIO).then_some(Update {
            rows,
            delta,
            rows_scale,
            columns_scale,
            c: lu,
        })
    }

    /// y ← y − Z C⁻¹ W y: from T⁻¹ b to T'⁻¹ b.
    pub(super) fn apply(&self, y: &mut [f64], z: &ZColumns) {
        let mut v = Mat::<f64>::zeros(self.rows.len(), 1);
        for &(ri, j, d) in &self.delta {
            v[(ri, 0)] += d * y[j];
        }
        for (i, s) in self.rows_scale.iter().enumerate() {
            v[(i, 0)] *= s;
        }
        self.c.solve(&mut v);
        for (i, s) in self.columns_scale.iter().enumerate() {
            v[(i, 0)] *= s;
        }
        for (rc, &row) in self.rows.iter().enumerate() {
            let s = v[(rc, 0)];
            for (yi, zi) in y.iter_mut().zip(z.column(row)) {
                *yi -= s * zi;
            }
        }
    }
}
