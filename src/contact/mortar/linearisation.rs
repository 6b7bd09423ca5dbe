//! The tangent of the mortar terms, exact. Small kinematics: the terms are linear in u on
//! the reference geometry. Large kinematics: forward-mode automatic differentiation of the
//! cell kernel (`segments.rs`) with dual numbers, per slave cell and master cell: the
//! derivatives with respect to the slave cell's nodes, its two corner normals and the
//! master cell's nodes (16 slots), the corner normals then chained to the nodes of the
//! cells that share the corner. They contain every geometric variation (normals, segment
//! ends, projections, Jacobians, the dual basis).

use super::friction::Branch;
use super::geometry::averaged_normal_at;
use super::segments::{CellTerms, Overlap, SlaveCell};
use super::Mortar;
use crate::assembly::coupled::Triplets;
use crate::mesh::Mesh;
use num_dual::DualSVec64;
use rayon::prelude::*;

/// Derivative slots: slave cell nodes 0..6, its corner normals 6..10, master cell nodes
/// 10..16 (two per node, x then y).
type Dual = DualSVec64<16>;

/// Per multiplier index, (column, value) pairs sorted by column.
pub(super) type SparseRows = Vec<Vec<(usize, f64)>>;

fn seed(v: f64, slot: usize) -> Dual {
    Dual::from_re(v).derivative(slot)
}

/// One slave cell's derivatives: of the contracted force rows (row, column, value), and
/// per multiplier index of the weighted gaps, D_j and the weighted slips (j, column, value).
#[derive(Default)]
struct CellDerivatives {
    rows: Vec<(usize, usize, f64)>,
    dg: Vec<(usize, usize, f64)>,
    dd: Vec<(usize, usize, f64)>,
    ds: Vec<(usize, usize, f64)>,
}

/// Sums the entries of each multiplier's derivative per column (sorted by column).
fn by_multiplier(entries: Vec<(usize, usize, f64)>, nm: usize) -> Vec<Vec<(usize, f64)>> {
    let mut out: Vec<Vec<(usize, f64)>> = vec![vec![]; nm];
    for (j, col, v) in entries {
        out[j].push((col, v));
    }
    for e in out.iter_mut() {
        merge(e);
    }
    out
}

/// Sorts (index, value) pairs by index and sums duplicates.
fn merge(e: &mut Vec<(usize, f64)>) {
    e.sort_by_key(|p| p.0);
    let mut w = 0;
    for r in 0..e.len() {
        if w > 0 && e[w - 1].0 == e[r].0 {
            e[w - 1].1 += e[r].1;
        } else {
            e[w] = e[r];
            w += 1;
        }
    }
    e.truncate(w);
}

/// The exact tangent of the contact terms with small kinematics: on the fixed reference
/// geometry the weighted gaps and slips are linear in u (their derivatives are minus the
/// normal force coefficients and the tangential ones), D_j and the coefficients constant.
/// `base` is the first multiplier row.
#[allow(clippy::too_many_arguments)]
pub(super) fn linear_tangent(
    terms: &[CellTerms],
    c: f64,
    active: &[bool],
    d: &[f64],
    law: &[Branch],
    base: usize,
    nm: usize,
    k: &mut Triplets,
) {
    use std::collections::BTreeMap;
    let mut f: Vec<BTreeMap<usize, f64>> = vec![BTreeMap::new(); nm];
    let mut tf: Vec<BTreeMap<usize, f64>> = vec![BTreeMap::new(); nm];
    for t in terms {
        for &(j, dof, v) in &t.force {
            if active[j] {
                *f[j].entry(dof).or_insert(0.0) += v;
            }
        }
        for &(j, dof, v) in &t.tforce {
            if law[j] == Branch::Stick {
                *tf[j].entry(dof).or_insert(0.0) += v;
            }
        }
    }
    for j in 0..nm {
        if !active[j] {
            continue;
        }
        // row g̃_j = 0: −∂g̃_j/∂u = F_j; augmentation −c g̃_j/D_j F_j: (c/D_j) F_j F_jᵀ
        let scale = c / d[j];
        for (&dof, &v) in &f[j] {
            k.add(base + j, dof, v);
            for (&col, &w) in &f[j] {
                k.add(dof, col, scale * v * w);
            }
        }
        // stick row s̃_j = 0: −∂s̃_j/∂u = −T_j
        for (&dof, &v) in &tf[j] {
            k.add(base + nm + j, dof, -v);
        }
    }
}

