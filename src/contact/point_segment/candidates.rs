//! Candidate search: the master cells within reach of each slave cell, by bounding boxes
//! on the initial or a displaced geometry.

use super::super::surface::Surface;
use crate::mesh::Mesh;

/// Master cells within reach of each slave cell on the initial geometry: those whose
/// bounding box, grown by `margin` times the larger of the two cells' sizes, meets the
/// slave cell's.
pub fn initial_candidates(
    mesh: &Mesh,
    slave: &Surface,
    master: &Surface,
    margin: f64,
) -> Vec<Vec<usize>> {
    candidates_within(mesh, None, slave, master, margin, 0.0)
}

/// The same on the geometry displaced by `u` (full dofs) when given, the boxes grown by at
/// least `reach` (a distance).
pub fn candidates_within(
    mesh: &Mesh,
    u: Option<&[f64]>,
    slave: &Surface,
    master: &Surface,
    margin: f64,
    reach: f64,
) -> Vec<Vec<usize>> {
    within(
        mesh,
        u,
        (slave, master),
        reach,
        Sweep::BothWays(0.0),
        |s, m| margin * s.max(m),
    )
}

/// The master cells whose couplings with each slave cell a matrix pattern reserves: as
/// `candidates_within`, the margin `margin` times the *smaller* of the two cells' sizes.
/// The reserve is for pairings that change as the bodies move a little (a point sliding
/// to the next fine cell); larger motion is taken in by the reach. On a graded mesh the
/// larger cell is a coarse one far from the contact zone, and a margin of a few of its
/// sizes reserved couplings of cells a gap of many fine cells apart (SSNP154 D at 93k
/// unknowns: slave cells of 2.5–4.9 mm up the arc with the block's top 8 mm below): their
/// nodes joined the contact interface the solver condenses on, which grew from the 700
/// unknowns contact couples to 2300, its dense LU about 30 times the cost.
pub fn pattern_candidates_within(
    mesh: &Mesh,
    u: Option<&[f64]>,
    slave: &Surface,
    master: &Surface,
    margin: f64,
    reach: f64,
) -> Vec<Vec<usize>> {
    within(
        mesh,
        u,
        (slave, master),
        reach,
        Sweep::BothWays(0.0),
        |s, m| margin * s.min(m),
    )
}

/// The pattern candidates to take in at the displacement `u` predicted for the loading's
/// end: those within `margin` of the smaller cell there (`pattern_candidates_within`), and
/// those within `reach` (a distance) of it unless these would more than double the master
/// cells that `u` alone brings into the pattern with the cells `held` there already (a body
/// predicted to slide far would take in every master cell along its path; the interface
/// grows with them).
pub fn anticipated_candidates<'a>(
    mesh: &Mesh,
    u: &[f64],
    (slave, master): (&Surface, &Surface),
    (margin, reach): (f64, f64),
    held: impl IntoIterator<Item = &'a Vec<usize>>,
) -> Vec<Vec<usize>> {
    let mut in_pattern = vec![false; master.cells.len()];
    for &m in held.into_iter().flatten() {
        in_pattern[m] = true;
    }
    // the master cells of the pattern with these added
    let cells = |new: &[Vec<usize>]| {
        let mut all = in_pattern.clone();
        for &m in new.iter().flatten() {
            all[m] = true;
        }
        all.iter().filter(|&&c| c).count()
    };
    let at_u = pattern_candidates_within(mesh, Some(u), slave, master, margin, 0.0);
    let within = pattern_candidates_within(mesh, Some(u), slave, master, margin, reach);
    if cells(&within) <= 2 * cells(&at_u) {
        within
    } else {
        at_u
    }
}

