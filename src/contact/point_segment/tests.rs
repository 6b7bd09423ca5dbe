//! Anticipated candidates: a block lifted ten cells above a foundation has none; a
//! predicted displacement that sets it down brings every slave cell within reach at once,
//! and a prediction gone wild is refused. A coarse block half a cell of its own above a
//! fine foundation reserves no pattern until it comes within a few fine cells. A body
//! carried through another finds the master cells along its normal, not those beside; swept
//! inward only, it finds them and not those across an open gap. A point inside the master body
//! pairs however deep; one through it does not. Statuses on the linearisation: a block set
//! down from beyond reach closes, one held short opens.

use super::*;
use crate::fem::material::Modelisation;
use crate::mesh::generate::rectangle;
use crate::mesh::{CellKind, Mesh, MeshBuilder};

/// A 1.4 × 0.5 block (cells of side 0.1, groups `Upper…`) a gap of 1.0 above a 20 × 1
/// foundation (groups `Lower…`); the block's nodes come last.
fn lifted_block() -> (Mesh, usize) {
    let upper = rectangle([0.3, 1.0], 1.4, 0.5, 14, 5, CellKind::Quad4, 0.0).unwrap();
    over_foundation(&upper)
}

/// `upper` (groups `Upper…`) over a 20 × 1 foundation of cells of side 0.1 (groups
/// `Lower…`) whose top is y = 0; the upper body's nodes come last.
fn over_foundation(upper: &Mesh) -> (Mesh, usize) {
    let lower = rectangle([0.0, -1.0], 20.0, 1.0, 200, 10, CellKind::Quad4, 0.0).unwrap();
    let mut b = MeshBuilder::new("block over a foundation");
    b.append(&lower, |g| format!("Lower{g}"));
    b.append(upper, |g| format!("Upper{g}"));
    (b.finish().unwrap(), lower.num_nodes())
}

#[test]
fn a_predicted_displacement_brings_the_slave_cells_within_reach_at_once() {
    let (mesh, first_upper) = lifted_block();
    let slave = Surface::from_group(&mesh, "UpperBottom", "slave").unwrap();
    let master = Surface::from_group(&mesh, "LowerTop", "master").unwrap();
    let cells = slave.cells.len();
    let mut p = PointToSegment::new(
        &mesh,
        slave,
        master,
        Options::default(),
        Modelisation::PlaneStrain,
        1.0,
    );
    p.initialise(&mesh);
    assert!(p.candidates.iter().all(Vec::is_empty), "ten cells apart");
    let moved = |dx: f64, dy: f64| {
        let mut u = vec![0.0; 2 * mesh.num_nodes()];
        for n in first_upper..mesh.num_nodes() {
            u[2 * n] = dx;
            u[2 * n + 1] = dy;
        }
        u
    };
    // set down: every slave cell within reach, in one growth of the pattern
    p.anticipate(&mesh, &moved(0.0, -1.0), 0.0);
    assert_eq!(p.candidates_generation, 1);
    assert!(
        p.candidates.iter().all(|c| !c.is_empty()),
        "all {cells} cells"
    );
    let held: Vec<Vec<usize>> = p.candidates.clone();
    // the same again: nothing new
    p.anticipate(&mesh, &moved(0.0, -1.0), 0.0);
    assert_eq!(p.candidates_generation, 1);
    // the candidates held, and those of a prediction (`reach` 0: at u alone)
    let (slave, master) = (p.slave.clone(), p.master.clone());
    let union = |held: &[Vec<usize>], u: &[f64], reach: f64| -> Vec<Vec<usize>> {
        let near =
            pattern_candidates_within(&mesh, Some(u), &slave, &master, CANDIDATE_MARGIN, reach);
        let mut all: Vec<Vec<usize>> = held.to_vec();
        for (list, more) in all.iter_mut().zip(near) {
            let new: Vec<usize> = more.into_iter().filter(|m| !list.contains(m)).collect();
            list.extend(new);
            list.sort_unstable();
        }
        all
    };
    let sorted = |c: &[Vec<usize>]| -> Vec<Vec<usize>> {
        c.iter()
            .map(|l| {
                let mut l = l.clone();
                l.sort_unstable();
                l
            })
            .collect()
    };
    // slid along by five block widths, with a reach of half that: the pattern would take
    // in the master cells along the path, more than twice those under the block where it
    // stopped and where it was: those only
    let slid = moved(7.0, -1.0);
    let expected = union(&held, &slid, 0.0);
    assert!(sorted(&expected) != sorted(&union(&held, &slid, 3.5)));
    p.anticipate(&mesh, &slid, 3.5);
    assert_eq!(p.candidates_generation, 2);
    assert_eq!(sorted(&p.candidates), expected);
    // slid by one more cell, with a reach of six cells: taken with the reach
    let held = p.candidates.clone();
    let nudged = moved(7.1, -1.0);
    let expected = union(&held, &nudged, 0.6);
    assert!(sorted(&expected) != sorted(&union(&held, &nudged, 0.0)));
    p.anticipate(&mesh, &nudged, 0.6);
    assert_eq!(p.candidates_generation, 3);
    assert_eq!(sorted(&p.candidates), expected);
}

