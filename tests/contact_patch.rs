//! Contact patch test: two blocks with non-matching interface meshes pressed together by a
//! uniform pressure. The exact contact pressure is uniform; the mortar formulation must
//! reproduce it to 1e-8, for linear and quadratic cells.

use tribo::case::{build_mesh, run, schema::CaseFile};
use tribo::mesh::generate::rectangle;
use tribo::mesh::{CellKind, MeshBuilder};

const P: f64 = 25.0;

fn case_text(formulation: &str) -> String {
    format!(
        r#"
[mesh]
generator = "rectangle"
width = 1.0
height = 1.0
nx = 1
ny = 1
[[material]]
group = "LowerBody"
E = 1000.0
nu = 0.3
[[material]]
group = "UpperBody"
E = 1000.0
nu = 0.3
[[displacement]]
group = "LowerBottom"
dy = 0.0
[[displacement]]
group = "LowerLeft"
dx = 0.0
[[displacement]]
group = "UpperLeft"
dx = 0.0
[[pressure]]
group = "UpperTop"
p = {P}
[[contact]]
slave = "UpperBottom"
master = "LowerTop"
formulation = "{formulation}"
initial = "all"
"#
    )
}

/// Largest relative deviation of the nodal contact pressures from P.
fn patch(kind: CellKind, formulation: &str) -> f64 {
    let lower = rectangle([0.0, -1.0], 2.0, 1.0, 3, 2, kind, 0.0).unwrap();
    let upper = rectangle([0.0, 0.0], 2.0, 1.0, 5, 2, kind, 0.0).unwrap();
    let mut b = MeshBuilder::new("two blocks");
    b.append(&lower, |g| format!("Lower{g}"));
    b.append(&upper, |g| format!("Upper{g}"));
    let mesh = b.finish().unwrap();
    let case: CaseFile = toml::from_str(&case_text(formulation)).unwrap();
    let _ = build_mesh; // the mesh is assembled here from two generated blocks
    let out = run(&case, &mesh, false).unwrap();
    let worst = out.contact_pressure[0]
        .iter()
        .map(|&(_, p)| ((p - P) / P).abs())
        .fold(0.0, f64::max);
    println!(
        "{kind} {formulation}: max |p - P| / P = {worst:.2e} {:?}",
        out.contact_pressure[0]
    );
    worst
}

#[test]
fn mortar_passes_the_contact_patch_test() {
    for kind in [CellKind::Quad4, CellKind::Quad8] {
        assert!(patch(kind, "mortar") < 1e-8, "{kind}");
    }
}

#[test]
fn point_to_segment_patch_test_is_reported() {
    // The reference's point-to-segment method is not expected to pass: printed only.
    for kind in [CellKind::Quad4, CellKind::Quad8] {
        let e = patch(kind, "point-to-segment");
        assert!(e.is_finite());
    }
}
