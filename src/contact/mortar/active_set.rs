//! The active set's inputs: which slave nodes touch at the start, the nodal weighted gaps,
//! D_j and coverage, and the weights that scale the multiplier rows.

use super::super::projection::point_and_tangent;
use super::geometry::project_along;
use super::segments::CellTerms;
use super::Mortar;
use crate::mesh::Mesh;

/// The weighted gaps at the point of the last large-kinematics evaluation, with their
/// derivatives by displacement (sparse rows over u's dofs): the first-order model of the
/// contact constraints that the Newton correction from that point solves.
pub(super) struct Linearisation {
    pub u0: Vec<f64>,
    pub g: Vec<f64>,
    pub d: Vec<f64>,
    pub facing: Vec<bool>,
    pub dg: Vec<Vec<(usize, f64)>>,
}

impl Linearisation {
    /// Value plus derivative times (u − u0) for each node's row.
    fn extend(&self, value: &[f64], rows: &[Vec<(usize, f64)>], u: &[f64]) -> Vec<f64> {
        value
            .iter()
            .zip(rows)
            .map(|(v, row)| {
                v + row
                    .iter()
                    .map(|&(c, w)| w * (u[c] - self.u0[c]))
                    .sum::<f64>()
            })
            .collect()
    }
}

impl Mortar {
    /// Active set of the linearised problem at u: the nonlinear criterion with the gaps of
    /// the last evaluation extended linearly. Large kinematics far from the solution (a
    /// first iterate from a point contact pushes a body many cells deep) distorts the
    /// cells where the nonlinear gaps are measured; the linearised ones are those the
    /// correction itself satisfies. The friction branches are left to the iterate's own
    /// update: re-solved here too, they cycled at the ends of a shoe sliding round a ring
    /// (tests/history.rs: step cuts, 67 load steps for 60).
    pub(super) fn statuses_linearised(&mut self, u: &[f64], lam: &[f64]) -> Option<usize> {
        let guard = self.linearisation.lock().unwrap();
        let lin = guard.as_ref()?;
        let nm = self.mult_nodes.len();
        if lin.g.len() != nm || u.len() != lin.u0.len() {
            return None;
        }
        let g = lin.extend(&lin.g, &lin.dg, u);
        let (d, facing) = (lin.d.clone(), lin.facing.clone());
        drop(guard);
        // Nodes to release (negative pressure) go first, those to close (penetrating)
        // next: changing both at once cycles far from the solution (a first iterate from a
        // point contact closes nodes far out, whose pressures then pull the inner ones).
        let proposed: Vec<bool> = (0..nm)
            .map(|j| facing[j] && d[j] != 0.0 && lam[j] - self.c * g[j] / d[j] > 0.0)
            .collect();
        let releases = (0..nm).any(|j| self.active[j] && !proposed[j]);
        let mut changes = 0;
        for j in 0..nm {
            if proposed[j] != self.active[j] && (!releases || !proposed[j]) {
                changes += 1;
                self.active[j] = proposed[j];
            }
        }
        self.grow_pattern(Some(lam));
        Some(changes)
    }

    /// Whether slave corner node n touches the master: its own gap, measured along its
    /// averaged normal, is below 1e-6 of the adjacent slave cell size. (The weighted gap of
    /// a single touching point is positive, so it cannot start the active set.)
    pub(super) fn touching(&self, mesh: &Mesh, u: &[f64], n: usize) -> bool {
        // a mid-side node: only with an initial gap (a touching point is a corner)
        if !self.cells_of_node.contains_key(&n) && self.initial_gap.is_none() {
            return false;
        }
        self.nodal_gaps(mesh, u, n)
            .iter()
            .any(|&(gap, size)| gap <= self.initial_gap.unwrap_or(1e-6 * size))
    }

    /// Slave node n's own gaps (negative: penetrating) to the master cells it projects on,
    /// along its averaged normal (a mid-side node: its cell's normal there), each with the
    /// size of the slave cell it was measured from.
    pub(super) fn nodal_gaps(&self, mesh: &Mesh, u: &[f64], n: usize) -> Vec<(f64, f64)> {
        let mid_cells: Vec<usize>;
        let cells = match self.cells_of_node.get(&n) {
            Some(c) => c,
            None => {
                mid_cells = (0..self.slave.cells.len())
                    .filter(|&ic| mesh.cell_nodes(self.slave.cells[ic]).contains(&n))
                    .collect();
                &mid_cells
            }
        };
        let mut out = vec![];
        if cells.is_empty() {
            return out;
        }
        let x = Self::pos(mesh, u, n);
        let nv = if self.cells_of_node.contains_key(&n) {
            self.node_normal(mesh, u, n)
        } else {
            self.cell_normal(mesh, u, cells[0], 0.0)
        };
        for &ic in cells {
            let sn = mesh.cell_nodes(self.slave.cells[ic]);
            let (a, b) = (mesh.coords[sn[0]], mesh.coords[sn[1]]);
            let size = (a[0] - b[0]).hypot(a[1] - b[1]);
            for &im in &self.candidates[ic] {
                let mc = self.master.cells[im];
                let xm: Vec<[f64; 2]> = mesh
                    .cell_nodes(mc)
                    .iter()
                    .map(|&m| Self::pos(mesh, u, m))
                    .collect();
                let (xi, _) = project_along(mesh.kind(mc), &xm, x, nv);
                if xi.abs() <= 1.0 + 1e-9 {
                    let (pm, _) = point_and_tangent(mesh.kind(mc), &xm, xi);
                    out.push(((pm[0] - x[0]) * nv[0] + (pm[1] - x[1]) * nv[1], size));
                }
            }
        }
        out
    }

