//! The tangent of the mortar terms. Small kinematics: exact (the terms are linear in u on
//! the reference geometry). Large kinematics: the derivatives of the weighted gaps, D_j and
//! the force coefficients by central differences, cell by cell (each perturbed dof only
//! re-evaluates the slave cells that read it); they contain every geometric variation
//! (normals, segment ends, projections, Jacobians) to ~1e-8.

use super::friction::Branch;
use super::segments::CellTerms;
use super::Mortar;
use crate::assembly::coupled::Triplets;
use crate::mesh::Mesh;
use rayon::prelude::*;

/// Central-difference derivatives of one cell group's terms with respect to one dof:
/// weighted gaps, weights, forces (ordered: the triplets and the sums of duplicates come out
/// the same every time), slips and tangential forces.
struct DofDerivatives {
    dg: Vec<f64>,
    dd: Vec<f64>,
    df: std::collections::BTreeMap<(usize, usize), f64>,
    ds: Vec<f64>,
    dtf: std::collections::BTreeMap<(usize, usize), f64>,
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
    /// The u-columns of the tangent by central differences; `gd` the weighted gaps and D_j,
    /// `fj` the force coefficients of the active nodes, `rows` the first multiplier row.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn difference_tangent(
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
    ) {
        let (g, d) = gd;
        let nm = self.mult_nodes.len();
        // u-derivatives by central differences, cell by cell: each dof's in parallel (on
        // a copy of u per thread), their triplets then emitted in dof order, so the
        // matrix is the same whatever the threads.
        let mut dofs: Vec<usize> = self.readers.keys().copied().collect();
        dofs.sort_unstable();
        let derivatives: Vec<DofDerivatives> = dofs
            .par_iter()
            .map_init(
                || u.to_vec(),
                |up, &dof| {
                    let h = 1e-7 * (1.0 + mesh.coords[dof / 2][dof % 2].abs().max(1.0));
                    let mut dv = DofDerivatives {
                        dg: vec![0.0; nm],
                        dd: vec![0.0; nm],
                        df: Default::default(),
                        ds: vec![0.0; nm],
                        dtf: Default::default(),
                    };
                    for (sign, s) in [(1.0, h), (-1.0, -h)] {
                        up[dof] = u[dof] + s;
                        for &ic in &self.readers[&dof] {
                            let t = self.cell_terms(mesh, up, ic);
                            for (j, v) in t.gap {
                                dv.dg[j] += sign * v / (2.0 * h);
                            }
                            for (j, v) in t.dj {
                                dv.dd[j] += sign * v / (2.0 * h);
                            }
                            for (j, row, v) in t.force {
                                *dv.df.entry((j, row)).or_insert(0.0) += sign * v / (2.0 * h);
                            }
                            for (j, v) in t.slip {
                                dv.ds[j] += sign * v / (2.0 * h);
                            }
                            for (j, row, v) in t.tforce {
                                *dv.dtf.entry((j, row)).or_insert(0.0) += sign * v / (2.0 * h);
                            }
                        }
                    }
                    up[dof] = u[dof];
                    dv
                },
            )
            .collect();
        for (&dof, dv) in dofs.iter().zip(derivatives) {
            let DofDerivatives {
                dg,
                dd,
                df,
                ds,
                dtf,
            } = dv;
            if let Some(mu) = self.friction {
                for ((j, row), v) in dtf {
                    k.add(row, dof, lam[nm + j] * v);
                }
                for j in 0..nm {
                    let row = rows + nm + j;
                    let v = match law[j] {
                        Branch::Stick => -ds[j],
                        Branch::Slip(sg) => -(lam[nm + j] - mu * lam[j] * sg) / self.c * dd[j],
                        Branch::Free => -lam[nm + j] / self.c * dd[j],
                    };
                    if v != 0.0 {
                        k.add(row, dof, v);
                    }
                }
            }
            for ((j, row), v) in df {
                let aug = if active[j] {
                    -self.c * g[j] / d[j]
                } else {
                    0.0
                };
                k.add(row, dof, (lam[j] + aug) * v);
            }
            for j in 0..nm {
                if active[j] && (dg[j] != 0.0 || dd[j] != 0.0) {
                    let (gj, dj) = (g[j], d[j]);
                    for &(row, v) in &fj[j] {
                        k.add(
                            row,
                            dof,
                            -self.c * (v / dj * dg[j] - gj * v / (dj * dj) * dd[j]),
                        );
                    }
                }
            }
            for j in 0..nm {
                let v = if active[j] {
                    -dg[j]
                } else {
                    -lam[j] * dd[j] / self.c
                };
                if v != 0.0 {
                    k.add(rows + j, dof, v);
                }
            }
        }
    }
}