impl Mortar {
    /// The derivatives of a slave corner's averaged normal with respect to the nodes of
    /// the cells sharing it: its value and (dof, ∂n/∂dof) per dof.
    fn normal_jacobian(
        &self,
        mesh: &Mesh,
        u: &[f64],
        n: usize,
    ) -> ([f64; 2], Vec<(usize, [f64; 2])>) {
        let cells = &self.cells_of_node[&n];
        let mut nodes: Vec<usize> = cells
            .iter()
            .flat_map(|&ic| mesh.cell_nodes(self.slave.cells[ic]).iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        let pos = |m: usize| {
            let k = nodes.iter().position(|&x| x == m).unwrap();
            let p = Self::pos(mesh, u, m);
            [seed(p[0], 2 * k), seed(p[1], 2 * k + 1)]
        };
        let v = averaged_normal_at(mesh, &self.slave, cells, n, &pos);
        let e = [
            v[0].eps.0.unwrap_or_default(),
            v[1].eps.0.unwrap_or_default(),
        ];
        let jac = nodes
            .iter()
            .enumerate()
            .flat_map(|(k, &m)| (0..2).map(move |c| (k, m, c)))
            .map(|(k, m, c)| (2 * m + c, [e[0][2 * k + c], e[1][2 * k + c]]))
            .collect();
        ([v[0].re, v[1].re], jac)
    }

    /// One slave cell's derivatives with large kinematics; `weight` the factor of each
    /// normal force coefficient in the residual (λ_j, plus the augmentation on active
    /// nodes), `traction` the tangential multipliers (with friction).
    fn cell_derivatives(
        &self,
        mesh: &Mesh,
        u: &[f64],
        ic: usize,
        weight: &[f64],
        traction: Option<&[f64]>,
    ) -> CellDerivatives {
        let snodes = mesh.cell_nodes(self.slave.cells[ic]);
        let nn = snodes.len();
        let displacement =
            |x: [Dual; 2], n: usize| [x[0] - mesh.coords[n][0], x[1] - mesh.coords[n][1]];
        let x: Vec<[Dual; 2]> = snodes
            .iter()
            .enumerate()
            .map(|(a, &n)| {
                let p = Self::pos(mesh, u, n);
                [seed(p[0], 2 * a), seed(p[1], 2 * a + 1)]
            })
            .collect();
        let (n0, j0) = self.normal_jacobian(mesh, u, snodes[0]);
        let (n1, j1) = self.normal_jacobian(mesh, u, snodes[1]);
        let cell = SlaveCell {
            u: x.iter()
                .zip(snodes)
                .map(|(&p, &n)| displacement(p, n))
                .collect(),
            x,
            corner_normals: [
                [seed(n0[0], 6), seed(n0[1], 7)],
                [seed(n1[0], 8), seed(n1[1], 9)],
            ],
        };
        let jacs = [j0, j1];
        let master = |im: usize| {
            let nodes = mesh.cell_nodes(self.master.cells[im]);
            let x: Vec<[Dual; 2]> = nodes
                .iter()
                .enumerate()
                .map(|(b, &n)| {
                    let p = Self::pos(mesh, u, n);
                    [seed(p[0], 10 + 2 * b), seed(p[1], 11 + 2 * b)]
                })
                .collect();
            let d = x
                .iter()
                .zip(nodes)
                .map(|(&p, &n)| displacement(p, n))
                .collect();
            (x, d)
        };
        // the derivative of q with respect to the dofs, given the master cell's nodes
        let scatter = |q: &Dual, mnodes: &[usize], out: &mut dyn FnMut(usize, f64)| {
            let Some(e) = &q.eps.0 else { return };
            for (s, &v) in e.iter().enumerate() {
                if v == 0.0 {
                    continue;
                }
                match s {
                    0..6 if s / 2 < nn => out(2 * snodes[s / 2] + s % 2, v),
                    6..10 => {
                        for &(dof, dn) in &jacs[(s - 6) / 2] {
                            out(dof, v * dn[s % 2]);
                        }
                    }
                    10.. if (s - 10) / 2 < mnodes.len() => out(2 * mnodes[(s - 10) / 2] + s % 2, v),
                    _ => {}
                }
            }
        };
        let mult: Vec<usize> = snodes.iter().map(|n| self.mult_of[n]).collect();
        let mut out = CellDerivatives::default();
        let d = self.cell_kernel(mesh, u, ic, &cell, master, |o: Overlap<Dual>| {
            let mnodes = mesh.cell_nodes(self.master.cells[o.im]);
            for l in (0..nn).chain(3..3 + mnodes.len()) {
                for c in 0..2 {
                    let row = if l < 3 {
                        2 * snodes[l] + c
                    } else {
                        2 * mnodes[l - 3] + c
                    };
                    let mut q = Dual::from_re(0.0);
                    for j in 0..nn {
                        q += o.force[j][l][c] * weight[mult[j]];
                        if let Some(t) = traction {
                            q += o.tforce[j][l][c] * t[mult[j]];
                        }
                    }
                    scatter(&q, mnodes, &mut |col, v| out.rows.push((row, col, v)));
                }
            }
            for j in 0..nn {
                scatter(&o.gap[j], mnodes, &mut |col, v| {
                    out.dg.push((mult[j], col, v))
                });
                if traction.is_some() {
                    scatter(&o.slip[j], mnodes, &mut |col, v| {
                        out.ds.push((mult[j], col, v))
                    });
                }
            }
        });
        for j in 0..nn {
            scatter(&d[j], &[], &mut |col, v| out.dd.push((mult[j], col, v)));
        }
        out
    }

    /// The u-columns of the tangent with large kinematics; `gd` the weighted gaps and D_j,
    /// `fj` the force coefficients of the active nodes, `rows` the first multiplier row.
    /// Returns the derivatives of every node's weighted gap and slip (per multiplier index,
    /// by column).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn exact_tangent(
        &self,
        mesh: &Mesh,
        u: &[f64],
        lam: &[f64],
        gd: (&[f64], &[f64]),
        fj: &[Vec<(usize, f64)>],
        active: &[bool],
        law: &[Branch],
        rows: usize,
        k: &mut Triplets,
    ) -> SparseRows {
        let (g, d) = gd;
        let nm = self.mult_nodes.len();
        let c = self.c;
        // The augmentation −c g̃_j/D_j F_j of an active node vanishes at a solution (g̃_j =
        // 0), and so do the parts of its derivative that carry g̃_j: its curvature (F_j's
        // own derivative times c g̃_j/D_j) and the variation of 1/D_j. Newton leaves them
        // out and keeps the Gauss–Newton part (c/D_j) ∂g̃_j ∂g̃_jᵀ, which the linearised
        // constraint ∂g̃_j du = −g̃_j cancels: the correction is then that of semi-smooth
        // Newton on the plain mortar equations (Popp et al. 2009), the curvature weighted by
        // the multipliers alone. With it, far from the solution c g̃_j/D_j is a cell's
        // stiffness times the gap to close: a closed start pulling nodes a cell size in
        // carried a tension tens of times the contact pressure, a fine mesh's newly closed
        // nodes as large a pressure; both threw the first corrections off (SSNP154 A at
        // 0.094 mm from the points within 0.1 mm: 111 → 13 iterations). Convergence stays
        // quadratic: at a solution the tangent is exact.
        let exact = self.exact_augmentation;
        let weight: Vec<f64> = (0..nm)
            .map(|j| {
                lam[j]
                    - if active[j] && exact {
                        c * g[j] / d[j]
                    } else {
                        0.0
                    }
            })
            .collect();
        let traction = self.friction.map(|_| &lam[nm..2 * nm]);
        // cells in parallel, their entries then emitted in cell order: the matrix is the
        // same whatever the threads
        let cells: Vec<CellDerivatives> = (0..self.slave.cells.len())
            .into_par_iter()
            .map(|ic| self.cell_derivatives(mesh, u, ic, &weight, traction))
            .collect();
        let (mut dg, mut dd, mut ds) = (vec![], vec![], vec![]);
        for cd in cells {
            for (r, col, v) in cd.rows {
                k.add(r, col, v);
            }
            dg.extend(cd.dg);
            dd.extend(cd.dd);
            ds.extend(cd.ds);
        }
        let (dg, dd, ds) = (
            by_multiplier(dg, nm),
            by_multiplier(dd, nm),
            by_multiplier(ds, nm),
        );
        for j in 0..nm {
            // the augmentation's factor −c g̃_j/D_j on F_j varies with g̃_j and D_j
            if active[j] {
                let mut f = fj[j].clone();
                merge(&mut f);
                let (gj, dj) = (g[j], d[j]);
                for &(row, v) in &f {
                    for &(col, w) in &dg[j] {
                        k.add(row, col, -c * v / dj * w);
                    }
                    if exact {
                        for &(col, w) in &dd[j] {
                            k.add(row, col, c * gj * v / (dj * dj) * w);
                        }
                    }
                }
                for &(col, w) in &dg[j] {
                    k.add(rows + j, col, -w);
                }
            } else if lam[j] != 0.0 {
                // (zero with a zero multiplier, and then outside a pattern that has not
                // reserved the node's cells: see `Mortar::reserved`)
                for &(col, w) in &dd[j] {
                    k.add(rows + j, col, -lam[j] / c * w);
                }
            }
            if let Some(mu) = self.friction {
                let row = rows + nm + j;
                let tj = lam[nm + j];
                match law[j] {
                    Branch::Stick => {
                        for &(col, w) in &ds[j] {
                            k.add(row, col, -w);
                        }
                    }
                    Branch::Slip(sg) => {
                        for &(col, w) in &dd[j] {
                            k.add(row, col, -(tj - mu * lam[j] * sg) / c * w);
                        }
                    }
                    Branch::Free if tj != 0.0 => {
                        for &(col, w) in &dd[j] {
                            k.add(row, col, -tj / c * w);
                        }
                    }
                    Branch::Free => {}
                }
            }
        }
        dg
    }
}
