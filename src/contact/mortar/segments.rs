//! One slave cell's mortar terms: the dual basis on the cell, the overlap segments with
//! the master cells it faces (master ends projected along the slave normal field), and on
//! them by Gauss quadrature the weighted gaps, D_j, the normal and tangential force
//! coefficients and the weighted slips.

use super::super::projection::point_and_tangent;
use super::geometry::cross;
use super::Mortar;
use crate::fem::element::{shape, shape_grad, MAX_NODES};
use crate::fem::quadrature::gauss_legendre;
use crate::mesh::Mesh;

/// What one slave cell contributes: per slave node j (multiplier index) its weighted gap,
/// its D_j = ∫ N_j, and force coefficients (dof, value) per unit λ_j.
#[derive(Default, Clone)]
pub(super) struct CellTerms {
    pub gap: Vec<(usize, f64)>,
    pub dj: Vec<(usize, f64)>,
    /// ∫ N_j over the parts of the cell that face the master surface
    pub cover: Vec<(usize, f64)>,
    pub force: Vec<(usize, usize, f64)>,
    /// With friction: weighted slips s̃_j = ∫ Φ_j (Δu_s − Δu_m)·τ̂ since the step start,
    /// and tangential force coefficients per unit traction t_j.
    pub slip: Vec<(usize, f64)>,
    pub tforce: Vec<(usize, usize, f64)>,
}

