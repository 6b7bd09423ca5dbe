//! Plane geometry of the overlap check: whether a point is inside a body bounded by straight
//! pieces, how deep, and when a moving point crosses a moving piece.

pub type P = [f64; 2];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}

fn cross(a: P, b: P) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// a + s (b − a).
pub fn lerp(a: P, b: P, s: f64) -> P {
    [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]
}

/// Distance from p to the segment ab.
pub fn distance_to_segment(p: P, a: P, b: P) -> f64 {
    let (e, w) = (sub(b, a), sub(p, a));
    let ee = dot(e, e);
    let t = if ee > 0.0 {
        (dot(w, e) / ee).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (w[0] - t * e[0]).hypot(w[1] - t * e[1])
}

/// Whether p is inside the region bounded by `pieces` (closed chains of straight pieces:
/// every boundary of a body, holes included): the parity of the pieces a ray to +x crosses.
/// A point on a piece may count as either; callers measure depth, which is 0 there.
pub fn inside(p: P, pieces: &[(P, P)]) -> bool {
    let mut odd = false;
    for &(a, b) in pieces {
        // half-open in y, so that a ray through a shared vertex counts it once
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if x > p[0] {
                odd = !odd;
            }
        }
    }
    odd
}

/// How deep p is inside the region bounded by `pieces` (its distance to the nearest
/// piece), None when it is outside.
pub fn depth(p: P, pieces: &[(P, P)]) -> Option<f64> {
    if !inside(p, pieces) {
        return None;
    }
    Some(
        pieces
            .iter()
            .map(|&(a, b)| distance_to_segment(p, a, b))
            .fold(f64::INFINITY, f64::min),
    )
}

/// The times s in (0, 1) at which the point p0 + s dp lies on the piece whose ends move
/// linearly from (a0, b0) to (a1, b1), appended to `out`: the moments it may enter or leave
/// the body. (Collinear at all times: none, it slides along the boundary.)
pub fn crossing_times(p0: P, p1: P, a: (P, P), b: (P, P), out: &mut Vec<f64>) {
    let (e0, e1) = (sub(b.0, a.0), sub(b.1, a.1));
    let (w0, w1) = (sub(p0, a.0), sub(p1, a.1));
    let (de, dw) = (sub(e1, e0), sub(w1, w0));
    // cross(e0 + s de, w0 + s dw) = c0 + c1 s + c2 s²
    let c0 = cross(e0, w0);
    let c1 = cross(e0, dw) + cross(de, w0);
    let c2 = cross(de, dw);
    let size = c0.abs() + c1.abs() + c2.abs();
    if size == 0.0 {
        return;
    }
    let mut roots = [f64::NAN; 2];
    if c2.abs() <= 1e-14 * size {
        if c1.abs() > 1e-14 * size {
            roots[0] = -c0 / c1;
        }
    } else {
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc >= 0.0 {
            // the stable pair of roots
            let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
            roots = [q / c2, if q != 0.0 { c0 / q } else { f64::NAN }];
        }
    }
    for s in roots {
        if !(s > 0.0 && s < 1.0) {
            continue;
        }
        let (e, w) = (lerp(e0, e1, s), lerp(w0, w1, s));
        let ee = dot(e, e);
        let t = if ee > 0.0 { dot(w, e) / ee } else { 0.0 };
        if (-1e-9..=1.0 + 1e-9).contains(&t) {
            out.push(s);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit square, counter-clockwise, as four pieces.
    fn square() -> Vec<(P, P)> {
        let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        (0..4).map(|i| (c[i], c[(i + 1) % 4])).collect()
    }

    #[test]
    fn a_point_inside_has_its_distance_to_the_boundary_as_depth() {
        let d = depth([0.5, 0.3], &square()).unwrap();
        assert!((d - 0.3).abs() < 1e-15, "{d}");
        assert!(depth([1.5, 0.5], &square()).is_none());
        assert!(depth([0.5, -1e-3], &square()).is_none());
    }

    #[test]
    fn a_point_on_the_boundary_or_a_vertex_has_no_depth() {
        for p in [[0.5, 0.0], [1.0, 0.5], [0.0, 0.0], [1.0, 1.0], [0.5, 1.0]] {
            let d = depth(p, &square()).unwrap_or(0.0);
            assert!(d <= 1e-15, "{p:?}: {d}");
        }
    }

    #[test]
    fn a_hole_is_outside() {
        // the square with a square hole (clockwise) of side 0.5 in its middle
        let mut pieces = square();
        let h = [[0.25, 0.25], [0.25, 0.75], [0.75, 0.75], [0.75, 0.25]];
        pieces.extend((0..4).map(|i| (h[i], h[(i + 1) % 4])));
        assert!(depth([0.5, 0.5], &pieces).is_none());
        let d = depth([0.1, 0.5], &pieces).unwrap();
        assert!((d - 0.1).abs() < 1e-15, "{d}");
    }

    #[test]
    fn a_point_through_a_fixed_piece_crosses_it_once() {
        let mut s = vec![];
        crossing_times(
            [0.5, 2.0],
            [0.5, -2.0],
            ([0.0, 1.0], [0.0, 1.0]),
            ([1.0, 1.0], [1.0, 1.0]),
            &mut s,
        );
        assert_eq!(s.len(), 1);
        assert!((s[0] - 0.25).abs() < 1e-15, "{s:?}");
        // passing beside the piece: no crossing
        s.clear();
        crossing_times(
            [2.5, 2.0],
            [2.5, -2.0],
            ([0.0, 1.0], [0.0, 1.0]),
            ([1.0, 1.0], [1.0, 1.0]),
            &mut s,
        );
        assert!(s.is_empty(), "{s:?}");
    }

    #[test]
    fn a_moving_piece_met_by_a_still_point() {
        // the piece y = 1 − 2s over x in [0, 1] sweeps the still point (0.5, 0) at s = 1/2
        let mut s = vec![];
        crossing_times(
            [0.5, 0.0],
            [0.5, 0.0],
            ([0.0, 1.0], [0.0, -1.0]),
            ([1.0, 1.0], [1.0, -1.0]),
            &mut s,
        );
        assert_eq!(s.len(), 1);
        assert!((s[0] - 0.5).abs() < 1e-15, "{s:?}");
        // sliding along the piece, collinear throughout: no crossing event
        s.clear();
        crossing_times(
            [0.0, 0.0],
            [1.0, 0.0],
            ([0.0, 0.0], [0.0, 0.0]),
            ([1.0, 0.0], [1.0, 0.0]),
            &mut s,
        );
        assert!(s.is_empty(), "{s:?}");
    }
}