/// A block of 2 × 2 cells a gap of 0.5 (five cells of 0.1 of the foundation, a quarter of
/// its own) above a fine foundation; the block's nodes come last.
fn coarse_block_over_fine() -> (Mesh, usize) {
    let upper = rectangle([6.0, 0.5], 8.0, 2.0, 4, 1, CellKind::Quad4, 0.0).unwrap();
    over_foundation(&upper)
}

#[test]
fn a_coarse_cell_far_in_fine_cells_reserves_no_pattern_until_it_comes_near() {
    let (mesh, first_upper) = coarse_block_over_fine();
    let slave = Surface::from_group(&mesh, "UpperBottom", "slave").unwrap();
    let master = Surface::from_group(&mesh, "LowerTop", "master").unwrap();
    // within three of the larger cells (the block's: 6.0) every slave cell has candidates;
    // within three of the smaller (the foundation's: 0.3) none has
    let near = candidates_within(&mesh, None, &slave, &master, CANDIDATE_MARGIN, 0.0);
    assert!(near.iter().all(|c| !c.is_empty()));
    let reserved = pattern_candidates_within(&mesh, None, &slave, &master, CANDIDATE_MARGIN, 0.0);
    assert!(reserved.iter().all(Vec::is_empty));
    let closed = Options {
        initial: InitialStatus::Closed,
        ..Options::default()
    };
    let mut p = PointToSegment::new(&mesh, slave, master, closed, Modelisation::PlaneStrain, 1.0);
    // its points pair (within twice the block's cell) but, open and far in fine cells,
    // bring nothing into the pattern
    p.initialise(&mesh);
    assert!(p.points.iter().any(|q| !q.excluded), "paired");
    assert!(p.points.iter().all(|q| !q.active));
    assert!(p.candidates.iter().all(Vec::is_empty));
    assert_eq!(p.candidates_generation, 0);
    // lowered to a gap of 0.2 (two fine cells): every slave cell's points pair within the
    // reserve, and their cells join the pattern
    let mut u = vec![0.0; 2 * mesh.num_nodes()];
    for n in first_upper..mesh.num_nodes() {
        u[2 * n + 1] = -0.3;
    }
    for i in 0..p.points.len() {
        p.pair(&mesh, &u, i, true, &[], false);
    }
    assert!(p.candidates.iter().all(|c| !c.is_empty()));
}

#[test]
fn a_body_carried_through_another_finds_the_cells_along_its_normal_not_beside() {
    // the block set 1.3 down from a gap of 1.0: its bottom 0.3 inside the foundation
    let (mesh, first_upper) = lifted_block();
    let slave = Surface::from_group(&mesh, "UpperBottom", "slave").unwrap();
    let master = Surface::from_group(&mesh, "LowerTop", "master").unwrap();
    let mut u = vec![0.0; 2 * mesh.num_nodes()];
    for n in first_upper..mesh.num_nodes() {
        u[2 * n + 1] = -1.3;
    }
    let around = candidates_within(&mesh, Some(&u), &slave, &master, 1.0, 0.4);
    let swept = swept_candidates(&mesh, Some(&u), &slave, &master, 1.0, 0.4);
    for (ic, (a, s)) in around.iter().zip(&swept).enumerate() {
        // the master cell under the slave cell (cells of 0.1 from x = 0; the block's from
        // x = 0.3) and its neighbours within the margin (0.1, ends included): five at most
        assert!(s.contains(&(ic + 3)), "cell {ic}: {s:?}");
        assert!(s.iter().all(|m| a.contains(m)));
        assert!(s.len() <= 5, "cell {ic}: {} swept", s.len());
        // all around: the 0.4 reach both ways along the surface, 8 or more
        assert!(a.len() >= 8, "cell {ic}: {} around", a.len());
    }
    // not inside: no sweep reaches the foundation from a gap of 1.0
    let none = swept_candidates(&mesh, None, &slave, &master, 1.0, 0.4);
    assert!(none.iter().all(Vec::is_empty));
}

