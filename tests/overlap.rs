//! The physical contact check (contact/overlap) through whole runs: a body pushed through
//! another, or starting deep inside it, is refused whatever the formulation; a body pressed
//! onto another is not.

mod common;

use common::{block_on_foundation, bodies, case_head, HELD_BELOW_CONTACT_ABOVE};
use tribo::case::{run, schema::CaseFile};
use tribo::mesh::generate::rectangle;
use tribo::mesh::{CellKind, Mesh};

fn outcome(mesh: &Mesh, text: &str) -> Result<(), String> {
    let case: CaseFile = toml::from_str(text).unwrap();
    run(&case, mesh, false)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

/// The block's top moved down by `dy` onto (or through) the foundation 1 deep.
fn pushed_block(formulation: &str, dy: f64) -> Result<(), String> {
    let (mesh, head) = block_on_foundation(2.0, 8);
    let text = format!(
        "{head}{HELD_BELOW_CONTACT_ABOVE}formulation = \"{formulation}\"\n\
         [[displacement]]\ngroup = \"UpperTop\"\ndx = 0.0\ndy = {dy:?}\n"
    );
    outcome(&mesh, &text)
}

#[test]
fn a_block_pushed_through_the_foundation_is_refused_by_every_formulation() {
    for formulation in ["point-to-segment", "node-to-segment", "mortar"] {
        let e = pushed_block(formulation, -1e6).expect_err(formulation);
        // mortar sees the contact and crushes the block instead
        if formulation == "mortar" {
            assert!(e.contains("turned inside out"), "{e}");
        } else {
            for part in [
                "[[contact]] 1: the bodies pass through each other",
                "5 nodes of 'UpperBottom' went inside the body of 'LowerTop' on the way",
                "deepest at 5.000e-1 (more than 8.333e-2, half its shortest cell side)",
            ] {
                assert!(e.contains(part), "{formulation}: {e}");
            }
        }
        // a press of a hundredth of a cell side is contact, not an overlap
        pushed_block(formulation, -1e-3).unwrap_or_else(|e| panic!("{formulation}: {e}"));
    }
}

#[test]
fn bodies_overlapping_at_the_start_are_refused_unless_within_the_tolerance() {
    // the block's cells are 0.2 × 1/6: it may start 1/12 deep, not 0.3
    for (start, refused) in [(-0.3, true), (-0.01, false)] {
        let lower = rectangle([-0.5, -1.0], 2.0, 1.0, 8, 2, CellKind::Quad4, 0.0).unwrap();
        let upper = rectangle([0.0, start], 1.0, 0.5, 5, 3, CellKind::Quad4, 0.0).unwrap();
        let mesh = bodies(&[("Lower", &lower), ("Upper", &upper)]);
        let head = case_head(&[("LowerBody", 1000.0, 0.3), ("UpperBody", 1000.0, 0.3)]);
        let text = format!(
            "{head}{HELD_BELOW_CONTACT_ABOVE}formulation = \"mortar\"\n\
             [[displacement]]\ngroup = \"UpperTop\"\ndx = 0.0\ndy = 0.0\n"
        );
        let got = outcome(&mesh, &text);
        if refused {
            let e = got.expect_err("0.3 deep");
            assert!(
                e.contains("[[contact]] 1: the undeformed bodies overlap"),
                "{e}"
            );
            assert!(e.contains("deepest at 3.000e-1"), "{e}");
        } else {
            got.unwrap();
        }
    }
}
