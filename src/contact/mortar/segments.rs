//! One slave cell's mortar terms: the dual basis on the cell, the overlap segments with
//! the master cells it faces (master ends projected along the slave normal field), and on
//! them by Gauss quadrature the weighted gaps, D_j, the normal and tangential force
//! coefficients and the weighted slips.
//!
//! The kernel is generic over the number type: with f64 it gives the residual's terms,
//! with dual numbers their exact derivatives (normals, segment ends, projections,
//! Jacobians and the dual basis included), from the same code.

use super::super::projection::{point_and_tangent, seg_shape, step_settled};
use super::super::real::{constant, value, values, Real};
use super::geometry::{cross, norm, project_along, unit_normal};
use super::Mortar;
use crate::fem::quadrature::gauss_legendre;
use crate::mesh::Mesh;
use std::sync::OnceLock;

/// What one slave cell contributes: per slave node j (multiplier index) its weighted gap,
/// its D_j = ∫ N_j, and force coefficients (dof, value) per unit λ_j.
#[derive(Default, Clone)]
pub(super) struct CellTerms {
    pub gap: Vec<(usize, f64)>,
    pub dj: Vec<(usize, f64)>,
    /// ∫ N_j over the parts of the cell that face the master surface
    pub cover: Vec<(usize, f64)>,
    /// The share of the cell (of its parameter range) that faces a candidate master cell
    pub span: f64,
    pub force: Vec<(usize, usize, f64)>,
    /// With friction: weighted slips s̃_j = ∫ Φ_j (Δu_s − Δu_m)·τ̂ since the step start,
    /// and tangential force coefficients per unit traction t_j.
    pub slip: Vec<(usize, f64)>,
    pub tforce: Vec<(usize, usize, f64)>,
}

/// A slave cell at the evaluation point: where its geometry is evaluated, its
/// displacements, and the averaged unit normals at its two corners.
pub(super) struct SlaveCell<T> {
    pub x: Vec<[T; 2]>,
    pub u: Vec<[T; 2]>,
    pub corner_normals: [[T; 2]; 2],
}

/// What the overlap of a slave cell with master cell `im` contributes, summed over its
/// Gauss points. Per slave node j of the cell (local index) and local node l (the slave
/// cell's nodes 0..3, then the master cell's 3..6): force and tangential force
/// coefficients per unit multiplier, component by component.
pub(super) struct Overlap<T> {
    pub im: usize,
    pub gap: [T; 3],
    pub slip: [T; 3],
    pub cover: [f64; 3],
    /// the share of the slave cell's parameter range the overlap spans
    pub span: f64,
    pub force: [[[T; 2]; 6]; 3],
    pub tforce: [[[T; 2]; 6]; 3],
}

/// N, dN/dξ, point, tangent and normal field of the slave cell at one ξ.
type FieldAt<T> = ([T; 3], [T; 3], [T; 2], [T; 2], [T; 2]);

/// Gauss–Legendre points of the overlaps and the cells (6: exact for the products of
/// quadratic shape functions, dual functions and curved Jacobians to ~1e-10).
fn gauss6() -> &'static (Vec<f64>, Vec<f64>) {
    static RULE: OnceLock<(Vec<f64>, Vec<f64>)> = OnceLock::new();
    RULE.get_or_init(|| gauss_legendre(6))
}

impl Mortar {
    /// The terms of slave cell ic at displacement u.
    pub(super) fn cell_terms(&self, mesh: &Mesh, u: &[f64], ic: usize) -> CellTerms {
        let snodes = mesh.cell_nodes(self.slave.cells[ic]);
        let nn = snodes.len();
        let cell = SlaveCell {
            x: snodes.iter().map(|&n| self.geo(mesh, u, n)).collect(),
            u: snodes.iter().map(|&n| [u[2 * n], u[2 * n + 1]]).collect(),
            corner_normals: [
                self.node_normal(mesh, u, snodes[0]),
                self.node_normal(mesh, u, snodes[1]),
            ],
        };
        let master = |im: usize| {
            let nodes = mesh.cell_nodes(self.master.cells[im]);
            let x = nodes.iter().map(|&n| self.geo(mesh, u, n)).collect();
            let d = nodes.iter().map(|&n| [u[2 * n], u[2 * n + 1]]).collect();
            (x, d)
        };
        let mut out = CellTerms::default();
        let mult: Vec<usize> = snodes.iter().map(|n| self.mult_of[n]).collect();
        let d = self.cell_kernel(mesh, u, ic, &cell, master, |o: Overlap<f64>| {
            let mnodes = mesh.cell_nodes(self.master.cells[o.im]);
            let dof = |l: usize, c: usize| {
                if l < 3 {
                    2 * snodes[l] + c
                } else {
                    2 * mnodes[l - 3] + c
                }
            };
            let locals: Vec<usize> = (0..nn).chain(3..3 + mnodes.len()).collect();
            out.span += o.span;
            for j in 0..nn {
                let k = mult[j];
                out.gap.push((k, o.gap[j]));
                out.cover.push((k, o.cover[j]));
                for &l in &locals {
                    for c in 0..2 {
                        out.force.push((k, dof(l, c), o.force[j][l][c]));
                    }
                }
                if self.friction.is_some() {
                    out.slip.push((k, o.slip[j]));
                    for &l in &locals {
                        for c in 0..2 {
                            out.tforce.push((k, dof(l, c), o.tforce[j][l][c]));
                        }
                    }
                }
            }
        });
        for a in 0..nn {
            out.dj.push((mult[a], d[a]));
        }
        out
    }

