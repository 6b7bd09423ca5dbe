//! Closest-point projection of a point on a Seg2/Seg3 segment (current coordinates):
//! Newton on ξ for (x − x̄(ξ))·x̄'(ξ) = 0; the segment's shape functions, points and
//! tangents, generic over the number type (values or dual numbers).

use super::real::{constant, Real};
use crate::mesh::CellKind;

#[derive(Clone, Copy, Debug)]
pub struct Projection {
    /// Parametric coordinate of the projection, unclamped.
    pub xi: f64,
    /// Whether Newton converged.
    pub converged: bool,
}

/// Shape functions of a Seg2/Seg3 and their ξ-derivatives at ξ (any real or dual ξ:
/// the mortar terms are differentiated through the parametric coordinates).
pub fn seg_shape<T: Real>(kind: CellKind, xi: T) -> ([T; 3], [T; 3]) {
    let (half, one): (T, T) = (constant(0.5), constant(1.0));
    match kind {
        CellKind::Seg2 => (
            [half * (one - xi), half * (one + xi), constant(0.0)],
            [constant(-0.5), half, constant(0.0)],
        ),
        _ => (
            [
                half * xi * (xi - 1.0),
                half * xi * (xi + 1.0),
                one - xi * xi,
            ],
            [xi - 0.5, xi + 0.5, xi * -2.0],
        ),
    }
}

/// Position and tangent dx/dξ of the segment at ξ.
pub fn point_and_tangent<T: Real>(kind: CellKind, x: &[[T; 2]], xi: T) -> ([T; 2], [T; 2]) {
    let (n, dn) = seg_shape(kind, xi);
    let zero: T = constant(0.0);
    let mut p = [zero; 2];
    let mut t = [zero; 2];
    for a in 0..kind.num_nodes() {
        for k in 0..2 {
            p[k] += n[a] * x[a][k];
            t[k] += dn[a] * x[a][k];
        }
    }
    (p, t)
}

/// Whether a Newton step on a cell coordinate ξ has converged: below `tolerance`, or below
/// what the coordinates allow. A point at |p| from the origin is known to about
/// ε |p|; on a cell whose tangent dx/dξ has length |t| that is ε |p| / |t| in ξ, and the
/// steps jitter there. A fine mesh far from the origin never gets them below 1e-13 (SSNP154
/// A at 1.38M unknowns: 0.01 mm cells 8 mm out); a loop that waits for that gives up and
/// drops the point, and the residual jumps.
pub fn step_settled(step: f64, tolerance: f64, point: [f64; 2], tangent: [f64; 2]) -> bool {
    let scale = point[0].abs().max(point[1].abs());
    let length = tangent[0].hypot(tangent[1]);
    step.abs() < tolerance.max(64.0 * f64::EPSILON * scale / length)
}

/// Projects `p` on the segment with node coordinates `x`.
pub fn project(kind: CellKind, x: &[[f64; 2]], p: [f64; 2]) -> Projection {
    // Start from the chord projection.
    let (a, b) = (x[0], x[1]);
    let ab = [b[0] - a[0], b[1] - a[1]];
    let l2 = ab[0] * ab[0] + ab[1] * ab[1];
    let mut xi = 2.0 * ((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1]) / l2 - 1.0;
    if kind == CellKind::Seg2 {
        return Projection {
            xi,
            converged: true,
        };
    }
    for _ in 0..20 {
        let (q, t) = point_and_tangent(kind, x, xi);
        // second derivative of a Seg3: constant
        let tt = [
            x[0][0] + x[1][0] - 2.0 * x[2][0],
            x[0][1] + x[1][1] - 2.0 * x[2][1],
        ];
        let d = [p[0] - q[0], p[1] - q[1]];
        let f = d[0] * t[0] + d[1] * t[1];
        let df = -(t[0] * t[0] + t[1] * t[1]) + d[0] * tt[0] + d[1] * tt[1];
        let step = f / df;
        xi -= step;
        if step_settled(step, 1e-14, q, t) {
            return Projection {
                xi,
                converged: true,
            };
        }
    }
    Projection {
        xi,
        converged: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projection_on_a_curved_seg3_is_orthogonal() {
        // Seg3 along a circle arc of radius 2 around the origin.
        let r: f64 = 2.0;
        let ang = |t: f64| [r * t.cos(), r * t.sin()];
        let x = [ang(0.2), ang(0.8), ang(0.5)];
        let p = [2.5 * 0.45f64.cos(), 2.5 * 0.45f64.sin()];
        let pr = project(CellKind::Seg3, &x, p);
        assert!(pr.converged);
        let (q, t) = point_and_tangent(CellKind::Seg3, &x, pr.xi);
        let d = [p[0] - q[0], p[1] - q[1]];
        assert!((d[0] * t[0] + d[1] * t[1]).abs() < 1e-12);
    }

    #[test]
    fn projection_on_seg2_is_exact() {
        let x = [[0.0, 0.0], [2.0, 0.0]];
        let pr = project(CellKind::Seg2, &x, [1.5, 0.3]);
        assert!((pr.xi - 0.5).abs() < 1e-15);
    }
}
