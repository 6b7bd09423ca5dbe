//! SSNP154 A (linear cells, frictionless, large kinematics) on the built-in mesh, solved
//! and checked: the Newton runs of the large-model tests read its report.

use tribo::case::{self, ssnp154, Outcome};
use tribo::mesh::generate::{ssnp154 as generate, Ssnp154Options};

/// SSNP154 A with `formulation` on the built-in linear mesh of contact cell `size` (mm):
/// every load step converged, and DY_B and SIYY_B within the validation's tolerance (1 %)
/// of the quadratic mesh's reference values (SSNP154 B, the finer answer; at these sizes
/// the mesh's error is below it).
pub fn solved(size: f64, formulation: &str) -> Outcome {
    let mesh = generate(&Ssnp154Options {
        quadratic: false,
        size,
        global_refine: 0,
    })
    .unwrap();
    let spec = ssnp154::builtin_mesh(false, size);
    let c = ssnp154::contact_case("A", spec, Some(formulation));
    let out = case::run_keeping(&c, &mesh, false).unwrap_or_else(|f| panic!("{}", f.error));
    assert!(out.report.steps.iter().all(|s| s.converged));
    let p = |n: &str| out.probes.iter().find(|q| q.0 == n).unwrap().1;
    let (dy, siyy) = (p("DY_B"), p("SIYY_B"));
    assert!((dy / -1.3080192481252 - 1.0).abs() < 0.01, "DY_B {dy}");
    assert!(
        (siyy / -3513.3741602327 - 1.0).abs() < 0.01,
        "SIYY_B {siyy}"
    );
    out
}
