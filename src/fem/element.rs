//! Shape functions on the reference cells, by `CellKind`.
//!
//! Reference cells: Seg on ξ ∈ [-1, 1] (nodes -1, +1, then 0); Tri on the unit triangle
//! (0,0), (1,0), (0,1); Quad on [-1, 1]² with corners counter-clockwise from (-1,-1).
//! Quad8 is the 8-node serendipity element.

use crate::mesh::CellKind;

/// Largest node count of any cell kind: fixed-size buffers use it.
pub const MAX_NODES: usize = 8;

/// Reference coordinates of the nodes of `kind` (segments use the first coordinate).
pub fn reference_nodes(kind: CellKind) -> &'static [[f64; 2]] {
    match kind {
        CellKind::Point1 => &[[0.0, 0.0]],
        CellKind::Seg2 => &[[-1.0, 0.0], [1.0, 0.0]],
        CellKind::Seg3 => &[[-1.0, 0.0], [1.0, 0.0], [0.0, 0.0]],
        CellKind::Tri3 => &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        CellKind::Tri6 => &[
            [0.0, 0.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [0.5, 0.0],
            [0.5, 0.5],
            [0.0, 0.5],
        ],
        CellKind::Quad4 => &[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]],
        CellKind::Quad8 => &[
            [-1.0, -1.0],
            [1.0, -1.0],
            [1.0, 1.0],
            [-1.0, 1.0],
            [0.0, -1.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [-1.0, 0.0],
        ],
    }
}

/// Shape function values at `xi`, written to `n[..kind.num_nodes()]`.
pub fn shape(kind: CellKind, xi: [f64; 2], n: &mut [f64]) {
    let (x, y) = (xi[0], xi[1]);
    match kind {
        CellKind::Point1 => n[0] = 1.0,
        CellKind::Seg2 => {
            n[0] = 0.5 * (1.0 - x);
            n[1] = 0.5 * (1.0 + x);
        }
        CellKind::Seg3 => {
            n[0] = 0.5 * x * (x - 1.0);
            n[1] = 0.5 * x * (x + 1.0);
            n[2] = 1.0 - x * x;
        }
        CellKind::Tri3 => {
            n[0] = 1.0 - x - y;
            n[1] = x;
            n[2] = y;
        }
        CellKind::Tri6 => {
            let l = 1.0 - x - y;
            n[0] = l * (2.0 * l - 1.0);
            n[1] = x * (2.0 * x - 1.0);
            n[2] = y * (2.0 * y - 1.0);
            n[3] = 4.0 * l * x;
            n[4] = 4.0 * x * y;
            n[5] = 4.0 * y * l;
        }
        CellKind::Quad4 => {
            n[0] = 0.25 * (1.0 - x) * (1.0 - y);
            n[1] = 0.25 * (1.0 + x) * (1.0 - y);
            n[2] = 0.25 * (1.0 + x) * (1.0 + y);
            n[3] = 0.25 * (1.0 - x) * (1.0 + y);
        }
        CellKind::Quad8 => {
            n[0] = 0.25 * (1.0 - x) * (1.0 - y) * (-x - y - 1.0);
            n[1] = 0.25 * (1.0 + x) * (1.0 - y) * (x - y - 1.0);
            n[2] = 0.25 * (1.0 + x) * (1.0 + y) * (x + y - 1.0);
            n[3] = 0.25 * (1.0 - x) * (1.0 + y) * (-x + y - 1.0);
            n[4] = 0.5 * (1.0 - x * x) * (1.0 - y);
            n[5] = 0.5 * (1.0 + x) * (1.0 - y * y);
            n[6] = 0.5 * (1.0 - x * x) * (1.0 + y);
            n[7] = 0.5 * (1.0 - x) * (1.0 - y * y);
        }
    }
}

/// Shape function gradients with respect to the reference coordinates at `xi`, written to
/// `dn[..kind.num_nodes()]` as [∂N/∂ξ, ∂N/∂η] (the second is 0 for segments).
pub fn shape_grad(kind: CellKind, xi: [f64; 2], dn: &mut [[f64; 2]]) {
    let (x, y) = (xi[0], xi[1]);
    match kind {
        CellKind::Point1 => dn[0] = [0.0, 0.0],
        CellKind::Seg2 => {
            dn[0] = [-0.5, 0.0];
            dn[1] = [0.5, 0.0];
        }
        CellKind::Seg3 => {
            dn[0] = [x - 0.5, 0.0];
            dn[1] = [x + 0.5, 0.0];
            dn[2] = [-2.0 * x, 0.0];
        }
        CellKind::Tri3 => {
            dn[0] = [-1.0, -1.0];
            dn[1] = [1.0, 0.0];
            dn[2] = [0.0, 1.0];
        }
        CellKind::Tri6 => {
            let l = 1.0 - x - y;
            dn[0] = [1.0 - 4.0 * l, 1.0 - 4.0 * l];
            dn[1] = [4.0 * x - 1.0, 0.0];
            dn[2] = [0.0, 4.0 * y - 1.0];
            dn[3] = [4.0 * (l - x), -4.0 * x];
            dn[4] = [4.0 * y, 4.0 * x];
            dn[5] = [-4.0 * y, 4.0 * (l - y)];
        }
        CellKind::Quad4 => {
            dn[0] = [-0.25 * (1.0 - y), -0.25 * (1.0 - x)];
            dn[1] = [0.25 * (1.0 - y), -0.25 * (1.0 + x)];
            dn[2] = [0.25 * (1.0 + y), 0.25 * (1.0 + x)];
            dn[3] = [-0.25 * (1.0 + y), 0.25 * (1.0 - x)];
        }
        CellKind::Quad8 => {
            dn[0] = [
                0.25 * (1.0 - y) * (2.0 * x + y),
                0.25 * (1.0 - x) * (x + 2.0 * y),
            ];
            dn[1] = [
                0.25 * (1.0 - y) * (2.0 * x - y),
                0.25 * (1.0 + x) * (2.0 * y - x),
            ];
            dn[2] = [
                0.25 * (1.0 + y) * (2.0 * x + y),
                0.25 * (1.0 + x) * (x + 2.0 * y),
            ];
            dn[3] = [
                0.25 * (1.0 + y) * (2.0 * x - y),
                0.25 * (1.0 - x) * (2.0 * y - x),
            ];
            dn[4] = [-x * (1.0 - y), -0.5 * (1.0 - x * x)];
            dn[5] = [0.5 * (1.0 - y * y), -y * (1.0 + x)];
            dn[6] = [-x * (1.0 + y), 0.5 * (1.0 - x * x)];
            dn[7] = [-0.5 * (1.0 - y * y), -y * (1.0 - x)];
        }
    }
}

