//! Element residual (internal forces) and tangent of one solid cell, for small strain or
//! total-Lagrangian finite strain (Green–Lagrange strain, St Venant–Kirchhoff), in plane
//! strain, plane stress and axisymmetry.
//!
//! Plane stress with large kinematics: St Venant–Kirchhoff is linear in E, so S_33 = 0
//! gives E_33 = −λ/(λ+2μ)(E_11+E_22) exactly and the in-plane S is the plane-stress law
//! with the reduced λ' = 2λμ/(λ+2μ) (the plane-stress elasticity matrix, unchanged). The
//! weak form is per unit reference thickness (total Lagrangian, ∫ S : δE dV₀); the
//! thickness stretch λ₃ = √(1 + 2E_33) enters only the Cauchy stress, through J = det F·λ₃.
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
    ke: Option<&mut [f64]>,
) -> Result<(), BadJacobian> {
    // The node count as a constant: the loops below unroll and vectorise.
    match kind.num_nodes() {
        3 => kernel::<3>(kind, x, u, sm, fe, ke),
        4 => kernel::<4>(kind, x, u, sm, fe, ke),
        6 => kernel::<6>(kind, x, u, sm, fe, ke),
        8 => kernel::<8>(kind, x, u, sm, fe, ke),
        n => unreachable!("no solid cell has {n} nodes"),
    }
}

fn kernel<const NN: usize>(
    kind: CellKind,
    x: &[[f64; 2]],
    u: &[[f64; 2]],
    sm: &SolidModel,
    fe: &mut [f64],
    mut ke: Option<&mut [f64]>,
) -> Result<(), BadJacobian> {
    let nd = 2 * NN;
    fe[..nd].fill(0.0);
    if let Some(k) = ke.as_deref_mut() {
        k[..nd * nd].fill(0.0);
    }
    let d = sm.material.matrix(sm.model);
    let axi = sm.model == Modelisation::Axisymmetric;
    let large = sm.kinematics == Kinematics::Large;
    let rule = stiffness_rule(kind);
    // The material part Bᵀ D B over Voigt rows [xx, yy, zz, xy]; the hoop row (zz) is zero
    // outside axisymmetry and skipped.
    let rows: &[usize] = if axi { &[0, 1, 2, 3] } else { &[0, 1, 3] };
    for (q, &xi) in rule.points.iter().enumerate() {
        let g = point_geometry(kind, x, xi, rule.weights[q], sm).ok_or(BadJacobian)?;
        let (f, fzz, e) = strain_at(&g, NN, u, sm);
        let s = apply(&d, &e);
        // B as 4 rows of nd columns
        let mut bm = [[0.0; MAX_DOFS]; 4];
        for a in 0..NN {
            let ba = b_rows(&g, a, &f, fzz, axi);
            for v in 0..4 {
                bm[v][2 * a] = ba[v][0];
                bm[v][2 * a + 1] = ba[v][1];
            }
        }
        // (the hoop row of B is zero outside axisymmetry: all four rows can be summed)
        let sdv = [s[0] * g.dv, s[1] * g.dv, s[2] * g.dv, s[3] * g.dv];
        for c in 0..nd {
            fe[c] += bm[0][c] * sdv[0] + bm[1][c] * sdv[1] + bm[2][c] * sdv[2] + bm[3][c] * sdv[3];
        }
        let Some(k) = ke.as_deref_mut() else { continue };
        // D·B scaled by the point's measure
        let mut dbm = [[0.0; MAX_DOFS]; 4];
        for &v in rows {
            for &w in rows {
                let dvw = d[v][w] * g.dv;
                if dvw != 0.0 {
                    for c in 0..nd {
                        dbm[v][c] += dvw * bm[w][c];
                    }
                }
            }
        }
        // Geometric stiffness ∇N_a · S · ∇N_b on both in-plane dofs (large kinematics),
        // summed in the same pass: for row r = 2a + i, (S ∇N_a) · ∇N_b at the columns
        // 2b + i, from ∇N spread over the columns of component i (`grad[i][p][c]`).
        let mut grad = [[[0.0; MAX_DOFS]; 2]; 2];
        let mut sgrad = [[0.0; 2]; MAX_NODES];
        if large {
            for a in 0..NN {
                let (ax, ay) = (g.dn[a][0], g.dn[a][1]);
                for i in 0..2 {
                    grad[i][0][2 * a + i] = ax;
                    grad[i][1][2 * a + i] = ay;
                }
                sgrad[a] = [
                    (ax * s[0] + ay * s[3]) * g.dv,
                    (ax * s[3] + ay * s[1]) * g.dv,
                ];
            }
        }
        // Every entry is summed, but only the upper triangle is kept (mirrored after the
        // loop) so that the matrix is exactly symmetric.
        for r in 0..nd {
            let row = &mut k[r * nd..(r + 1) * nd];
            let b = [bm[0][r], bm[1][r], bm[2][r], bm[3][r]];
            let (sg, gr) = (sgrad[r / 2], &grad[r % 2]);
            for c in 0..nd {
                row[c] += b[0] * dbm[0][c]
                    + b[1] * dbm[1][c]
                    + b[2] * dbm[2][c]
                    + b[3] * dbm[3][c]
                    + sg[0] * gr[0][c]
                    + sg[1] * gr[1][c];
            }
        }
        if large && axi {
            // hoop part of the geometric stiffness, on the radial dofs
            for a in 0..NN {
                for bn in 0..NN {
                    k[(2 * a) * nd + 2 * bn] += s[2] * g.n[a] * g.n[bn] / (g.r * g.r) * g.dv;
                }
            }
        }
    }
    if let Some(k) = ke {
        // mirror the upper triangle: exactly symmetric
        for r in 0..nd {
            for c in 0..r {
                k[r * nd + c] = k[c * nd + r];
            }
        }
    }
    Ok(())
}

