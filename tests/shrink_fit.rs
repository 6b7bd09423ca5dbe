//! Interference (shrink) fit of two concentric rings, plane strain, small strain: the inner
//! ring's outer radius exceeds the outer ring's inner radius by δ, resolved by contact in
//! one step. Contact pressure and radial displacements against the Lamé solution (0.5 %,
//! quadratic cells, non-matching interface, mortar).

mod common;

use common::{bodies, case_head};
use tribo::case::{run, schema::CaseFile};
use tribo::mesh::generate::ring;
use tribo::mesh::CellKind;

const E: f64 = 200_000.0;
const NU: f64 = 0.3;
const A: f64 = 10.0; // inner radius of the inner ring
const B: f64 = 15.0; // inner radius of the outer ring (the fit radius)
const C: f64 = 25.0; // outer radius of the outer ring
const DELTA: f64 = 0.01; // radial interference

/// Lamé in plane strain: a ring r1..r2 with σ_rr(r1) = s1, σ_rr(r2) = s2 has
/// u(r) = α r + β / r; returns (α, β).
fn lame(r1: f64, r2: f64, s1: f64, s2: f64) -> (f64, f64) {
    let mu = E / (2.0 * (1.0 + NU));
    let lambda = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    // σ_rr = 2(λ+μ) α − 2μ β / r²
    let beta = (s2 - s1) / (2.0 * mu * (1.0 / (r1 * r1) - 1.0 / (r2 * r2)));
    let alpha = (s1 + 2.0 * mu * beta / (r1 * r1)) / (2.0 * (lambda + mu));
    (alpha, beta)
}

#[test]
fn shrink_fit_matches_lame() {
    // fit pressure p from u_outer(b) − u_inner(b) = δ (linear in p)
    let u = |r1: f64, r2: f64, s1: f64, s2: f64, r: f64| {
        let (al, be) = lame(r1, r2, s1, s2);
        al * r + be / r
    };
    let per_unit = u(B, C, -1.0, 0.0, B) - u(A, B, 0.0, -1.0, B);
    let p = DELTA / per_unit;
    let inner = ring(A, B + DELTA, 6, 24, 90.0, CellKind::Quad8).unwrap();
    let outer = ring(B, C, 8, 31, 90.0, CellKind::Quad8).unwrap();
    let mesh = bodies(&[("In", &inner), ("Out", &outer)]);
    let head = case_head(&[("InBody", E, NU), ("OutBody", E, NU)]);
    let text = format!(
        r#"{head}
[model]
modelisation = "plane_strain"
kinematics = "small"
[[displacement]]
group = "InStart"
dy = 0.0
[[displacement]]
group = "OutStart"
dy = 0.0
[[displacement]]
group = "InEnd"
dx = 0.0
[[displacement]]
group = "OutEnd"
dx = 0.0
[[contact]]
slave = "InOuter"
master = "OutInner"
formulation = "mortar"
initial = "all"
"#
    );
    let case: CaseFile = toml::from_str(&text).unwrap();
    let out = run(&case, &mesh, false).unwrap();
    let mut worst_p: f64 = 0.0;
    for &(_, pc) in &out.contact_pressure[0] {
        worst_p = worst_p.max((pc / p - 1.0).abs());
    }
    let radial = |n: usize| {
        let x = mesh.coords[n];
        let r = x[0].hypot(x[1]);
        (r, (out.u[2 * n] * x[0] + out.u[2 * n + 1] * x[1]) / r)
    };
    let mut worst_u: f64 = 0.0;
    for (group, r1, r2, s1, s2) in [("InInner", A, B, 0.0, -p), ("OutOuter", B, C, -p, 0.0)] {
        for n in mesh.node_group(group).unwrap() {
            let (r, ur) = radial(n);
            let exact = u(r1, r2, s1, s2, r);
            worst_u = worst_u.max((ur / exact - 1.0).abs());
        }
    }
    println!(
        "Lamé fit pressure {p:.4} MPa: contact pressure within {:.3} %, radial displacements \
         at r = a and r = c within {:.3} %",
        100.0 * worst_p,
        100.0 * worst_u
    );
    assert!(
        worst_p < 5e-3,
        "contact pressure off by {:.3} %",
        100.0 * worst_p
    );
    assert!(
        worst_u < 5e-3,
        "radial displacement off by {:.3} %",
        100.0 * worst_u
    );
}
