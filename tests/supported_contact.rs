//! A node both supported and in contact: the two blocks' left edges are clamped, so the
//! slave surface's corner node and the master node under it have no free dof, and the
//! corner's contact constraint has nothing to act on. Every formulation refuses it before
//! any work, naming the node (node 13 is the upper block's bottom-left corner with Quad4
//! cells, 30 with Quad8: the lower block's nodes come first); listed in `exclude`, the node
//! takes no contact and every formulation carries the load.

mod common;

use common::{bodies, case_head};
use tribo::case::{run, schema::CaseFile};
use tribo::mesh::generate::rectangle;
use tribo::mesh::CellKind;

/// The lower block's vertical reaction, all vertical reactions, and the contact pressure
/// reported at the corner.
fn outcome(formulation: &str, kind: CellKind, exclude: bool) -> Result<[f64; 3], String> {
    let lower = rectangle([0.0, -1.0], 2.0, 1.0, 3, 2, kind, 0.0).unwrap();
    let upper = rectangle([0.0, 0.0], 2.0, 1.0, 5, 2, kind, 0.0).unwrap();
    let mut mesh = bodies(&[("Lower", &lower), ("Upper", &upper)]);
    // the upper block's bottom-left corner
    let corner = mesh
        .node_group("UpperBottom")
        .unwrap()
        .into_iter()
        .find(|&n| mesh.coords[n] == [0.0, 0.0])
        .unwrap();
    mesh.node_groups.insert("Corner".into(), vec![corner]);
    let exclude = if exclude {
        r#"exclude = ["Corner"]"#
    } else {
        ""
    };
    let head = case_head(&[("LowerBody", 1000.0, 0.3), ("UpperBody", 1000.0, 0.3)]);
    let text = format!(
        r#"{head}
[[displacement]]
group = "LowerBottom"
dy = 0.0
[[displacement]]
group = "LowerLeft"
dx = 0.0
dy = 0.0
[[displacement]]
group = "UpperLeft"
dx = 0.0
dy = 0.0
[[pressure]]
group = "UpperTop"
p = 25.0
[[contact]]
slave = "UpperBottom"
master = "LowerTop"
formulation = "{formulation}"
{exclude}
"#
    );
    let case: CaseFile = toml::from_str(&text).unwrap();
    let out = run(&case, &mesh, false).map_err(|e| e.to_string())?;
    let ry: f64 = mesh
        .node_group("LowerBottom")
        .unwrap()
        .iter()
        .chain(mesh.node_group("LowerLeft").unwrap().iter())
        .map(|&n| out.reactions[2 * n + 1])
        .sum();
    let all: f64 = out.reactions.iter().skip(1).step_by(2).sum();
    let p_corner = out.contact_pressure[0]
        .iter()
        .find(|q| q.0 == corner)
        .map_or(f64::NAN, |q| q.1);
    Ok([ry, all, p_corner])
}

#[test]
fn a_supported_node_in_contact_is_handled_or_named() {
    for formulation in ["mortar", "point-to-segment", "node-to-segment"] {
        for kind in [CellKind::Quad4, CellKind::Quad8] {
            let r = outcome(formulation, kind, false).map(|o| o[0]);
            println!("{formulation} {kind}: {r:?}");
            // (before: node-to-segment failed on a singular system naming nothing, and
            // quadratic mortar exited 0 with a base reaction of 5e16)
            let e = r.expect_err("a supported slave node is refused");
            let corner = if kind == CellKind::Quad4 { 13 } else { 30 };
            assert!(
                e.contains(&format!(
                    "slave node {corner} has both displacements imposed"
                )),
                "{formulation} {kind}: {e}"
            );
        }
    }
}

#[test]
fn a_supported_node_listed_in_exclude_takes_no_contact() {
    for formulation in ["mortar", "point-to-segment", "node-to-segment"] {
        for kind in [CellKind::Quad4, CellKind::Quad8] {
            let [ry, all, p] = outcome(formulation, kind, true)
                .unwrap_or_else(|e| panic!("{formulation} {kind}: {e}"));
            // the pressure 25 on the top, 2 wide, reaches the supports (most of it the lower
            // block's, through the contact); the corner carries no pressure
            println!(
                "{formulation} {kind}: reactions {all} (lower block {ry}), corner pressure {p}"
            );
            assert!(
                (all - 50.0).abs() <= 1e-9 * 50.0,
                "{formulation} {kind}: {all}"
            );
            assert!(ry > 0.5 * 50.0, "{formulation} {kind}: {ry}");
            assert!(
                p.abs() <= 1e-9 * 25.0,
                "{formulation} {kind}: corner pressure {p}"
            );
        }
    }
}
