use super::*;
use crate::mesh::generate::rectangle;
use crate::mesh::{CellKind, MeshBuilder};

/// A 1 × 0.5 block (2 × 1 cells of side 0.5, groups `Upper…`) standing at `lift` above the
/// top of a 2 × 1 foundation (4 × 2 cells, groups `Lower…`); the upper block's nodes come
/// last.
fn two_blocks(lift: f64, kind: CellKind) -> (Mesh, usize) {
    let lower = rectangle([0.0, -1.0], 2.0, 1.0, 4, 2, kind, 0.0).unwrap();
    let upper = rectangle([0.5, lift], 1.0, 0.5, 2, 1, kind, 0.0).unwrap();
    let mut b = MeshBuilder::new("two blocks");
    b.append(&lower, |g| format!("Lower{g}"));
    b.append(&upper, |g| format!("Upper{g}"));
    (b.finish().unwrap(), lower.num_nodes())
}

fn check(mesh: &Mesh, allowance: f64) -> OverlapCheck {
    let slave = Surface::from_group(mesh, "UpperBottom", "slave").unwrap();
    let master = Surface::from_group(mesh, "LowerTop", "master").unwrap();
    OverlapCheck::from_surfaces(mesh, &[(&slave, &master, allowance)])
}

/// The upper block moved by `d` (and the lower one by `lower`).
fn moved(mesh: &Mesh, first_upper: usize, d: [f64; 2], lower: [f64; 2]) -> Vec<f64> {
    let mut u = vec![0.0; 2 * mesh.num_nodes()];
    for n in 0..mesh.num_nodes() {
        let m = if n >= first_upper { d } else { lower };
        u[2 * n] = m[0];
        u[2 * n + 1] = m[1];
    }
    u
}

#[test]
fn touching_bodies_and_a_penetration_within_the_tolerance_pass() {
    for kind in [CellKind::Quad4, CellKind::Quad8, CellKind::Tri3] {
        let (mesh, first) = two_blocks(0.0, kind);
        let c = check(&mesh, 0.0);
        let zero = vec![0.0; 2 * mesh.num_nodes()];
        assert_eq!(c.at_start(&mesh), None, "{kind}: nodes on the surface");
        // a penalty-like sink of 0.1, a fifth of the cell side
        let u = moved(&mesh, first, [0.0, -0.1], [0.0, 0.0]);
        assert_eq!(c.during_step(&mesh, &zero, &u), None, "{kind}");
        // sliding along the surface, however far
        let u = moved(&mesh, first, [0.3, 0.0], [0.0, 0.0]);
        assert_eq!(c.during_step(&mesh, &zero, &u), None, "{kind}");
    }
}

#[test]
fn a_node_deep_in_a_cell_of_the_other_body_is_flagged_with_its_depth() {
    let (mesh, first) = two_blocks(0.0, CellKind::Quad4);
    let c = check(&mesh, 0.0);
    let zero = vec![0.0; 2 * mesh.num_nodes()];
    let u = moved(&mesh, first, [0.0, -0.4], [0.0, 0.0]);
    let e = c
        .during_step(&mesh, &zero, &u)
        .expect("0.4 deep, tolerance 0.25");
    assert!(
        e.contains("[[contact]] 1: the bodies pass through each other"),
        "{e}"
    );
    // the three bottom nodes of the upper block, each 0.4 deep
    assert!(
        e.contains("3 nodes of 'UpperBottom' went inside the body of 'LowerTop'"),
        "{e}"
    );
    assert!(e.contains("deepest at 4.000e-1 (more than 2.500e-1"), "{e}");
    assert!(!e.contains("on the way"), "{e}");
    // the foundation's top nodes under the block are inside it too (the other side)
    let u = moved(&mesh, first, [0.0, -0.3], [0.0, 0.0]);
    assert!(c.during_step(&mesh, &zero, &u).is_some());
}

#[test]
fn a_body_pushed_through_the_other_in_one_step_is_flagged_on_the_way() {
    let (mesh, first) = two_blocks(0.0, CellKind::Quad4);
    let c = check(&mesh, 0.0);
    let zero = vec![0.0; 2 * mesh.num_nodes()];
    // from on top of the foundation to 1e6 below it: no overlap at either end
    let u = moved(&mesh, first, [0.0, -1e6], [0.0, 0.0]);
    let e = c.during_step(&mesh, &zero, &u).expect("passed through");
    assert!(e.contains("on the way"), "{e}");
    // the foundation is 1 deep: half of it is the deepest a node gets
    assert!(e.contains("deepest at 5.000e-1"), "{e}");
}

#[test]
fn bodies_moving_together_however_far_pass() {
    let (mesh, first) = two_blocks(0.0, CellKind::Quad4);
    let c = check(&mesh, 0.0);
    let zero = vec![0.0; 2 * mesh.num_nodes()];
    for d in [[0.0, 1e6], [0.0, -1e6], [1e6, 3.0]] {
        let u = moved(&mesh, first, d, d);
        assert_eq!(c.during_step(&mesh, &zero, &u), None, "{d:?}");
    }
}

#[test]
fn an_initial_overlap_is_flagged_beyond_the_tolerance_and_the_allowance() {
    let (mesh, _) = two_blocks(-0.4, CellKind::Quad4);
    let e = check(&mesh, 0.0)
        .at_start(&mesh)
        .expect("0.4 deep at the start");
    assert!(e.contains("the undeformed bodies overlap"), "{e}");
    assert!(e.contains("deepest at 4.000e-1"), "{e}");
    // an allowance (mortar's adjust) of 0.2 covers it: 0.4 < 0.25 + 0.2
    assert_eq!(check(&mesh, 0.2).at_start(&mesh), None);
    let (mesh, _) = two_blocks(-0.2, CellKind::Quad4);
    assert_eq!(check(&mesh, 0.0).at_start(&mesh), None, "0.2 < 0.25");
}