/// As `candidates_within` without a reach, each slave cell's box taken over the cell swept
/// `sweep` both ways along its chord's normal: the master cells a body carried through
/// another, or a gap closed, brings along the normal, without those beside them (a reach
/// of `sweep` all around held 2 sweep / h master cells of size h for each slave cell).
pub fn swept_candidates(
    mesh: &Mesh,
    u: Option<&[f64]>,
    slave: &Surface,
    master: &Surface,
    margin: f64,
    sweep: f64,
) -> Vec<Vec<usize>> {
    within(
        mesh,
        u,
        (slave, master),
        0.0,
        Sweep::BothWays(sweep),
        |s, m| margin * s.max(m),
    )
}

/// As `swept_candidates`, each slave cell swept `depth` inward only (into its own body):
/// the master cells it has passed through, however deep, without widening its reach across
/// an open gap.
pub fn overlap_candidates(
    mesh: &Mesh,
    u: &[f64],
    slave: &Surface,
    master: &Surface,
    margin: f64,
    depth: f64,
) -> Vec<Vec<usize>> {
    within(
        mesh,
        Some(u),
        (slave, master),
        0.0,
        Sweep::Inward(depth),
        |s, m| margin * s.max(m),
    )
}

/// How far a slave cell's box is swept along its chord's normal.
#[derive(Clone, Copy)]
enum Sweep {
    BothWays(f64),
    /// into the slave's body only
    Inward(f64),
}

/// The master cells of each slave cell whose bounding boxes, on the geometry displaced by
/// `u`, come within `margin(slave size, master size)` or `reach` of each other, the slave
/// cell's box taken over the cell swept `sweep` both ways along its chord's normal.
fn within(
    mesh: &Mesh,
    u: Option<&[f64]>,
    (slave, master): (&Surface, &Surface),
    reach: f64,
    sweep: Sweep,
    margin: impl Fn(f64, f64) -> f64,
) -> Vec<Vec<usize>> {
    let at = |n: usize| -> [f64; 2] {
        let x = mesh.coords[n];
        u.map_or(x, |u| [x[0] + u[2 * n], x[1] + u[2 * n + 1]])
    };
    let bbox = |c: usize| {
        let mut lo = [f64::MAX; 2];
        let mut hi = [f64::MIN; 2];
        for &n in mesh.cell_nodes(c) {
            let x = at(n);
            for d in 0..2 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
        (lo, hi)
    };
    let mboxes: Vec<_> = master.cells.iter().map(|&c| bbox(c)).collect();
    slave
        .cells
        .iter()
        .zip(&slave.ccw)
        .map(|(&sc, &ccw)| {
            let (mut slo, mut shi) = bbox(sc);
            let ssize = (shi[0] - slo[0]).hypot(shi[1] - slo[1]);
            let nodes = mesh.cell_nodes(sc);
            let (a, b) = (at(nodes[0]), at(nodes[1]));
            let chord = (b[0] - a[0]).hypot(b[1] - a[1]);
            // (the chord's left-hand unit normal: inward where the cell runs
            // counter-clockwise round its body)
            let left = [(a[1] - b[1]) / chord, (b[0] - a[0]) / chord];
            match sweep {
                Sweep::BothWays(sweep) if sweep > 0.0 && chord > 0.0 => {
                    // (the box of the cell moved ± sweep n: its own, grown by |sweep n|)
                    for d in 0..2 {
                        slo[d] -= (left[d] * sweep).abs();
                        shi[d] += (left[d] * sweep).abs();
                    }
                }
                Sweep::Inward(depth) if depth > 0.0 && chord > 0.0 => {
                    let sign = if ccw { depth } else { -depth };
                    for d in 0..2 {
                        slo[d] = slo[d].min(slo[d] + sign * left[d]);
                        shi[d] = shi[d].max(shi[d] + sign * left[d]);
                    }
                }
                _ => {}
            }
            mboxes
                .iter()
                .enumerate()
                .filter(|(_, (lo, hi))| {
                    let r = margin(ssize, (hi[0] - lo[0]).hypot(hi[1] - lo[1])).max(reach);
                    (0..2).all(|d| lo[d] - r <= shi[d] && slo[d] <= hi[d] + r)
                })
                .map(|(i, _)| i)
                .collect()
        })
        .collect()
}