#[test]
fn an_inward_sweep_finds_the_cells_a_body_passed_through_not_those_across_a_gap() {
    let (mesh, first_upper) = lifted_block();
    let slave = Surface::from_group(&mesh, "UpperBottom", "slave").unwrap();
    let master = Surface::from_group(&mesh, "LowerTop", "master").unwrap();
    let lowered = |dy: f64| {
        let mut u = vec![0.0; 2 * mesh.num_nodes()];
        for n in first_upper..mesh.num_nodes() {
            u[2 * n + 1] = dy;
        }
        u
    };
    // 0.3 inside the foundation (three cells): the margin alone sees nothing, a sweep of 0.4
    // into the block finds the master cell under each slave cell and at most its neighbours
    let inside = lowered(-1.3);
    let margin_only = overlap_candidates(&mesh, &inside, &slave, &master, 1.0, 0.0);
    assert!(margin_only.iter().all(Vec::is_empty));
    let passed = overlap_candidates(&mesh, &inside, &slave, &master, 1.0, 0.4);
    for (ic, s) in passed.iter().enumerate() {
        assert!(s.contains(&(ic + 3)), "cell {ic}: {s:?}");
        assert!(s.len() <= 5, "cell {ic}: {} found", s.len());
    }
    // 0.3 above it (an open gap of three cells): the same sweep, inward, finds nothing,
    // where one both ways would reach across the gap
    let above = lowered(-0.7);
    assert!(overlap_candidates(&mesh, &above, &slave, &master, 1.0, 0.4)
        .iter()
        .all(Vec::is_empty));
    assert!(
        swept_candidates(&mesh, Some(&above), &slave, &master, 1.0, 0.4)
            .iter()
            .all(|c| !c.is_empty())
    );
}

/// The lifted block's bottom as the slave of the foundation's top, with the default
/// options, initialised; and the displacement that lowers the block by -dy.
fn lifted_block_pair() -> (Mesh, PointToSegment, impl Fn(f64) -> Vec<f64>) {
    let (mesh, first_upper) = lifted_block();
    let slave = Surface::from_group(&mesh, "UpperBottom", "slave").unwrap();
    let master = Surface::from_group(&mesh, "LowerTop", "master").unwrap();
    let opts = Options::default();
    let mut p = PointToSegment::new(&mesh, slave, master, opts, Modelisation::PlaneStrain, 1.0);
    p.initialise(&mesh);
    let nodes = mesh.num_nodes();
    let lowered = move |dy: f64| {
        let mut u = vec![0.0; 2 * nodes];
        for n in first_upper..nodes {
            u[2 * n + 1] = dy;
        }
        u
    };
    (mesh, p, lowered)
}

#[test]
fn a_point_inside_the_master_body_pairs_however_deep_and_one_beyond_it_does_not() {
    let (mesh, mut p, lowered) = lifted_block_pair();
    // the block's bottom 0.5 inside the foundation (1 deep): five of its cells, beyond the
    // reach of two; every point pairs, and its cell joins the pattern
    p.pair_all(&mesh, &lowered(-1.5));
    assert!(p.points.iter().all(|q| !q.excluded));
    assert!(p.candidates.iter().all(|c| !c.is_empty()));
    // 0.2 below the foundation's bottom: through it, no point pairs
    p.pair_all(&mesh, &lowered(-2.2));
    assert!(p.points.iter().all(|q| q.excluded));
}

#[test]
fn linearised_statuses_close_a_block_set_down_from_beyond_reach_and_open_one_held_short() {
    let (mesh, mut p, lowered) = lifted_block_pair();
    // a gap of 1.0, five times the reach: every point unpaired, open
    assert!(p.points.iter().all(|q| q.excluded && !q.active));
    assert!(p.candidates.iter().all(Vec::is_empty));
    let lam = vec![0.0; p.num_multipliers()];
    let n = p.points.len();
    // linearised at rest, taken where a correction set the block 0.05 into the foundation:
    // every point pairs there and closes (gap −1.0 + 1.05), and its cell joins the pattern
    let rest = lowered(0.0);
    assert_eq!(
        p.linearised_status(&mesh, &rest, &lowered(-1.05), &lam),
        Some(n)
    );
    assert!(p.points.iter().all(|q| q.active && !q.excluded));
    assert!(p.candidates.iter().all(|c| !c.is_empty()));
    // a translation is exact in the linearisation: the iterate's own statuses agree
    assert_eq!(p.update_status(&mesh, &lowered(-1.05), &lam), 0);
    // taken where the block stops 0.05 short of the foundation: every point opens
    assert_eq!(
        p.linearised_status(&mesh, &rest, &lowered(-0.95), &lam),
        Some(n)
    );
    assert!(p.points.iter().all(|q| !q.active));
    // linearised half-way down (still beyond reach), taken 0.05 in: closed again
    assert_eq!(
        p.linearised_status(&mesh, &lowered(-0.5), &lowered(-1.05), &lam),
        Some(n)
    );
    assert!(p.points.iter().all(|q| q.active));
}
