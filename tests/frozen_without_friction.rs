//! Frozen-body corrections without friction where a factorisation of the bodies is costly
//! (`newton/frozen.rs`, FROZEN_WITHOUT_FRICTION_SOLVES): later Newton points keep the bodies'
//! factorisations (contact terms current) once the residual is below 0.1, as with
//! friction; on small models every correction after a step's first stays a full Newton
//! one (they converge quadratically, and a factorisation costs little there).

mod common;

use common::ssnp154_a::solved;
use tribo::case::Outcome;

/// SSNP154 A with point-to-segment on the built-in linear mesh of contact cell `size`
/// (mm), checked (`solved`).
fn a_point_to_segment(size: f64) -> Outcome {
    solved(size, "point-to-segment")
}

/// The frozen-body corrections at Newton points after a step's first (re-solves and the
/// linear stage left out), with their iteration numbers.
fn later_frozen_points(out: &Outcome) -> Vec<(f64, usize)> {
    let mut found = vec![];
    for step in &out.report.steps {
        let points = step
            .iterations
            .iter()
            .filter(|i| !i.active_set_resolve && !i.linear_kinematics);
        for it in points.skip(1).filter(|i| i.frozen_bodies) {
            found.push((step.time, it.iteration));
        }
    }
    found
}

/// 98k unknowns (a factorisation of the bodies costs about 150 solves): the second load
/// step's points below 0.1 keep the bodies' factorisations.
#[test]
fn a_large_frictionless_model_keeps_the_bodies_factorisations_at_later_points() {
    let out = a_point_to_segment(1.5 * 0.5f64.powi(5));
    let frozen = later_frozen_points(&out);
    assert!(
        !frozen.is_empty(),
        "no frozen correction after a step's first point"
    );
}

/// 27k unknowns (about 80 solves): every later point factorises the bodies.
#[test]
fn a_smaller_frictionless_model_takes_full_corrections_at_later_points() {
    let out = a_point_to_segment(1.5 * 0.5f64.powf(3.5));
    let frozen = later_frozen_points(&out);
    assert!(frozen.is_empty(), "frozen corrections at {frozen:?}");
}
