//! Contact tractions recovered from the stresses at the surface nodes (p = −n·σ·n,
//! shear = t·σ·n), on the initial or the deformed geometry, and a half-width estimate from
//! nodal pressures.

use crate::contact::surface::Surface;
use crate::mesh::Mesh;

/// The Hertz line-contact pressure p0 √(1 − x²/a²) inside the half-width a, 0 outside.
pub fn hertz_pressure(a: f64, p0: f64, x: f64) -> f64 {
    if x.abs() < a {
        p0 * (1.0 - (x / a).powi(2)).sqrt()
    } else {
        0.0
    }
}

/// Unit outward normal at each node of a surface: mean of the adjacent edges' normals
/// (of the reference geometry, or of the deformed one when `u` is given).
pub fn nodal_normals(mesh: &Mesh, surface: &Surface, u: Option<&[f64]>) -> Vec<(usize, [f64; 2])> {
    let pos = |n: usize| match u {
        Some(u) => [
            mesh.coords[n][0] + u[2 * n],
            mesh.coords[n][1] + u[2 * n + 1],
        ],
        None => mesh.coords[n],
    };
    let mut acc: std::collections::BTreeMap<usize, [f64; 2]> = Default::default();
    for (i, &c) in surface.cells.iter().enumerate() {
        let nodes = mesh.cell_nodes(c);
        let (a, b) = (pos(nodes[0]), pos(nodes[1]));
        let t = [b[0] - a[0], b[1] - a[1]];
        let l = t[0].hypot(t[1]);
        let n = if surface.ccw[i] {
            [t[1] / l, -t[0] / l]
        } else {
            [-t[1] / l, t[0] / l]
        };
        for &node in nodes {
            let e = acc.entry(node).or_insert([0.0; 2]);
            e[0] += n[0];
            e[1] += n[1];
        }
    }
    acc.into_iter()
        .map(|(node, v)| {
            let l = v[0].hypot(v[1]);
            (node, [v[0] / l, v[1] / l])
        })
        .collect()
}

/// (node, pressure −n·σ·n, shear t·σ·n with t = n turned by +90°) at the surface nodes.
pub fn surface_tractions(
    mesh: &Mesh,
    surface: &Surface,
    stress: &[[f64; 4]],
    u: Option<&[f64]>,
) -> Vec<(usize, f64, f64)> {
    nodal_normals(mesh, surface, u)
        .into_iter()
        .map(|(node, n)| {
            let s = stress[node];
            let sn = [s[0] * n[0] + s[3] * n[1], s[3] * n[0] + s[1] * n[1]];
            let t = [-n[1], n[0]];
            (
                node,
                -(n[0] * sn[0] + n[1] * sn[1]),
                t[0] * sn[0] + t[1] * sn[1],
            )
        })
        .collect()
}

/// A large-displacement contact pressure as it is measured: (deformed x, true pressure)
/// per slave node. A `nominal` pressure (per initial length: point-to-segment and
/// node-to-segment weights use the initial slave Jacobian) is multiplied by the surface
/// stretch, the initial over the deformed distance between the node's neighbours along the
/// surface (nodes ordered by their initial x); the mortar integrals are on the current
/// configuration, so its multipliers are true pressures already.
pub fn deformed_profile(
    mesh: &Mesh,
    u: &[f64],
    pressures: &[(usize, f64)],
    nominal: bool,
) -> Vec<(f64, f64)> {
    let mut pts: Vec<([f64; 2], [f64; 2], f64)> = pressures
        .iter()
        .map(|&(n, p)| {
            let x0 = mesh.coords[n];
            (x0, [x0[0] + u[2 * n], x0[1] + u[2 * n + 1]], p)
        })
        .collect();
    pts.sort_by(|l, r| l.0[0].total_cmp(&r.0[0]));
    let dist = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    (0..pts.len())
        .map(|i| {
            let (lo, hi) = (i.saturating_sub(1), (i + 1).min(pts.len() - 1));
            let stretch = if nominal {
                dist(pts[hi].0, pts[lo].0) / dist(pts[hi].1, pts[lo].1)
            } else {
                1.0
            };
            (pts[i].1[0], pts[i].2 * stretch)
        })
        .collect()
}

/// Contact half-width from nodal pressures along a coordinate x ≥ 0 (the pressure vanishing
/// beyond it): the elliptical (Hertz-shaped) profile p² = A − B x² fitted by least squares
/// to the loaded nodes of the outer half of the loaded zone but the last one (whose value
/// averages the pressure over a support that straddles the edge), a = √(A/B); through the
/// last two loaded nodes when fewer remain; the last loaded node's x when no fit is defined
/// or the fit ends before it.
pub fn half_width(samples: &[(f64, f64)]) -> Option<f64> {
    let mut s: Vec<(f64, f64)> = samples.to_vec();
    s.sort_by(|a, b| a.0.total_cmp(&b.0));
    let pmax = s.iter().fold(0.0f64, |m, p| m.max(p.1));
    // multipliers of open nodes are zero up to round-off: "loaded" is above 1e-3 of the peak
    let loaded: Vec<(f64, f64)> = s.into_iter().filter(|p| p.1 > 1e-3 * pmax).collect();
    let &(x_last, _) = loaded.last()?;
    let inner: Vec<(f64, f64)> = loaded[..loaded.len() - 1]
        .iter()
        .copied()
        .filter(|p| p.0 >= 0.5 * x_last)
        .collect();
    let fit: Vec<(f64, f64)> = if inner.len() >= 3 {
        inner
    } else {
        loaded[loaded.len().checked_sub(2)?..].to_vec()
    };
    // least squares of y = p² against z = x²: y = A − B z
    let n = fit.len() as f64;
    let (sz, sy) = fit
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 * p.0, b + p.1 * p.1));
    let (mz, my) = (sz / n, sy / n);
    let (mut szz, mut szy) = (0.0, 0.0);
    for p in &fit {
        let (dz, dy) = (p.0 * p.0 - mz, p.1 * p.1 - my);
        szz += dz * dz;
        szy += dz * dy;
    }
    let b = -szy / szz;
    let a = my + b * mz;
    if b > 0.0 && a > 0.0 && (a / b).sqrt() >= x_last {
        Some((a / b).sqrt())
    } else {
        Some(x_last)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_width_of_sampled_hertz_profile_is_exact() {
        let (a, p0) = (6.2146, 3585.36);
        let s: Vec<(f64, f64)> = (0..12)
            .map(|i| {
                let x = 0.6 * i as f64;
                (
                    x,
                    if x < a {
                        p0 * (1.0 - (x / a).powi(2)).sqrt()
                    } else {
                        0.0
                    },
                )
            })
            .collect();
        assert!((half_width(&s).unwrap() - a).abs() < 1e-9);
    }

    #[test]
    fn uniform_stress_gives_its_normal_traction() {
        // a unit square's top edge, σ_yy = -10, σ_xy = 3
        let m = crate::mesh::generate::rectangle(
            [0.0, 0.0],
            1.0,
            1.0,
            2,
            2,
            crate::mesh::CellKind::Quad4,
            0.0,
        )
        .unwrap();
        let top = Surface::from_group(&m, "Top", "test").unwrap();
        let stress = vec![[0.0, -10.0, 0.0, 3.0]; m.num_nodes()];
        for (_, p, t) in surface_tractions(&m, &top, &stress, None) {
            assert!((p - 10.0).abs() < 1e-12);
            assert!((t.abs() - 3.0).abs() < 1e-12);
        }
    }
}
