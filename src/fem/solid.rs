//! Element residual (internal forces) and tangent of one solid cell, for small strain or
//! total-Lagrangian finite strain (Green–Lagrange strain, St Venant–Kirchhoff), in plane
//! strain, plane stress (small strain only) and axisymmetry.
//!
//! Element dofs are ordered node by node: [u_x0, u_y0, u_x1, u_y1, ...].

use super::element::{shape, shape_grad, MAX_NODES};
use super::material::{apply, Elastic, Modelisation};
use super::quadrature::stiffness_rule;
use crate::mesh::CellKind;

pub const MAX_DOFS: usize = 2 * MAX_NODES;

/// A cell whose Jacobian is not positive at a quadrature point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BadJacobian;

#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Kinematics {
    Small,
    Large,
}

/// Everything a cell kernel needs besides geometry and displacements.
#[derive(Clone, Copy, Debug)]
pub struct SolidModel {
    pub model: Modelisation,
    pub kinematics: Kinematics,
    pub material: Elastic,
    /// Out-of-plane thickness for plane stress and plane strain (1 per unit thickness).
    pub thickness: f64,
}

/// Geometry of one quadrature point: shape values, physical gradients, weight × measure.
pub struct PointGeometry {
    pub n: [f64; MAX_NODES],
    pub dn: [[f64; 2]; MAX_NODES],
    /// Quadrature weight × det J × (thickness or 2πr).
    pub dv: f64,
    /// Radius at the point (axisymmetry), else 0.
    pub r: f64,
}

