//! Right-preconditioned restarted GMRES, used to solve a non-symmetric tangent exactly with
//! the LDLᵀ factorisation of its symmetric part as preconditioner: the contact tangents
//! (friction, mortar geometry) differ from their symmetric part only near the contact, so a
//! few iterations reach round-off, several times cheaper than a sparse LU.

/// A relative residual accepted when GMRES cannot do better (round-off): far below what
/// Newton needs (its tolerance is ~1e-6 on forces).
const ATTAINABLE: f64 = 1e-10;

/// Solves A x = b to ‖b − A x‖∞ ≤ `tol` ‖b‖∞ (the true residual, checked at each restart),
/// starting from `x`. `apply_a(v, out)` sets out = A v; `precond(v)` replaces v by M⁻¹ v.
/// Returns the number of iterations, or the relative residual reached if it did not converge
/// within `max_iterations`.
pub fn solve(
    apply_a: &mut dyn FnMut(&[f64], &mut [f64]),
    precond: &mut dyn FnMut(&mut [f64]),
    b: &[f64],
    x: &mut [f64],
    tol: f64,
    restart: usize,
    max_iterations: usize,
) -> Result<usize, f64> {
    let n = b.len();
    let norm_inf = |v: &[f64]| v.iter().fold(0.0f64, |m, a| m.max(a.abs()));
    let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
    let scale = norm_inf(b).max(f64::MIN_POSITIVE);
    let mut r = vec![0.0; n];
    let mut w = vec![0.0; n];
    let mut z = vec![0.0; n];
    let mut iterations = 0;
    let mut previous = f64::INFINITY;
    loop {
        apply_a(x, &mut r);
        for (ri, bi) in r.iter_mut().zip(b) {
            *ri = bi - *ri;
        }
        let res = norm_inf(&r) / scale;
        if res <= tol {
            return Ok(iterations);
        }
        // A cycle that did not halve the residual: round-off reached (accepted when near
        // the tolerance: the estimate met the test but the true residual cannot follow, as
        // in ill-conditioned saddle-point systems) or a preconditioner too far from the
        // matrix (give up now rather than after every iteration allowed).
        let stagnated = res > 0.5 * previous;
        if (stagnated || iterations >= max_iterations) && res <= ATTAINABLE.max(tol) {
            return Ok(iterations);
        }
        if stagnated || iterations >= max_iterations {
            return Err(res);
        }
        previous = res;
        // Arnoldi on A M⁻¹ from r, with Givens rotations on the Hessenberg matrix.
        let beta = dot(&r, &r).sqrt();
        let mut basis: Vec<Vec<f64>> = vec![r.iter().map(|v| v / beta).collect()];
        let mut h: Vec<Vec<f64>> = vec![]; // column j: h[j][0..=j+1]
        let mut cs: Vec<(f64, f64)> = vec![];
        let mut g = vec![beta];
        // Stop the cycle when the 2-norm estimate (≥ the ∞-norm) meets the test.
        let target = tol * scale;
        for j in 0..restart.min(max_iterations - iterations) {
            z.copy_from_slice(&basis[j]);
            precond(&mut z);
            apply_a(&z, &mut w);
            // modified Gram–Schmidt, twice (the basis stays orthogonal to round-off)
            let mut col = vec![0.0; j + 2];
            for _ in 0..2 {
                for (i, v) in basis.iter().enumerate() {
                    let hij = dot(&w, v);
                    col[i] += hij;
                    for (wk, vk) in w.iter_mut().zip(v) {
                        *wk -= hij * vk;
                    }
                }
            }
            let hn = dot(&w, &w).sqrt();
            col[j + 1] = hn;
            for (i, &(c, s)) in cs.iter().enumerate() {
                let (a, b) = (col[i], col[i + 1]);
                col[i] = c * a + s * b;
                col[i + 1] = -s * a + c * b;
            }
            let d = col[j].hypot(col[j + 1]);
            let (c, s) = if d == 0.0 {
                (1.0, 0.0)
            } else {
                (col[j] / d, col[j + 1] / d)
            };
            col[j] = d;
            col[j + 1] = 0.0;
            cs.push((c, s));
            g.push(-s * g[j]);
            g[j] *= c;
            h.push(col);
            iterations += 1;
            let done = g[j + 1].abs() <= target || hn == 0.0;
            if !done {
                basis.push(w.iter().map(|v| v / hn).collect());
            }
            if done || basis.len() > restart {
                break;
            }
        }
        // y = H⁻¹ g (upper triangular), x += M⁻¹ (V y)
        let k = h.len();
        let mut y = vec![0.0; k];
        for i in (0..k).rev() {
            let mut s = g[i];
            for (jj, yj) in y.iter().enumerate().take(k).skip(i + 1) {
                s -= h[jj][i] * yj;
            }
            y[i] = s / h[i][i];
        }
        z.fill(0.0);
        for (v, &yj) in basis.iter().zip(&y) {
            for (zk, vk) in z.iter_mut().zip(v) {
                *zk += yj * vk;
            }
        }
        precond(&mut z);
        for (xi, zi) in x.iter_mut().zip(&z) {
            *xi += zi;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-symmetric tridiagonal system, preconditioned by the inverse of its diagonal or
    /// by nothing: GMRES reaches the exact solution in both cases.
    #[test]
    fn nonsymmetric_system_is_solved_to_round_off() {
        let n = 60;
        let apply = |v: &[f64], out: &mut [f64]| {
            for i in 0..n {
                let mut s = 4.0 * v[i];
                if i > 0 {
                    s -= 1.5 * v[i - 1];
                }
                if i + 1 < n {
                    s -= 0.5 * v[i + 1];
                }
                out[i] = s;
            }
        };
        let x_exact: Vec<f64> = (0..n).map(|i| (0.2 * i as f64).sin() + 1.0).collect();
        let mut b = vec![0.0; n];
        apply(&x_exact, &mut b);
        for diag in [true, false] {
            let mut x = vec![0.0; n];
            let mut a = apply;
            let mut m = |v: &mut [f64]| {
                if diag {
                    v.iter_mut().for_each(|e| *e /= 4.0);
                }
            };
            let its = solve(&mut a, &mut m, &b, &mut x, 1e-13, 10, 200).unwrap();
            let err = x
                .iter()
                .zip(&x_exact)
                .fold(0.0f64, |e, (u, v)| e.max((u - v).abs()));
            assert!(
                err < 1e-11,
                "diag {diag}: error {err} after {its} iterations"
            );
            assert!(its > 1, "a non-trivial system needs several iterations");
        }
    }

    #[test]
    fn exact_preconditioner_converges_at_once_and_failure_is_reported() {
        let apply = |v: &[f64], out: &mut [f64]| {
            out[0] = 2.0 * v[0] + v[1];
            out[1] = -v[0] + 3.0 * v[1];
        };
        // exact inverse of [[2, 1], [-1, 3]] (det 7)
        let mut inv = |v: &mut [f64]| {
            let (a, b) = (v[0], v[1]);
            v[0] = (3.0 * a - b) / 7.0;
            v[1] = (a + 2.0 * b) / 7.0;
        };
        let b = [1.0, 2.0];
        let mut x = [0.0, 0.0];
        let mut a = apply;
        let its = solve(&mut a, &mut inv, &b, &mut x, 1e-14, 5, 5).unwrap();
        assert!(its <= 1, "{its}");
        assert!((x[0] - 1.0 / 7.0).abs() < 1e-15 && (x[1] - 5.0 / 7.0).abs() < 1e-15);
        // no iterations allowed: the residual of the start is reported
        let mut x = [0.0, 0.0];
        let mut none = |_: &mut [f64]| {};
        let err = solve(&mut a, &mut none, &b, &mut x, 1e-14, 5, 0).unwrap_err();
        assert_eq!(err, 1.0);
    }
}
