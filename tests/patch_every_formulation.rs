//! Non-matching two-block contact patch tests for every formulation: both slave choices,
//! every cell kind, several ratios of interface cells (3:5, 4:7, 7:4, 5:3). Each must
//! converge, the base reaction must carry the applied pressure (to 1e-6), and mortar must
//! reproduce the uniform pressure at every slave node (1e-8). (The issue saw
//! point-to-segment stall on such meshes: "no convergence in 50 iterations".)

mod common;

use common::{bodies, case_head};
use tribo::case::{run, schema::CaseFile};
use tribo::mesh::generate::rectangle;
use tribo::mesh::CellKind;

const P: f64 = 25.0;

fn check(kind: CellKind, formulation: &str, n_lower: usize, n_upper: usize, upper_slave: bool) {
    let lower = rectangle([0.0, -1.0], 2.0, 1.0, n_lower, 2, kind, 0.0).unwrap();
    let upper = rectangle([0.0, 0.0], 2.0, 1.0, n_upper, 2, kind, 0.0).unwrap();
    let mesh = bodies(&[("Lower", &lower), ("Upper", &upper)]);
    let head = case_head(&[("LowerBody", 1000.0, 0.3), ("UpperBody", 3000.0, 0.25)]);
    let (slave, master) = if upper_slave {
        ("UpperBottom", "LowerTop")
    } else {
        ("LowerTop", "UpperBottom")
    };
    let text = format!(
        r#"{head}
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
slave = "{slave}"
master = "{master}"
formulation = "{formulation}"
"#
    );
    let case: CaseFile = toml::from_str(&text).unwrap();
    let what = format!("{kind} {formulation} {n_lower}:{n_upper} slave {slave}");
    let out = run(&case, &mesh, false).unwrap_or_else(|e| panic!("{what}: {e}"));
    let ry: f64 = mesh
        .node_group("LowerBottom")
        .unwrap()
        .iter()
        .map(|&n| out.reactions[2 * n + 1])
        .sum();
    let balance = ry / (2.0 * P);
    let worst = out.contact_pressure[0]
        .iter()
        .map(|&(_, p)| ((p - P) / P).abs())
        .fold(0.0, f64::max);
    println!(
        "{what}: {} iterations, reaction / load {balance:.9}, max |p - P| / P {worst:.1e}",
        out.report.total_iterations
    );
    assert!(
        (balance - 1.0).abs() < 1e-6,
        "{what}: reaction / load {balance}"
    );
    if formulation == "mortar" {
        assert!(worst < 1e-8, "{what}: max |p - P| / P = {worst}");
    }
}

#[test]
fn every_formulation_converges_on_non_matching_patch_tests() {
    for formulation in ["mortar", "point-to-segment", "node-to-segment"] {
        for kind in [
            CellKind::Tri3,
            CellKind::Tri6,
            CellKind::Quad4,
            CellKind::Quad8,
        ] {
            for (nl, nu) in [(3, 5), (4, 7), (7, 4), (5, 3)] {
                for upper_slave in [true, false] {
                    check(kind, formulation, nl, nu, upper_slave);
                }
            }
        }
    }
}
