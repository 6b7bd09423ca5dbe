//! Which surface of a mortar pair carries the multipliers: the coarser one where the two
//! face each other. A multiplier space finer than the master's trace resolves the master's
//! kinks and oscillates (concentric rings, a quadratic slave of 63 nodes on a linear master
//! of 25: ±6 % of the Lamé pressure; the other way round 0.13 %; SSNP154 refined: 3.6 %
//! of p0 and 55 % on quadratic cells), so the user's slave and master name the pair, and
//! the formulation picks the stable side: the answer does not depend on the naming. Where
//! both faces are straight and in line there are no kinks: the user's choice stands (a
//! block sliding along a long foundation keeps its multipliers on the block).

use super::super::point_segment::initial_candidates;
use super::super::surface::Surface;
use super::PATTERN_MARGIN;
use crate::mesh::Mesh;

/// A surface counts as coarser when its node spacing exceeds the other's by this factor
/// (near-equal spacings keep the user's choice: either side is stable then).
const COARSER: f64 = 1.2;

fn chord(mesh: &Mesh, cell: usize) -> ([f64; 2], [f64; 2]) {
    let n = mesh.cell_nodes(cell);
    (mesh.coords[n[0]], mesh.coords[n[1]])
}

fn length(c: ([f64; 2], [f64; 2])) -> f64 {
    (c.0[0] - c.1[0]).hypot(c.0[1] - c.1[1])
}

/// Distance from p to the segment ab.
fn distance(p: [f64; 2], (a, b): ([f64; 2], [f64; 2])) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// Mean node spacing (chord length per pair of consecutive nodes) over the cells of `s`
/// whose midpoint lies within `reach` of `other` (None if there is none), and the unit
/// chord directions of those cells.
fn facing_spacing(
    mesh: &Mesh,
    s: &Surface,
    other: &Surface,
    reach: f64,
) -> (Option<f64>, Vec<[f64; 2]>) {
    let near = initial_candidates(mesh, s, other, PATTERN_MARGIN);
    let (mut total, mut gaps) = (0.0, 0usize);
    let mut directions = vec![];
    for (ic, c) in near.iter().enumerate() {
        let ch = chord(mesh, s.cells[ic]);
        let mid = [0.5 * (ch.0[0] + ch.1[0]), 0.5 * (ch.0[1] + ch.1[1])];
        let d = c
            .iter()
            .map(|&im| distance(mid, chord(mesh, other.cells[im])))
            .fold(f64::INFINITY, f64::min);
        if d <= reach {
            let l = length(ch);
            total += l;
            gaps += mesh.cell_nodes(s.cells[ic]).len() - 1;
            directions.push([(ch.1[0] - ch.0[0]) / l, (ch.1[1] - ch.0[1]) / l]);
        }
    }
    ((gaps > 0).then(|| total / gaps as f64), directions)
}

/// Whether the facing cells of both surfaces (their chords, mid-side nodes aside) all lie
/// along one direction: no kink for a fine side to resolve.
fn straight(directions: &[[f64; 2]], mesh: &Mesh, surfaces: [&Surface; 2]) -> bool {
    let Some(d0) = directions.first() else {
        return true;
    };
    let in_line = directions
        .iter()
        .all(|d| (d0[0] * d[1] - d0[1] * d[0]).abs() < 1e-9);
    // mid-side nodes on the chords too (a curved Seg3 has a kink-free but curved face)
    let mids_on_chords = surfaces.iter().all(|s| {
        s.cells.iter().all(|&c| {
            let n = mesh.cell_nodes(c);
            n.len() < 3 || {
                let (a, b, m) = (mesh.coords[n[0]], mesh.coords[n[1]], mesh.coords[n[2]]);
                let l = length((a, b));
                ((b[0] - a[0]) * (m[1] - a[1]) - (b[1] - a[1]) * (m[0] - a[0])).abs()
                    <= 1e-9 * l * l
            }
        })
    });
    in_line && mids_on_chords
}

/// The pair with the multipliers on the coarser surface: (slave, master, swapped).
pub fn multiplier_side(mesh: &Mesh, slave: Surface, master: Surface) -> (Surface, Surface, bool) {
    // where the surfaces are within a few of their smallest cells of each other: the
    // likely contact zone (the whole interface of a fit)
    let smallest = slave
        .cells
        .iter()
        .chain(&master.cells)
        .map(|&c| length(chord(mesh, c)))
        .fold(f64::INFINITY, f64::min);
    let reach = 3.0 * smallest;
    let (s, mut directions) = facing_spacing(mesh, &slave, &master, reach);
    let (m, more) = facing_spacing(mesh, &master, &slave, reach);
    directions.extend(more);
    match (s, m) {
        (Some(s), Some(m))
            if m > COARSER * s && !straight(&directions, mesh, [&slave, &master]) =>
        {
            (master, slave, true)
        }
        _ => (slave, master, false),
    }
}