    /// The kernel of slave cell ic: hands each overlap with a candidate master cell to
    /// `sink` and returns D_j of the cell's nodes. `master(im)` gives master cell im's node
    /// positions and displacements; `u` is read only for the reference geometry of small
    /// kinematics' master normals.
    pub(super) fn cell_kernel<T: Real>(
        &self,
        mesh: &Mesh,
        u: &[f64],
        ic: usize,
        cell: &SlaveCell<T>,
        master: impl Fn(usize) -> (Vec<[T; 2]>, Vec<[T; 2]>),
        mut sink: impl FnMut(Overlap<T>),
    ) -> [T; 3] {
        let zero: T = constant(0.0);
        let c = self.slave.cells[ic];
        let kind = mesh.kind(c);
        let nn = kind.num_nodes();
        let snodes = mesh.cell_nodes(c);
        let (xs, us) = (&cell.x, &cell.u);
        // nodal normals: averaged at corners, the cell's own at a mid-side node
        let mut normals = [[zero; 2]; 3];
        normals[..2].copy_from_slice(&cell.corner_normals);
        if nn == 3 {
            normals[2] = unit_normal(kind, xs, self.slave.ccw[ic], zero);
        }
        let (gp, gw) = gauss6();
        // dual basis: Φ = A N with A = D M⁻¹ on this cell (current geometry)
        let mut m = [[zero; 3]; 3];
        let mut d = [zero; 3];
        for (q, &xi) in gp.iter().enumerate() {
            let xi = constant(xi);
            let (p, t) = point_and_tangent(kind, xs, xi);
            let j = norm(t) * self.measure(p) * gw[q];
            let (nv, _) = seg_shape(kind, xi);
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
        let dsum: f64 = d.iter().map(|v| value(*v).abs()).sum();
        for v in d.iter_mut() {
            if value(*v).abs() <= 1e-6 * dsum {
                *v = zero;
            }
        }
        let minv = invert(&m, nn);
        let mut amat = [[zero; 3]; 3];
        for a in 0..nn {
            for b in 0..nn {
                amat[a][b] = d[a] * minv[a][b];
            }
        }
        // the slave at ξ: shape functions and their derivatives, point, tangent, and the
        // normal field n(ξ) = Σ N_k n_k
        let field = |xi: T| -> FieldAt<T> {
            let (nv, dn) = seg_shape(kind, xi);
            let (p, t) = point_and_tangent(kind, xs, xi);
            let mut nf = [zero; 2];
            for a in 0..nn {
                nf[0] += nv[a] * normals[a][0];
                nf[1] += nv[a] * normals[a][1];
            }
            (nv, dn, p, t, nf)
        };
        // the point of the slave cell whose normal passes through `target`
        let proj_slave = |target: [T; 2]| -> Option<T> {
            let mut xi = zero;
            for _ in 0..30 {
                let (_, dn, p, t, nf) = field(xi);
                let to = [target[0] - p[0], target[1] - p[1]];
                let r = cross(to, nf);
                // derivative: −t × n + (target − p) × n'  (n' from the nodal normals)
                let mut nd = [zero; 2];
                for a in 0..nn {
                    nd[0] += dn[a] * normals[a][0];
                    nd[1] += dn[a] * normals[a][1];
                }
                let dr = cross(to, nd) - cross(t, nf);
                if value(dr).abs() < 1e-300 {
                    return None;
                }
                let step = r / dr;
                xi -= step;
                if step_settled(value(step), 1e-13, values(p), values(t)) {
                    return Some(xi);
                }
                if value(xi).abs() > 10.0 {
                    return None;
                }
            }
            None
        };
        let by_value = |a: T, b: T| if value(a) <= value(b) { (a, b) } else { (b, a) };
        for &im in &self.candidates[ic] {
            let mc = self.master.cells[im];
            let mkind = mesh.kind(mc);
            let mnodes = mesh.cell_nodes(mc);
            let (xm, um) = master(im);
            // master end nodes projected on the slave cell along the normal field
            let (Some(xa), Some(xb)) = (proj_slave(xm[0]), proj_slave(xm[1])) else {
                continue;
            };
            let (mut lo, mut hi) = by_value(xa, xb);
            if value(lo) < -1.0 {
                lo = constant(-1.0);
            }
            if value(hi) > 1.0 {
                hi = constant(1.0);
            }
            if value(hi) - value(lo) < 1e-12 {
                continue;
            }
            let mut o = Overlap {
                im,
                gap: [zero; 3],
                slip: [zero; 3],
                cover: [0.0; 3],
                span: 0.5 * value(hi - lo),
                force: [[[zero; 2]; 6]; 3],
                tforce: [[[zero; 2]; 6]; 3],
            };
            let mut any = false;
            for (q, &g) in gp.iter().enumerate() {
                let xi = (lo + hi) * 0.5 + (hi - lo) * (0.5 * g);
                let (nv, _, p, t, nf) = field(xi);
                // project along the normal field on the master cell
                let (xim, ok) = project_along(mkind, &xm, p, nf);
                if !ok || value(xim).abs() > 1.0 + 1e-9 {
                    continue;
                }
                any = true;
                let (mut pm, _) = point_and_tangent(mkind, &xm, xim);
                if self.adjust.is_some() {
                    let step = self.cell_to_curve(mesh, u, im, &xm, xim);
                    pm = [pm[0] + step[0], pm[1] + step[1]];
                }
                let mut ps = p;
                if self.small {
                    // geometry on the reference configuration, gap with the displacements
                    let (dm, _) = point_and_tangent(mkind, &um, xim);
                    let (ds, _) = point_and_tangent(kind, us, xi);
                    pm = [pm[0] + dm[0], pm[1] + dm[1]];
                    ps = [p[0] + ds[0], p[1] + ds[1]];
                }
                let ln = norm(nf);
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
                    // slave. (Reference geometry: constants for the tangent.)
                    let nmas = self.master_normal(mesh, u, im, value(xim));
                    let (cs, cm) = (self.compliance.0[ic], self.compliance.1[im]);
                    let (ws, wm) = if cs + cm > 0.0 { (cm, cs) } else { (1.0, 1.0) };
                    let b = [nhat[0] * ws - wm * nmas[0], nhat[1] * ws - wm * nmas[1]];
                    let lb = norm(b);
                    if value(lb) > 1e-12 {
                        nhat = [b[0] / lb, b[1] / lb];
                    }
                }
                let gap = (pm[0] - ps[0]) * nhat[0] + (pm[1] - ps[1]) * nhat[1];
                let w = (hi - lo) * norm(t) * self.measure(p) * (gw[q] * 0.5);
                let (nm, _) = seg_shape(mkind, xim);
                // slip since the step start along τ̂ (slave relative to master)
                let tau = [-nhat[1], nhat[0]];
                let slip = if self.friction.is_some() {
                    let mut rel = [zero; 2];
                    for c in 0..2 {
                        for (a, &n) in snodes.iter().enumerate() {
                            rel[c] += nv[a] * (us[a][c] - self.u_start[2 * n + c]);
                        }
                        for (b, &n) in mnodes.iter().enumerate() {
                            rel[c] -= nm[b] * (um[b][c] - self.u_start[2 * n + c]);
                        }
                    }
                    rel[0] * tau[0] + rel[1] * tau[1]
                } else {
                    zero
                };
                for j in 0..nn {
                    let mut phi = zero;
                    for b in 0..nn {
                        phi += amat[j][b] * nv[b];
                    }
                    let wphi = w * phi;
                    o.gap[j] += wphi * gap;
                    o.cover[j] += value(w * nv[j]);
                    for comp in 0..2 {
                        for a in 0..nn {
                            o.force[j][a][comp] += wphi * nv[a] * nhat[comp];
                        }
                        for b in 0..mnodes.len() {
                            o.force[j][3 + b][comp] -= wphi * nm[b] * nhat[comp];
                        }
                    }
                    if self.friction.is_some() {
                        o.slip[j] += wphi * slip;
                        for comp in 0..2 {
                            for a in 0..nn {
                                o.tforce[j][a][comp] += wphi * nv[a] * tau[comp];
                            }
                            for b in 0..mnodes.len() {
                                o.tforce[j][3 + b][comp] -= wphi * nm[b] * tau[comp];
                            }
                        }
                    }
                }
            }
            if any {
                sink(o);
            }
        }
        d
    }
}

/// Gauss–Jordan inverse of the leading n×n block (n ≤ 3), pivoting on the values.
fn invert<T: Real>(m: &[[T; 3]; 3], n: usize) -> [[T; 3]; 3] {
    let mut a = *m;
    let mut inv = [[constant::<T>(0.0); 3]; 3];
    for (i, row) in inv.iter_mut().enumerate().take(n) {
        row[i] = constant(1.0);
    }
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&i, &j| value(a[i][col]).abs().total_cmp(&value(a[j][col]).abs()))
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
                    let (ac, ic) = (a[col][j], inv[col][j]);
                    a[r][j] -= f * ac;
                    inv[r][j] -= f * ic;
                }
            }
        }
    }
    inv
}
