//! Quadrature rules on the reference cells.
//!
//! The stiffness rules are those of the reference code (contact.md §3.3): Quad4 2×2,
//! Quad8 3×3, Tri3 1 point, Tri6 3 points, with its point order (the extrapolation to
//! nodes depends on it). Higher rules (Gauss–Legendre of any order, collapsed Gauss on
//! triangles) serve error norms and edge loads.

use crate::mesh::CellKind;
use std::sync::OnceLock;

#[derive(Clone, Debug)]
pub struct Rule {
    pub points: Vec<[f64; 2]>,
    pub weights: Vec<f64>,
}

impl Rule {
    pub fn len(&self) -> usize {
        self.points.len()
    }
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}

/// Gauss–Legendre points and weights on [-1, 1] with `n` points (exact to degree 2n-1).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(n >= 1);
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        // Newton on P_n from the Chebyshev-like initial guess.
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { z } else { p1 };
            let pnm1 = if n == 1 { 1.0 } else { p0 };
            dp = n as f64 * (z * pn - pnm1) / (z * z - 1.0);
            let dz = pn / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        if n == 1 {
            z = 0.0;
            dp = 1.0;
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        let wi = if n == 1 {
            2.0
        } else {
            2.0 / ((1.0 - z * z) * dp * dp)
        };
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    (x, w)
}

/// Line rule with `n` Gauss points (second coordinate 0).
pub fn line(n: usize) -> Rule {
    let (x, w) = gauss_legendre(n);
    Rule {
        points: x.iter().map(|&p| [p, 0.0]).collect(),
        weights: w,
    }
}

/// Tensor n×n Gauss rule on [-1, 1]².
pub fn quad(n: usize) -> Rule {
    let (x, w) = gauss_legendre(n);
    let mut r = Rule {
        points: vec![],
        weights: vec![],
    };
    for j in 0..n {
        for i in 0..n {
            r.points.push([x[i], x[j]]);
            r.weights.push(w[i] * w[j]);
        }
    }
    r
}

/// Collapsed (Duffy) n×n Gauss rule on the unit triangle, exact to degree 2n-2 at least.
pub fn triangle(n: usize) -> Rule {
    let (x, w) = gauss_legendre(n);
    let mut r = Rule {
        points: vec![],
        weights: vec![],
    };
    for j in 0..n {
        for i in 0..n {
            let u = 0.5 * (1.0 + x[i]);
            let v = 0.5 * (1.0 + x[j]);
            r.points.push([u * (1.0 - v), v]);
            r.weights.push(0.25 * w[i] * w[j] * (1.0 - v));
        }
    }
    r
}

/// A rule for integrating over a cell of `kind` polynomials of degree `degree`.
pub fn exact_to_degree(kind: CellKind, degree: usize) -> Rule {
    let n = degree / 2 + 1;
    match kind.dim() {
        0 => Rule {
            points: vec![[0.0, 0.0]],
            weights: vec![1.0],
        },
        1 => line(n),
        _ if kind.num_corners() == 3 => triangle(n + 1),
        _ => quad(n),
    }
}

fn build_stiffness_rule(kind: CellKind) -> Rule {
    match kind {
        CellKind::Point1 => Rule {
            points: vec![[0.0, 0.0]],
            weights: vec![1.0],
        },
        CellKind::Seg2 => line(2),
        CellKind::Seg3 => line(3),
        CellKind::Tri3 => Rule {
            points: vec![[1.0 / 3.0, 1.0 / 3.0]],
            weights: vec![0.5],
        },
        CellKind::Tri6 => Rule {
            points: vec![
                [1.0 / 6.0, 1.0 / 6.0],
                [2.0 / 3.0, 1.0 / 6.0],
                [1.0 / 6.0, 2.0 / 3.0],
            ],
            weights: vec![1.0 / 6.0; 3],
        },
        CellKind::Quad4 => {
            let a = 1.0 / 3f64.sqrt();
            Rule {
                points: vec![[-a, -a], [a, -a], [a, a], [-a, a]],
                weights: vec![1.0; 4],
            }
        }
        CellKind::Quad8 => {
            let a = 0.6f64.sqrt();
            let (wc, wm, w0) = (25.0 / 81.0, 40.0 / 81.0, 64.0 / 81.0);
            Rule {
                points: vec![
                    [-a, -a],
                    [a, -a],
                    [a, a],
                    [-a, a],
                    [0.0, -a],
                    [a, 0.0],
                    [0.0, a],
                    [-a, 0.0],
                    [0.0, 0.0],
                ],
                weights: vec![wc, wc, wc, wc, wm, wm, wm, wm, w0],
            }
        }
    }
}