    /// Weighted gaps, D_j, whether each slave node faces the master surface (at least
    /// half of ∫ N_j is covered by master segments) and the weighted slips (zero without
    /// friction) at u.
    #[allow(clippy::type_complexity)]
    pub(super) fn gaps(&self, mesh: &Mesh, u: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<bool>, Vec<f64>) {
        let nm = self.mult_nodes.len();
        let (mut g, mut d) = (vec![0.0; nm], vec![0.0; nm]);
        let mut sl = vec![0.0; nm];
        // (measured from the removed initial gaps, once `initialise` has set them)
        for (k, o) in self.offset.iter().enumerate() {
            g[k] = -o;
        }
        let terms = self.all_cell_terms(mesh, u);
        for t in &terms {
            for &(k, v) in &t.gap {
                g[k] += v;
            }
            for &(k, v) in &t.dj {
                d[k] += v;
            }
            for &(k, v) in &t.slip {
                sl[k] += v;
            }
        }
        let facing = self.facing(mesh, u, &terms, &d);
        *self.terms_cache.lock().unwrap() = Some((u.to_vec(), terms));
        (g, d, facing, sl)
    }

    /// Every slave cell's terms at u (in parallel).
    pub(super) fn all_cell_terms(&self, mesh: &Mesh, u: &[f64]) -> Vec<super::segments::CellTerms> {
        use rayon::prelude::*;
        (0..self.slave.cells.len())
            .into_par_iter()
            .map(|ic| self.cell_terms(mesh, u, ic))
            .collect()
    }

    /// Whether each slave node faces the master, from the cells' terms `terms` at u: more
    /// than half of its ∫ N_j covered by master segments, and all of its cells covered
    /// unless a master end lies within them. A node under the master's end (the corner
    /// of a block on a longer foundation that carries the multipliers) sits at half,
    /// where the iterates' tiny motions of the corner flip it, and its activity with it (a
    /// 2-cycle at any step size): an active one there goes on facing down to 0.4. A node
    /// of `exclude` faces nothing (it never takes contact).
    ///
    /// Elsewhere a cell partly covered is one at the edge of the candidate search (master
    /// cells within about a cell size): the rest of its projection lies on master cells
    /// not searched, and its nodes' weighted gaps integrate part of their support only.
    /// With quadratic cells Φ_j changes sign along a cell, so such a gap can be of either
    /// sign whatever the distance: SSNP154 D at 93k unknowns, a load step's start, had a
    /// node open by a cell size with a negative gap, the linearised active set closed it
    /// and the correction put 80× the peak pressure on a node near it (17 of 39
    /// iterations spent undoing that). Such a node is taken as not facing: once the
    /// iterate brings it near, the search finds its whole projection.
    pub(super) fn facing(
        &self,
        mesh: &Mesh,
        u: &[f64],
        terms: &[CellTerms],
        d: &[f64],
    ) -> Vec<bool> {
        let nm = d.len();
        let mut cov = vec![0.0; nm];
        let mut whole = vec![true; nm];
        for (t, mults) in terms.iter().zip(&self.cell_mults) {
            for &(k, v) in &t.cover {
                cov[k] += v;
            }
            if t.span < 1.0 - 1e-9 {
                for &k in mults {
                    whole[k] = false;
                }
            }
        }
        (0..nm)
            .map(|k| {
                if self.contact_excluded.contains(&k) || cov[k] <= 0.4 * d[k] {
                    return false;
                }
                // (the master end is looked for only where it matters: an active node, or
                // one partly covered)
                let active = self.active.get(k).copied().unwrap_or(false);
                let at_end = (active || !whole[k]) && self.under_master_end(mesh, u, k);
                let held = active && at_end;
                cov[k] > if held { 0.4 } else { 0.5 } * d[k] && (whole[k] || at_end)
            })
            .collect()
    }

    /// Whether an end of the master chain lies within a cell of slave node k: within its
    /// longest cell's length of the node, and END_MARGIN of it more. An end on the far
    /// corner of the cell (a cylinder's bottom on the axis, over a block's corner there)
    /// sits at that length, a gap's worth beyond it or not as the iterates move: the node
    /// then faced and did not in turn, active with a large pressure and released (SSNP154
    /// D with mortar at 8k unknowns, the second step: 76 Newton iterations, a 2-cycle).
    pub(super) fn under_master_end(&self, mesh: &Mesh, u: &[f64], k: usize) -> bool {
        let n = self.mult_nodes[k];
        let x = Self::pos(mesh, u, n);
        let reach = self
            .slave
            .cells
            .iter()
            .filter(|&&c| mesh.cell_nodes(c).contains(&n))
            .map(|&c| {
                let nodes = mesh.cell_nodes(c);
                let (a, b) = (Self::pos(mesh, u, nodes[0]), Self::pos(mesh, u, nodes[1]));
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
            .fold(0.0, f64::max)
            * (1.0 + END_MARGIN);
        self.master_ends.iter().any(|&m| {
            let y = Self::pos(mesh, u, m);
            (x[0] - y[0]).hypot(x[1] - y[1]) <= reach
        })
    }
}

/// The margin of `Mortar::under_master_end`, as a fraction of the cell's length.
const END_MARGIN: f64 = 0.01;

/// The weight D_j scaling each node's multiplier rows; a weightless node (on the axis) gets
/// the largest weight, so that its row sets its multiplier to zero on the usual scale.
pub(super) fn row_weights(d: &[f64]) -> Vec<f64> {
    let dref = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    d.iter().map(|&v| if v != 0.0 { v } else { dref }).collect()
}
