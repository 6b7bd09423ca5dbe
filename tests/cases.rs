//! The shipped case files run and meet the SSNP154 references within the built-in-mesh
//! tolerance (1 %: the built-in meshes are not the reference ones).

use std::path::Path;
use tribo::case;

fn run(file: &str, dy_ref: f64, siyy_ref: f64) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("cases/ssnp154")
        .join(file);
    let (c, dir) = case::load(&path).unwrap();
    let mesh = case::build_mesh(&c.mesh, &dir).unwrap();
    let out = case::run(&c, &mesh, false).unwrap();
    let get = |n: &str| out.probes.iter().find(|p| p.0 == n).unwrap().1;
    let (dy, siyy) = (get("DY_B"), get("SIYY_B"));
    println!(
        "{file}: DY_B {dy} ({:+.3} %), SIYY_B {siyy} ({:+.3} %)",
        100.0 * (dy / dy_ref - 1.0),
        100.0 * (siyy / siyy_ref - 1.0)
    );
    assert!((dy / dy_ref - 1.0).abs() < 0.01, "{file}: DY_B {dy}");
    assert!(
        (siyy / siyy_ref - 1.0).abs() < 0.01,
        "{file}: SIYY_B {siyy}"
    );
    // Newton with contact converges quadratically once the statuses are settled: in the
    // last step, the last pair of iterations above round-off shows order ≥ 1.8.
    let last = out.report.steps.last().unwrap();
    let r: Vec<f64> = last
        .iterations
        .iter()
        .map(|i| i.relative_residual)
        .collect();
    let k = (0..r.len() - 1)
        .rev()
        .find(|&k| r[k] < 1e-2 && r[k + 1] > 1e-11 && last.iterations[k].status_changes == 0)
        .expect("an asymptotic pair");
    let order = r[k + 1].ln() / r[k].ln();
    println!("{file}: last step residuals {r:?}, order {order:.2}");
    assert!(order >= 1.8, "{file}: order {order}");
    // the contact carries the whole load: Σ of the block's support reactions = 17 500 N
    let ry: f64 = mesh
        .node_group("Encast")
        .unwrap()
        .iter()
        .map(|&n| out.reactions[2 * n + 1])
        .sum();
    assert!(
        (ry - 17500.0).abs() < 1e-6 * 17500.0,
        "{file}: reaction {ry}"
    );
}

#[test]
fn ssnp154_a_case_file() {
    run("a.toml", -1.3069040401077, -3800.4949548283);
}

#[test]
fn ssnp154_b_case_file() {
    run("b.toml", -1.3080192481252, -3513.3741602327);
}