/// The stiffness rule of `kind` (cached).
pub fn stiffness_rule(kind: CellKind) -> &'static Rule {
    static RULES: OnceLock<Vec<Rule>> = OnceLock::new();
    let rules = RULES.get_or_init(|| {
        CellKind::ALL
            .iter()
            .map(|&k| build_stiffness_rule(k))
            .collect()
    });
    &rules[CellKind::ALL.iter().position(|&k| k == kind).unwrap()]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact integral of x^i y^j over the reference cell.
    fn exact_monomial(kind: CellKind, i: i32, j: i32) -> f64 {
        let line = |p: i32| {
            if p % 2 == 1 {
                0.0
            } else {
                2.0 / (p as f64 + 1.0)
            }
        };
        match kind.dim() {
            1 => line(i),
            _ if kind.num_corners() == 3 => {
                // ∫ x^i y^j over the unit triangle = i! j! / (i + j + 2)!
                let f = |n: i32| (1..=n).map(|k| k as f64).product::<f64>();
                f(i) * f(j) / f(i + j + 2)
            }
            _ => line(i) * line(j),
        }
    }

    fn check(kind: CellKind, rule: &Rule, degree: i32) {
        for i in 0..=degree {
            for j in 0..=(degree - i) {
                if kind.dim() == 1 && j > 0 {
                    continue;
                }
                let q: f64 = rule
                    .points
                    .iter()
                    .zip(&rule.weights)
                    .map(|(p, w)| w * p[0].powi(i) * p[1].powi(j))
                    .sum();
                let e = exact_monomial(kind, i, j);
                assert!((q - e).abs() < 1e-13, "{kind} x^{i} y^{j}: {q} vs {e}");
            }
        }
    }

    #[test]
    fn stiffness_rules_are_exact_to_their_degree() {
        // Quad4 2×2 and Seg2: degree 3 per direction; Quad8 3×3 and Seg3: degree 5;
        // Tri3 one point: degree 1; Tri6 three points: degree 2.
        check(CellKind::Seg2, stiffness_rule(CellKind::Seg2), 3);
        check(CellKind::Seg3, stiffness_rule(CellKind::Seg3), 5);
        check(CellKind::Quad4, stiffness_rule(CellKind::Quad4), 3);
        check(CellKind::Quad8, stiffness_rule(CellKind::Quad8), 5);
        check(CellKind::Tri3, stiffness_rule(CellKind::Tri3), 1);
        check(CellKind::Tri6, stiffness_rule(CellKind::Tri6), 2);
    }

    #[test]
    fn stiffness_rules_are_not_exact_beyond_their_degree() {
        // Guards the check itself: the one-point triangle rule misses x².
        let r = stiffness_rule(CellKind::Tri3);
        let q: f64 = r
            .points
            .iter()
            .zip(&r.weights)
            .map(|(p, w)| w * p[0] * p[0])
            .sum();
        assert!((q - exact_monomial(CellKind::Tri3, 2, 0)).abs() > 1e-3);
    }

    #[test]
    fn general_rules_are_exact() {
        for deg in 1..12 {
            check(
                CellKind::Seg2,
                &exact_to_degree(CellKind::Seg2, deg),
                deg as i32,
            );
            check(
                CellKind::Quad4,
                &exact_to_degree(CellKind::Quad4, deg),
                deg as i32,
            );
            check(
                CellKind::Tri3,
                &exact_to_degree(CellKind::Tri3, deg),
                deg as i32,
            );
        }
    }
}
