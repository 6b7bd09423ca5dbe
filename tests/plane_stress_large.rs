//! Plane stress with large kinematics (St Venant–Kirchhoff, thickness change included): a
//! plate stretched uniformly by 20 % against the exact uniaxial-stress SVK answer, computed
//! here from the 3D law (S22 = S33 = 0), and Newton's quadratic convergence.

use tribo::case::{build_mesh, build_problem, schema::CaseFile};
use tribo::fem::solid::{gauss_stresses_as, StressMeasure};
use tribo::solver::linear::Method;
use tribo::solver::newton::{solve, NewtonSettings};

const E: f64 = 1000.0;
const NU: f64 = 0.3;
const STRETCH: f64 = 0.2;
const W: f64 = 2.0;
const H: f64 = 1.0;
const T: f64 = 0.5;

fn plate(cell: &str) -> String {
    format!(
        r#"
[mesh]
generator = "rectangle"
width = {W}
height = {H}
nx = 4
ny = 3
cell = "{cell}"
[model]
modelisation = "plane_stress"
kinematics = "large"
thickness = {T}
[[material]]
group = "Body"
E = {E}
nu = {NU}
[[displacement]]
group = "Left"
dx = 0.0
[[displacement]]
group = "BottomLeft"
dy = 0.0
[[displacement]]
group = "Right"
dx = {}
"#,
        STRETCH * W
    )
}

/// The exact uniaxial-stress state of 3D St Venant–Kirchhoff at stretch F11: by symmetry
/// E22 = E33, and S22 = λ(E11 + 2E22) + 2μE22 = 0 gives E22 = −λ/(2(λ+μ)) E11; then
/// S11 = (λ+2μ)E11 + 2λE22. Returns (S11, F22, F33).
fn exact(f11: f64) -> (f64, f64, f64) {
    let l = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    let m = E / (2.0 * (1.0 + NU));
    let e11 = 0.5 * (f11 * f11 - 1.0);
    let e22 = -l / (2.0 * (l + m)) * e11;
    let s11 = (l + 2.0 * m) * e11 + 2.0 * l * e22;
    let f22 = (1.0 + 2.0 * e22).sqrt();
    (s11, f22, f22)
}

#[test]
fn stretched_plate_matches_exact_st_venant_kirchhoff() {
    for cell in ["Quad4", "Tri3", "Quad8", "Tri6"] {
        let case: CaseFile = toml::from_str(&plate(cell)).unwrap();
        let mesh = build_mesh(&case.mesh, std::path::Path::new("")).unwrap();
        let mut p = build_problem(&case, &mesh).unwrap();
        let settings = NewtonSettings {
            steps: 1,
            tolerance: 1e-12,
            max_iterations: 30,
            chord_steps: false,
            ..Default::default()
        };
        let report = solve(&mut p, &settings, Method::Cholesky).unwrap();
        assert!(report.steps[0].converged, "{cell}");
        let f11 = 1.0 + STRETCH;
        let (s11, f22, f33) = exact(f11);
        // displacement field: u = (F11 − 1) X, (F22 − 1) Y
        let mut err_u: f64 = 0.0;
        for (n, x) in mesh.coords.iter().enumerate() {
            err_u = err_u
                .max((p.u[2 * n] - (f11 - 1.0) * x[0]).abs())
                .max((p.u[2 * n + 1] - (f22 - 1.0) * x[1]).abs());
        }
        // stresses: PK2 (S11, 0, 0, 0) and Cauchy σ11 = F11² S11 / J, J = F11 F22 F33
        let sigma11 = f11 * f11 * s11 / (f11 * f22 * f33);
        let mut err_s: f64 = 0.0;
        let mut err_c: f64 = 0.0;
        for (k, &c) in p.asm.cells.iter().enumerate() {
            let sm = &p.asm.cell_model[k];
            let kind = mesh.kind(c);
            let nodes = mesh.cell_nodes(c);
            let x: Vec<[f64; 2]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
            let u: Vec<[f64; 2]> = nodes
                .iter()
                .map(|&n| [p.u[2 * n], p.u[2 * n + 1]])
                .collect();
            let mut out = [[0.0; 4]; 16];
            gauss_stresses_as(kind, &x, &u, sm, StressMeasure::Pk2, &mut out).unwrap();
            let rule = tribo::fem::quadrature::stiffness_rule(kind);
            for s in &out[..rule.points.len()] {
                let e = [s[0] - s11, s[1], s[2], s[3]];
                err_s = e.iter().fold(err_s, |a, v| a.max(v.abs()));
            }
            gauss_stresses_as(kind, &x, &u, sm, StressMeasure::Cauchy, &mut out).unwrap();
            for s in &out[..rule.points.len()] {
                let e = [s[0] - sigma11, s[1], s[2], s[3]];
                err_c = e.iter().fold(err_c, |a, v| a.max(v.abs()));
            }
        }
        // reaction on the pulled edge: nominal stress P11 = F11 S11 times the reference
        // section H·T (the reference thickness: total Lagrangian)
        let r = p.reactions();
        let fx: f64 = mesh
            .node_group("Right")
            .unwrap()
            .iter()
            .map(|&n| r[2 * n])
            .sum();
        let force = f11 * s11 * H * T;
        println!(
            "{cell}: S11 {s11}, sigma11 {sigma11}, F22 {f22}; errors u {err_u:e}, S {err_s:e}, \
             sigma {err_c:e}, reaction {fx} vs {force}"
        );
        assert!(err_u < 1e-8 * W, "{cell}: displacement error {err_u}");
        assert!(err_s < 1e-8 * s11, "{cell}: PK2 error {err_s}");
        assert!(err_c < 1e-8 * sigma11, "{cell}: Cauchy error {err_c}");
        assert!(
            (fx.abs() - force).abs() < 1e-8 * force,
            "{cell}: reaction {fx} vs {force}"
        );
        // quadratic convergence: the last pair still above round-off
        let r: Vec<f64> = report.steps[0]
            .iterations
            .iter()
            .map(|i| i.relative_residual)
            .collect();
        println!("{cell}: residual history {r:?}");
        let pair = (0..r.len() - 1)
            .rev()
            .find(|&k| r[k] < 1e-2 && r[k + 1] > 1e-13 && !report.steps[0].iterations[k].chord)
            .expect("an iteration in the asymptotic range");
        let order = r[pair + 1].ln() / r[pair].ln();
        assert!(order >= 1.8, "{cell}: order {order}: {r:?}");
    }
}