/// Evaluates shape functions and physical gradients at `xi` on the reference geometry `x`.
/// Returns None if det J ≤ 0.
pub fn point_geometry(
    kind: CellKind,
    x: &[[f64; 2]],
    xi: [f64; 2],
    weight: f64,
    sm: &SolidModel,
) -> Option<PointGeometry> {
    let nn = kind.num_nodes();
    let mut n = [0.0; MAX_NODES];
    let mut dref = [[0.0; 2]; MAX_NODES];
    shape(kind, xi, &mut n);
    shape_grad(kind, xi, &mut dref);
    let mut j = [[0.0; 2]; 2];
    for a in 0..nn {
        for r in 0..2 {
            for c in 0..2 {
                j[r][c] += x[a][r] * dref[a][c];
            }
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if det <= 0.0 || !det.is_finite() {
        return None;
    }
    let inv = [
        [j[1][1] / det, -j[0][1] / det],
        [-j[1][0] / det, j[0][0] / det],
    ];
    let mut dn = [[0.0; 2]; MAX_NODES];
    for a in 0..nn {
        // ∂N/∂x_c = Σ_k ∂N/∂ξ_k (J⁻¹)_kc
        for c in 0..2 {
            dn[a][c] = dref[a][0] * inv[0][c] + dref[a][1] * inv[1][c];
        }
    }
    let r: f64 = (0..nn).map(|a| n[a] * x[a][0]).sum();
    let measure = match sm.model {
        Modelisation::Axisymmetric => 2.0 * std::f64::consts::PI * r,
        _ => sm.thickness,
    };
    Some(PointGeometry {
        n,
        dn,
        dv: weight * det * measure,
        r,
    })
}

/// Strain-displacement rows of node `a` (4 Voigt rows × 2 dofs) for the given deformation
/// gradient components: small strain uses F = I.
fn b_rows(g: &PointGeometry, a: usize, f: &[[f64; 2]; 2], fzz: f64, axi: bool) -> [[f64; 2]; 4] {
    let (dx, dy) = (g.dn[a][0], g.dn[a][1]);
    [
        [f[0][0] * dx, f[1][0] * dx],
        [f[0][1] * dy, f[1][1] * dy],
        if axi {
            [fzz * g.n[a] / g.r, 0.0]
        } else {
            [0.0, 0.0]
        },
        [f[0][0] * dy + f[0][1] * dx, f[1][0] * dy + f[1][1] * dx],
    ]
}

/// Kinematic state at a point: F (in-plane), F_zz, and the strain in Voigt form
/// (small strain or Green–Lagrange).
pub fn strain_at(
    g: &PointGeometry,
    nn: usize,
    u: &[[f64; 2]],
    sm: &SolidModel,
) -> ([[f64; 2]; 2], f64, [f64; 4]) {
    let mut h = [[0.0; 2]; 2]; // displacement gradient ∂u_i/∂X_j
    let mut ur = 0.0;
    for a in 0..nn {
        for i in 0..2 {
            for jx in 0..2 {
                h[i][jx] += u[a][i] * g.dn[a][jx];
            }
        }
        ur += g.n[a] * u[a][0];
    }
    let axi = sm.model == Modelisation::Axisymmetric;
    let hzz = if axi { ur / g.r } else { 0.0 };
    match sm.kinematics {
        Kinematics::Small => (
            [[1.0, 0.0], [0.0, 1.0]],
            1.0,
            [h[0][0], h[1][1], hzz, h[0][1] + h[1][0]],
        ),
        Kinematics::Large => {
            let f = [[1.0 + h[0][0], h[0][1]], [h[1][0], 1.0 + h[1][1]]];
            let e = [
                h[0][0] + 0.5 * (h[0][0] * h[0][0] + h[1][0] * h[1][0]),
                h[1][1] + 0.5 * (h[0][1] * h[0][1] + h[1][1] * h[1][1]),
                hzz + 0.5 * hzz * hzz,
                h[0][1] + h[1][0] + h[0][0] * h[0][1] + h[1][0] * h[1][1],
            ];
            (f, 1.0 + hzz, e)
        }
    }
}

/// Internal forces `fe` (2·nn) and, if asked, the tangent `ke` (2·nn × 2·nn, row-major)
/// of one cell. `x` are the reference coordinates, `u` the nodal displacements.
/// Fails if the reference Jacobian is not positive at a quadrature point.
pub fn residual_tangent(
    kind: CellKind,
    x: &[[f64; 2]],
    u: &[[f64; 2]],
    sm: &SolidModel,
    fe: &mut [f64],
    mut ke: Option<&mut [f64]>,
) -> Result<(), BadJacobian> {
    let nn = kind.num_nodes();
    let nd = 2 * nn;
    fe[..nd].fill(0.0);
    if let Some(k) = ke.as_deref_mut() {
        k[..nd * nd].fill(0.0);
    }
    let d = sm.material.matrix(sm.model);
    let axi = sm.model == Modelisation::Axisymmetric;
    let large = sm.kinematics == Kinematics::Large;
    let rule = stiffness_rule(kind);
    for (q, &xi) in rule.points.iter().enumerate() {
        let g = point_geometry(kind, x, xi, rule.weights[q], sm).ok_or(BadJacobian)?;
        let (f, fzz, e) = strain_at(&g, nn, u, sm);
        let s = apply(&d, &e);
        let mut b = [[[0.0; 2]; 4]; MAX_NODES];
        for (a, ba) in b.iter_mut().enumerate().take(nn) {
            *ba = b_rows(&g, a, &f, fzz, axi);
        }
        for a in 0..nn {
            for i in 0..2 {
                let mut acc = 0.0;
                for v in 0..4 {
                    acc += b[a][v][i] * s[v];
                }
                fe[2 * a + i] += acc * g.dv;
            }
        }
        let Some(k) = ke.as_deref_mut() else { continue };
        // Material part Bᵀ D B, upper triangle only (mirrored after the loop): B as 4 × nd
        // rows, D·B precomputed per column.
        let mut bm = [[0.0; MAX_DOFS]; 4];
        for a in 0..nn {
            for v in 0..4 {
                bm[v][2 * a] = b[a][v][0];
                bm[v][2 * a + 1] = b[a][v][1];
            }
        }
        let mut dbm = [[0.0; MAX_DOFS]; 4];
        for v in 0..4 {
            for w in 0..4 {
                if d[v][w] != 0.0 {
                    for c in 0..nd {
                        dbm[v][c] += d[v][w] * bm[w][c];
                    }
                }
            }
        }
        for r in 0..nd {
            let br = [
                bm[0][r] * g.dv,
                bm[1][r] * g.dv,
                bm[2][r] * g.dv,
                bm[3][r] * g.dv,
            ];
            let row = &mut k[r * nd..(r + 1) * nd];
            for c in r..nd {
                row[c] +=
                    br[0] * dbm[0][c] + br[1] * dbm[1][c] + br[2] * dbm[2][c] + br[3] * dbm[3][c];
            }
        }
        if large {
            // Geometric stiffness: ∇N_a · S · ∇N_b on both in-plane dofs (+ hoop term),
            // upper triangle (b ≥ a) only.
            for a in 0..nn {
                for bn in a..nn {
                    let (ax, ay) = (g.dn[a][0], g.dn[a][1]);
                    let (bx, by) = (g.dn[bn][0], g.dn[bn][1]);
                    let kab = (ax * bx * s[0] + ay * by * s[1] + (ax * by + ay * bx) * s[3]) * g.dv;
                    k[(2 * a) * nd + 2 * bn] += kab;
                    k[(2 * a + 1) * nd + 2 * bn + 1] += kab;
                    if axi {
                        k[(2 * a) * nd + 2 * bn] += s[2] * g.n[a] * g.n[bn] / (g.r * g.r) * g.dv;
                    }
                }
            }
        }
    }
    if let Some(k) = ke {
        // Only the upper triangle was accumulated: mirror it.
        for r in 0..nd {
            for c in 0..r {
                k[r * nd + c] = k[c * nd + r];
            }
        }
    }
    Ok(())
}

/// Stress at each quadrature point of the stiffness rule, [xx, yy, zz, xy]: Cauchy stress
/// for large kinematics (σ = J⁻¹ F S Fᵀ), the linear stress otherwise. In plane stress
/// σ_zz = 0. Writes `rule.len()` entries into `out`.
pub fn gauss_stresses(
    kind: CellKind,
    x: &[[f64; 2]],
    u: &[[f64; 2]],
    sm: &SolidModel,
    out: &mut [[f64; 4]],
) -> Result<(), BadJacobian> {
    let nn = kind.num_nodes();
    let d = sm.material.matrix(sm.model);
    let rule = stiffness_rule(kind);
    for (q, &xi) in rule.points.iter().enumerate() {
        let g = point_geometry(kind, x, xi, rule.weights[q], sm).ok_or(BadJacobian)?;
        let (f, fzz, e) = strain_at(&g, nn, u, sm);
        let s = apply(&d, &e);
        out[q] = match sm.kinematics {
            Kinematics::Small => s,
            Kinematics::Large => {
                let j = (f[0][0] * f[1][1] - f[0][1] * f[1][0]) * fzz;
                let sm2 = [[s[0], s[3]], [s[3], s[1]]];
                let mut c = [[0.0; 2]; 2];
                for i in 0..2 {
                    for k in 0..2 {
                        for p in 0..2 {
                            for r in 0..2 {
                                c[i][k] += f[i][p] * sm2[p][r] * f[k][r];
                            }
                        }
                    }
                }
                [c[0][0] / j, c[1][1] / j, fzz * fzz * s[2] / j, c[0][1] / j]
            }
        };
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(m: Modelisation, k: Kinematics) -> SolidModel {
        SolidModel {
            model: m,
            kinematics: k,
            material: Elastic::new(1000.0, 0.3, "test").unwrap(),
            thickness: 1.0,
        }
    }

    fn distorted(kind: CellKind) -> Vec<[f64; 2]> {
        let base: Vec<[f64; 2]> = super::super::element::reference_nodes(kind).to_vec();
        base.iter()
            .enumerate()
            .map(|(i, p)| {
                // affine map + a small nonlinear wiggle, shifted to positive x for axisymmetry
                let s = 0.05 * ((i as f64) * 1.7).sin();
                [
                    2.0 + 1.1 * p[0] + 0.2 * p[1] + s,
                    0.5 + 0.1 * p[0] + 0.9 * p[1] - s,
                ]
            })
            .collect()
    }

    /// The tangent equals the finite-difference derivative of the internal forces.
    #[test]
    fn tangent_matches_finite_differences() {
        for kind in [
            CellKind::Tri3,
            CellKind::Tri6,
            CellKind::Quad4,
            CellKind::Quad8,
        ] {
            for m in [
                Modelisation::PlaneStrain,
                Modelisation::PlaneStress,
                Modelisation::Axisymmetric,
            ] {
                for k in [Kinematics::Small, Kinematics::Large] {
                    if m == Modelisation::PlaneStress && k == Kinematics::Large {
                        continue;
                    }
                    let sm = model(m, k);
                    let x = distorted(kind);
                    let nn = kind.num_nodes();
                    let nd = 2 * nn;
                    let u: Vec<[f64; 2]> = (0..nn)
                        .map(|a| [0.05 * (a as f64 * 0.9).cos(), 0.04 * (a as f64 * 1.3).sin()])
                        .collect();
                    let mut fe = [0.0; MAX_DOFS];
                    let mut ke = [0.0; MAX_DOFS * MAX_DOFS];
                    residual_tangent(kind, &x, &u, &sm, &mut fe, Some(&mut ke)).unwrap();
                    let h = 1e-7;
                    let mut max_err: f64 = 0.0;
                    let mut max_k: f64 = 0.0;
                    for col in 0..nd {
                        let mut up = u.clone();
                        let mut um = u.clone();
                        up[col / 2][col % 2] += h;
                        um[col / 2][col % 2] -= h;
                        let mut fp = [0.0; MAX_DOFS];
                        let mut fm = [0.0; MAX_DOFS];
                        residual_tangent(kind, &x, &up, &sm, &mut fp, None).unwrap();
                        residual_tangent(kind, &x, &um, &sm, &mut fm, None).unwrap();
                        for row in 0..nd {
                            let fd = (fp[row] - fm[row]) / (2.0 * h);
                            max_err = max_err.max((fd - ke[row * nd + col]).abs());
                            max_k = max_k.max(ke[row * nd + col].abs());
                        }
                    }
                    assert!(
                        max_err < 1e-6 * max_k,
                        "{kind} {m:?} {k:?}: FD error {max_err} (|K| {max_k})"
                    );
                }
            }
        }
    }

    /// A rigid rotation produces no Green–Lagrange strain, hence no internal force.
    #[test]
    fn large_rigid_rotation_is_stress_free() {
        for kind in [CellKind::Tri6, CellKind::Quad4, CellKind::Quad8] {
            let sm = model(Modelisation::PlaneStrain, Kinematics::Large);
            let x = distorted(kind);
            let th: f64 = 0.7;
            let u: Vec<[f64; 2]> = x
                .iter()
                .map(|p| {
                    [
                        th.cos() * p[0] - th.sin() * p[1] - p[0],
                        th.sin() * p[0] + th.cos() * p[1] - p[1],
                    ]
                })
                .collect();
            let mut fe = [0.0; MAX_DOFS];
            residual_tangent(kind, &x, &u, &sm, &mut fe, None).unwrap();
            assert!(fe.iter().all(|f| f.abs() < 1e-10), "{kind}: {fe:?}");
        }
    }
}