impl Mortar {
    /// The terms of slave cell ic at displacement u.
    pub(super) fn cell_terms(&self, mesh: &Mesh, u: &[f64], ic: usize) -> CellTerms {
        let c = self.slave.cells[ic];
        let kind = mesh.kind(c);
        let nn = kind.num_nodes();
        let snodes = mesh.cell_nodes(c);
        let xs: Vec<[f64; 2]> = snodes.iter().map(|&n| self.geo(mesh, u, n)).collect();
        let us: Vec<[f64; 2]> = snodes.iter().map(|&n| [u[2 * n], u[2 * n + 1]]).collect();
        // nodal normals: averaged at corners, the cell's own at a mid-side node
        let normals: Vec<[f64; 2]> = (0..nn)
            .map(|a| {
                if a < 2 {
                    self.node_normal(mesh, u, snodes[a])
                } else {
                    self.cell_normal(mesh, u, ic, 0.0)
                }
            })
            .collect();
        let (gp, gw) = gauss_legendre(6);
        // dual basis: Φ = A N with A = D M⁻¹ on this cell (current geometry)
        let mut m = [[0.0; 3]; 3];
        let mut d = [0.0; 3];
        for (q, &xi) in gp.iter().enumerate() {
            let (p, t) = point_and_tangent(kind, &xs, xi);
            let j = t[0].hypot(t[1]) * gw[q] * self.measure(p);
            let mut nv = [0.0; MAX_NODES];
            shape(kind, [xi, 0.0], &mut nv);
            for a in 0..nn {
                d[a] += nv[a] * j;
                for b in 0..nn {
                    m[a][b] += nv[a] * nv[b] * j;
                }
            }
        }
        // ∫ N_a r = 0 for a Seg3 corner on the axis when the cell is straight; on a curved
        // one (a sphere's pole) it is ~1e-7 of the cell's weight: a pressure so weakly
        // weighted is undetermined (and slows Newton), so such a node gets the zero weight
        // of the straight case (its force, λ D, is below 1e-6 of the cell's anyway).
        let dsum: f64 = d.iter().map(|v| v.abs()).sum();
        for v in d.iter_mut() {
            if v.abs() <= 1e-6 * dsum {
                *v = 0.0;
            }
        }
        let minv = invert(&m, nn);
        let mut amat = [[0.0; 3]; 3];
        for a in 0..nn {
            for b in 0..nn {
                amat[a][b] = d[a] * minv[a][b];
            }
        }
        let field = |xi: f64| -> ([f64; MAX_NODES], [f64; 2], [f64; 2], [f64; 2]) {
            let mut nv = [0.0; MAX_NODES];
            shape(kind, [xi, 0.0], &mut nv);
            let (p, t) = point_and_tangent(kind, &xs, xi);
            let mut nf = [0.0; 2];
            for a in 0..nn {
                nf[0] += nv[a] * normals[a][0];
                nf[1] += nv[a] * normals[a][1];
            }
            (nv, p, t, nf)
        };
        let mut out = CellTerms::default();
        for a in 0..nn {
            out.dj.push((self.mult_of[&snodes[a]], d[a]));
        }
        for &im in &self.candidates[ic] {
            let mc = self.master.cells[im];
            let mkind = mesh.kind(mc);
            let mnodes = mesh.cell_nodes(mc);
            let xm: Vec<[f64; 2]> = mnodes.iter().map(|&n| self.geo(mesh, u, n)).collect();
            let um: Vec<[f64; 2]> = mnodes.iter().map(|&n| [u[2 * n], u[2 * n + 1]]).collect();
            // master end nodes projected on the slave cell along the normal field
            let proj_slave = |target: [f64; 2]| -> Option<f64> {
                let mut xi = 0.0;
                for _ in 0..30 {
                    let (_, p, t, nf) = field(xi);
                    let r = cross([target[0] - p[0], target[1] - p[1]], nf);
                    // derivative: −t × n + (target − p) × n'  (n' from the nodal normals)
                    let mut dn = [[0.0; 2]; MAX_NODES];
                    shape_grad(kind, [xi, 0.0], &mut dn);
                    let mut nd = [0.0; 2];
                    for a in 0..nn {
                        nd[0] += dn[a][0] * normals[a][0];
                        nd[1] += dn[a][0] * normals[a][1];
                    }
                    let dr = -cross(t, nf) + cross([target[0] - p[0], target[1] - p[1]], nd);
                    if dr.abs() < 1e-300 {
                        return None;
                    }
                    let step = r / dr;
                    xi -= step;
                    if step.abs() < 1e-13 {
                        return Some(xi);
                    }
                    if xi.abs() > 10.0 {
                        return None;
                    }
                }
                None
            };
            let (Some(xa), Some(xb)) = (proj_slave(xm[0]), proj_slave(xm[1])) else {
                continue;
            };
            let lo = xa.min(xb).max(-1.0);
            let hi = xa.max(xb).min(1.0);
            if hi - lo < 1e-12 {
                continue;
            }
            for (q, &g) in gp.iter().enumerate() {
                let xi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * g;
                let (nv, p, t, nf) = field(xi);
                // project along the normal field on the master cell
                let mut xim = 0.0;
                let mut ok = false;
                for _ in 0..30 {
                    let (pm, tm) = point_and_tangent(mkind, &xm, xim);
                    let r = cross([pm[0] - p[0], pm[1] - p[1]], nf);
                    let dr = cross(tm, nf);
                    let step = r / dr;
                    xim -= step;
                    if step.abs() < 1e-13 {
                        ok = true;
                        break;
                    }
                }
                if !ok || xim.abs() > 1.0 + 1e-9 {
                    continue;
                }
                let (mut pm, _) = point_and_tangent(mkind, &xm, xim);
                let mut ps = p;
                if self.small {
                    // geometry on the reference configuration, gap with the displacements
                    let (dm, _) = point_and_tangent(mkind, &um, xim);
                    let (ds, _) = point_and_tangent(kind, &us, xi);
                    pm = [pm[0] + dm[0], pm[1] + dm[1]];
                    ps = [p[0] + ds[0], p[1] + ds[1]];
                }
                let ln = nf[0].hypot(nf[1]);
                let mut nhat = [nf[0] / ln, nf[1] / ln];
                if self.small {
                    // Small kinematics works on the reference configuration, where curved
                    // surfaces in contact are not yet parallel: the slave's normal alone
                    // would push the master obliquely (a tangential traction on a
                    // frictionless contact, and the interface shifted toward the slave).
                    // The deformed interface lies between the two surfaces, the softer one
                    // conforming to the stiffer (Hertz: each surface moves in proportion to
                    // its compliance), so its normal is the compliance-weighted mean
                    // c_m n_s − c_s n_m: the bisector for equal bodies, the stiff side's
                    // normal against a much softer one, and the same whichever side is the
                    // slave.
                    let nm = self.master_normal(mesh, u, im, xim);
                    let (cs, cm) = (self.compliance.0[ic], self.compliance.1[im]);
                    let (ws, wm) = if cs + cm > 0.0 { (cm, cs) } else { (1.0, 1.0) };
                    let b = [ws * nhat[0] - wm * nm[0], ws * nhat[1] - wm * nm[1]];
                    let lb = b[0].hypot(b[1]);
                    if lb > 1e-12 {
                        nhat = [b[0] / lb, b[1] / lb];
                    }
                }
                let gap = (pm[0] - ps[0]) * nhat[0] + (pm[1] - ps[1]) * nhat[1];
                let w = gw[q] * 0.5 * (hi - lo) * t[0].hypot(t[1]) * self.measure(p);
                let mut nm = [0.0; MAX_NODES];
                shape(mkind, [xim, 0.0], &mut nm);
                // slip since the step start along τ̂ (slave relative to master)
                let tau = [-nhat[1], nhat[0]];
                let slip = if self.friction.is_some() {
                    let mut rel = [0.0; 2];
                    for c in 0..2 {
                        for (a, &n) in snodes.iter().enumerate() {
                            rel[c] += nv[a] * (u[2 * n + c] - self.u_start[2 * n + c]);
                        }
                        for (b, &n) in mnodes.iter().enumerate() {
                            rel[c] -= nm[b] * (u[2 * n + c] - self.u_start[2 * n + c]);
                        }
                    }
                    rel[0] * tau[0] + rel[1] * tau[1]
                } else {
                    0.0
                };
                for j in 0..nn {
                    let phi: f64 = (0..nn).map(|b| amat[j][b] * nv[b]).sum();
                    let k = self.mult_of[&snodes[j]];
                    out.gap.push((k, w * phi * gap));
                    out.cover.push((k, w * nv[j]));
                    for a in 0..nn {
                        for comp in 0..2 {
                            out.force
                                .push((k, 2 * snodes[a] + comp, w * phi * nv[a] * nhat[comp]));
                        }
                    }
                    for (b, &mn) in mnodes.iter().enumerate() {
                        for comp in 0..2 {
                            out.force
                                .push((k, 2 * mn + comp, -w * phi * nm[b] * nhat[comp]));
                        }
                    }
                    if self.friction.is_some() {
                        out.slip.push((k, w * phi * slip));
                        for a in 0..nn {
                            for comp in 0..2 {
                                out.tforce.push((
                                    k,
                                    2 * snodes[a] + comp,
                                    w * phi * nv[a] * tau[comp],
                                ));
                            }
                        }
                        for (b, &mn) in mnodes.iter().enumerate() {
                            for comp in 0..2 {
                                out.tforce
                                    .push((k, 2 * mn + comp, -w * phi * nm[b] * tau[comp]));
                            }
                        }
                    }
                }
            }
        }
        out
    }
}

fn invert(m: &[[f64; 3]; 3], n: usize) -> [[f64; 3]; 3] {
    let mut a = *m;
    let mut inv = [[0.0; 3]; 3];
    for i in 0..n {
        inv[i][i] = 1.0;
    }
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap();
        a.swap(col, piv);
        inv.swap(col, piv);
        let dv = a[col][col];
        for j in 0..n {
            a[col][j] /= dv;
            inv[col][j] /= dv;
        }
        for r in 0..n {
            if r != col {
                let f = a[r][col];
                for j in 0..n {
                    a[r][j] -= f * a[col][j];
                    inv[r][j] -= f * inv[col][j];
                }
            }
        }
    }
    inv
}