/// Jacobian determinant of the map from the reference cell of a 2D `kind` to the physical
/// cell with node coordinates `x`, at `xi`.
pub fn jacobian_det(kind: CellKind, x: &[[f64; 2]], xi: [f64; 2]) -> f64 {
    let mut dn = [[0.0; 2]; MAX_NODES];
    shape_grad(kind, xi, &mut dn);
    let mut j = [[0.0; 2]; 2];
    for (a, xa) in x.iter().enumerate().take(kind.num_nodes()) {
        for r in 0..2 {
            for c in 0..2 {
                j[r][c] += xa[r] * dn[a][c];
            }
        }
    }
    j[0][0] * j[1][1] - j[0][1] * j[1][0]
}

#[cfg(test)]
mod tests {
    use super::*;

    const KINDS: [CellKind; 6] = [
        CellKind::Seg2,
        CellKind::Seg3,
        CellKind::Tri3,
        CellKind::Tri6,
        CellKind::Quad4,
        CellKind::Quad8,
    ];

    fn sample_points(kind: CellKind) -> Vec<[f64; 2]> {
        match kind.dim() {
            1 => vec![[-0.7, 0.0], [0.13, 0.0], [0.91, 0.0]],
            _ if kind.num_corners() == 3 => vec![[0.1, 0.2], [0.6, 0.3], [0.25, 0.05]],
            _ => vec![[-0.3, 0.8], [0.45, -0.6], [0.9, 0.1]],
        }
    }

    #[test]
    fn partition_of_unity_and_zero_gradient_sum() {
        for kind in KINDS {
            for xi in sample_points(kind) {
                let mut n = [0.0; MAX_NODES];
                let mut dn = [[0.0; 2]; MAX_NODES];
                shape(kind, xi, &mut n);
                shape_grad(kind, xi, &mut dn);
                let s: f64 = n[..kind.num_nodes()].iter().sum();
                assert!((s - 1.0).abs() < 1e-14, "{kind}: sum {s}");
                for d in 0..2 {
                    let g: f64 = dn[..kind.num_nodes()].iter().map(|g| g[d]).sum();
                    assert!(g.abs() < 1e-14, "{kind}: grad sum {g}");
                }
            }
        }
    }

    #[test]
    fn kronecker_property_at_nodes() {
        for kind in KINDS {
            for (i, &xi) in reference_nodes(kind).iter().enumerate() {
                let mut n = [0.0; MAX_NODES];
                shape(kind, xi, &mut n);
                for (j, &v) in n[..kind.num_nodes()].iter().enumerate() {
                    let expect = if i == j { 1.0 } else { 0.0 };
                    assert!((v - expect).abs() < 1e-14, "{kind}: N{j}(node {i}) = {v}");
                }
            }
        }
    }

    #[test]
    fn gradients_match_finite_differences() {
        let h = 1e-6;
        for kind in KINDS {
            for xi in sample_points(kind) {
                let mut dn = [[0.0; 2]; MAX_NODES];
                shape_grad(kind, xi, &mut dn);
                for d in 0..kind.dim() {
                    let (mut p, mut m) = (xi, xi);
                    p[d] += h;
                    m[d] -= h;
                    let mut np = [0.0; MAX_NODES];
                    let mut nm = [0.0; MAX_NODES];
                    shape(kind, p, &mut np);
                    shape(kind, m, &mut nm);
                    for a in 0..kind.num_nodes() {
                        let fd = (np[a] - nm[a]) / (2.0 * h);
                        assert!(
                            (fd - dn[a][d]).abs() < 1e-8,
                            "{kind} N{a} d{d}: {fd} vs {}",
                            dn[a][d]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn linear_fields_are_reproduced() {
        // Σ N_a x_a = x for the reference node coordinates (isoparametric completeness).
        for kind in KINDS {
            let nodes = reference_nodes(kind);
            for xi in sample_points(kind) {
                let mut n = [0.0; MAX_NODES];
                shape(kind, xi, &mut n);
                for d in 0..kind.dim() {
                    let v: f64 = (0..kind.num_nodes()).map(|a| n[a] * nodes[a][d]).sum();
                    assert!((v - xi[d]).abs() < 1e-14);
                }
            }
        }
    }
}
