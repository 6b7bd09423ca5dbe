//! Newton converges quadratically on a geometrically nonlinear problem: a slender cantilever
//! (large kinematics) bent by a tip load in one step.

use tribo::case::{build_mesh, build_problem, schema::CaseFile};
use tribo::solver::linear::Method;
use tribo::solver::newton::{solve, NewtonSettings};

#[test]
fn newton_converges_quadratically_with_large_kinematics() {
    let text = r#"
[mesh]
generator = "rectangle"
width = 10.0
height = 1.0
nx = 20
ny = 2
cell = "Quad8"
[model]
kinematics = "large"
[[material]]
group = "Body"
E = 1000.0
nu = 0.3
[[displacement]]
group = "Left"
dx = 0.0
dy = 0.0
[[force]]
group = "TopRight"
fy = -0.5
"#;
    let case: CaseFile = toml::from_str(text).unwrap();
    let mesh = build_mesh(&case.mesh, std::path::Path::new("")).unwrap();
    let mut p = build_problem(&case, &mesh).unwrap();
    let settings = NewtonSettings {
        steps: 1,
        tolerance: 1e-11,
        max_iterations: 30,
        ..Default::default()
    };
    let report = solve(&mut p, &settings, Method::Cholesky).unwrap();
    let tip = mesh.single_node("TopRight").unwrap();
    let deflection = -p.u[2 * tip + 1];
    // Geometrically nonlinear regime: deflection of the order of 10 % of the length.
    assert!(
        deflection > 0.5 && deflection < 5.0,
        "deflection {deflection}"
    );
    let r: Vec<f64> = report.steps[0]
        .iterations
        .iter()
        .map(|i| i.relative_residual)
        .collect();
    println!("residual history {r:?}");
    assert!(report.steps[0].converged);
    // Asymptotic rate: the last pair of iterations with the second residual still well
    // above round-off (1e-10) must show log r_{k+1} / log r_k >= 1.8 (2 is quadratic).
    let pair = (0..r.len() - 1)
        .rev()
        .find(|&k| r[k] < 1e-2 && r[k + 1] > 1e-10)
        .expect("an iteration in the asymptotic range");
    let order = r[pair + 1].ln() / r[pair].ln();
    println!(
        "last asymptotic pair {} -> {}: order {order:.2}",
        r[pair],
        r[pair + 1]
    );
    assert!(order >= 1.8, "order {order}: {r:?}");
}