/// Which stress `gauss_stresses_as` gives with large kinematics (small kinematics has one).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StressMeasure {
    Cauchy,
    /// Second Piola–Kirchhoff: S = J F⁻¹ σ F⁻ᵀ, work-conjugate to the Green–Lagrange strain.
    Pk2,
}

/// Stress at each quadrature point of the stiffness rule, [xx, yy, zz, xy]: Cauchy stress
/// for large kinematics (σ = J⁻¹ F S Fᵀ, J = det F·F_zz with F_zz the thickness stretch in
/// plane stress), the linear stress otherwise. In plane stress σ_zz = 0. Writes `rule.len()` entries into `out`.
pub fn gauss_stresses(
    kind: CellKind,
    x: &[[f64; 2]],
    u: &[[f64; 2]],
    sm: &SolidModel,
    out: &mut [[f64; 4]],
) -> Result<(), BadJacobian> {
    gauss_stresses_as(kind, x, u, sm, StressMeasure::Cauchy, out)
}

/// The thickness stretch λ₃ = √(1 + 2E_33) of plane stress with large kinematics, from the
/// in-plane Green–Lagrange strain [xx, yy, zz, γxy]: E_33 = −λ/(λ+2μ)(E_11+E_22), exact for
/// St Venant–Kirchhoff (S_33 = 0). NaN when 1 + 2E_33 ≤ 0 (the law has no thickness left
/// there: an in-plane stretch far beyond its range).
pub fn thickness_stretch(material: &Elastic, e: &[f64; 4]) -> f64 {
    let c = 1.0 + 2.0 * material.plane_stress_ezz(e[0], e[1]);
    if c > 0.0 {
        c.sqrt()
    } else {
        f64::NAN
    }
}

/// `gauss_stresses` in the given measure.
pub fn gauss_stresses_as(
    kind: CellKind,
    x: &[[f64; 2]],
    u: &[[f64; 2]],
    sm: &SolidModel,
    measure: StressMeasure,
    out: &mut [[f64; 4]],
) -> Result<(), BadJacobian> {
    let nn = kind.num_nodes();
    let d = sm.material.matrix(sm.model);
    let rule = stiffness_rule(kind);
    for (q, &xi) in rule.points.iter().enumerate() {
        let g = point_geometry(kind, x, xi, rule.weights[q], sm).ok_or(BadJacobian)?;
        let (f, mut fzz, e) = strain_at(&g, nn, u, sm);
        let s = apply(&d, &e);
        if sm.model == Modelisation::PlaneStress {
            fzz = thickness_stretch(&sm.material, &e);
        }
        out[q] = match (sm.kinematics, measure) {
            (Kinematics::Small, _) | (_, StressMeasure::Pk2) => s,
            (Kinematics::Large, StressMeasure::Cauchy) => {
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
