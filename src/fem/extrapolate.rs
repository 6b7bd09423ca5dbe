//! Gauss point → node extrapolation, as the reference code does it (contact.md §3.4):
//! fit a field that is linear in the corner shape functions (Q1 on quadrilaterals, P1 on
//! triangles) to the Gauss values by unweighted least squares, take its corner values, and
//! give each mid-side node the mean of its two corners. One Gauss point ⇒ constant.

use super::element::shape;
use super::quadrature::stiffness_rule;
use crate::mesh::CellKind;
use std::sync::OnceLock;

/// Row-major matrix (num_nodes × num_gauss) for `kind`: node value = Σ_g E[n][g] · value_g.
pub fn matrix(kind: CellKind) -> &'static [Vec<f64>] {
    static M: OnceLock<Vec<Vec<Vec<f64>>>> = OnceLock::new();
    let all = M.get_or_init(|| CellKind::ALL.iter().map(|&k| build(k)).collect());
    &all[CellKind::ALL.iter().position(|&k| k == kind).unwrap()]
}

fn build(kind: CellKind) -> Vec<Vec<f64>> {
    let rule = stiffness_rule(kind);
    let ng = rule.len();
    let nn = kind.num_nodes();
    let nc = kind.num_corners();
    if kind.dim() < 2 || ng == 1 {
        return vec![vec![1.0 / ng as f64; ng]; nn];
    }
    let linear = if nc == 3 {
        CellKind::Tri3
    } else {
        CellKind::Quad4
    };
    // P[g][c] = corner shape c at Gauss point g; M = PᵀP; corner values = M⁻¹ Pᵀ σ_g.
    let p: Vec<[f64; 4]> = rule
        .points
        .iter()
        .map(|&xi| {
            let mut n = [0.0; 8];
            shape(linear, xi, &mut n);
            [n[0], n[1], n[2], n[3]]
        })
        .collect();
    let mut m = vec![vec![0.0; nc]; nc];
    for row in &p {
        for i in 0..nc {
            for j in 0..nc {
                m[i][j] += row[i] * row[j];
            }
        }
    }
    let minv = invert(m);
    let mut e = vec![vec![0.0; ng]; nn];
    for c in 0..nc {
        for g in 0..ng {
            e[c][g] = (0..nc).map(|k| minv[c][k] * p[g][k]).sum();
        }
    }
    for (i, pair) in kind.midside_corners().iter().enumerate() {
        for g in 0..ng {
            e[nc + i][g] = 0.5 * (e[pair[0]][g] + e[pair[1]][g]);
        }
    }
    e
}

/// Gauss–Jordan inverse of a small SPD matrix.
fn invert(mut a: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    let n = a.len();
    let mut inv: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
        .collect();
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap();
        a.swap(col, piv);
        inv.swap(col, piv);
        let d = a[col][col];
        for j in 0..n {
            a[col][j] /= d;
            inv[col][j] /= d;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad4_rows_match_the_reference_code() {
        // contact.md §3.4: corner 1 from points 1..4 = [1+√3/2, -1/2, 1-√3/2, -1/2].
        let e = matrix(CellKind::Quad4);
        let s = 3f64.sqrt() / 2.0;
        let expect = [1.0 + s, -0.5, 1.0 - s, -0.5];
        for g in 0..4 {
            assert!((e[0][g] - expect[g]).abs() < 1e-12);
        }
    }

    #[test]
    fn quad8_corner_row_matches_the_reference_code() {
        let e = matrix(CellKind::Quad8);
        let expect = [
            0.958109, -0.305556, 0.097446, -0.305556, 0.326277, -0.104055, -0.104055, 0.326277,
            0.111111,
        ];
        for g in 0..9 {
            assert!((e[0][g] - expect[g]).abs() < 1e-6, "{g}: {}", e[0][g]);
        }
    }

    #[test]
    fn tri6_rows_and_midsides() {
        let e = matrix(CellKind::Tri6);
        let expect = [5.0 / 3.0, -1.0 / 3.0, -1.0 / 3.0];
        for g in 0..3 {
            assert!((e[0][g] - expect[g]).abs() < 1e-12);
            assert!((e[3][g] - 0.5 * (e[0][g] + e[1][g])).abs() < 1e-15);
        }
        assert_eq!(matrix(CellKind::Tri3), &[vec![1.0], vec![1.0], vec![1.0]]);
    }

    #[test]
    fn linear_fields_are_extrapolated_exactly() {
        for kind in [CellKind::Tri6, CellKind::Quad4, CellKind::Quad8] {
            let rule = stiffness_rule(kind);
            let f = |p: [f64; 2]| 2.0 + 3.0 * p[0] - 1.5 * p[1];
            let vals: Vec<f64> = rule.points.iter().map(|&p| f(p)).collect();
            let e = matrix(kind);
            for (n, &xi) in super::super::element::reference_nodes(kind)
                .iter()
                .enumerate()
            {
                let v: f64 = e[n].iter().zip(&vals).map(|(a, b)| a * b).sum();
                assert!((v - f(xi)).abs() < 1e-12, "{kind} node {n}");
            }
        }
    }
}
