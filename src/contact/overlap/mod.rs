//! The physical check of contact, whatever the formulation: no node of a contact surface may
//! be inside the other body's deformed cells deeper than a fraction of its own cells, at the
//! start or at any point of a load step (a body pushed through another in one step ends up
//! beyond it: the node's path between the two converged states is followed too).
//!
//! | file | what |
//! |---|---|
//! | `geometry.rs` | point in a body, depth, crossing times of a moving point and piece |

pub mod geometry;

use super::pair::ContactPair;
use super::surface::Surface;
use crate::mesh::topology::node_bodies;
use crate::mesh::Mesh;
use geometry::{crossing_times, depth, lerp, P};
use rayon::prelude::*;
use std::collections::{BTreeSet, HashMap};

/// How deep a node may sit inside the other body, as a fraction of its shortest adjacent
/// cell side: penalty and augmented contact let points sink in by a small fraction of a
/// cell, and a node half a cell deep is no longer a contact point but a body passing
/// through.
pub const DEPTH_FRACTION: f64 = 0.5;

/// The nodes of one surface of a pair, against the body of the other.
struct Side {
    pair: usize,
    surface: String,
    other: String,
    nodes: Vec<usize>,
    /// Per node, the depth it may have.
    tol: Vec<f64>,
    /// The pair's part of it (mortar's adjust).
    allowance: f64,
    /// The straight pieces (node pairs) of the other body's boundary, holes included.
    pieces: Vec<[usize; 2]>,
}

/// One node too deep inside the other body.
#[derive(Clone, Copy, Debug)]
struct Finding {
    node: usize,
    depth: f64,
    tol: f64,
    /// Where in the step (0: its start, 1: its end).
    s: f64,
}

pub struct OverlapCheck {
    sides: Vec<Side>,
}

/// The boundary pieces of the bodies `ids` (node ids per `bodies`): cell sides that belong to
/// one cell, a quadratic side as two pieces through its mid-side node.
fn boundary_pieces(mesh: &Mesh, bodies: &[usize], ids: &BTreeSet<usize>) -> Vec<[usize; 2]> {
    let mut count: HashMap<(usize, usize), (usize, Vec<usize>)> = HashMap::new();
    for c in mesh.cells_of_dim(2) {
        let nodes = mesh.cell_nodes(c);
        if !ids.contains(&bodies[nodes[0]]) {
            continue;
        }
        for side in mesh.kind(c).edges() {
            let (a, b) = (nodes[side[0]], nodes[side[1]]);
            let e = count
                .entry((a.min(b), a.max(b)))
                .or_insert((0, side.iter().map(|&k| nodes[k]).collect()));
            e.0 += 1;
        }
    }
    let mut pieces = vec![];
    for (_, (n, side)) in count {
        if n != 1 {
            continue;
        }
        match side[..] {
            [a, b, m] => pieces.extend([[a, m], [m, b]]),
            [a, b] => pieces.push([a, b]),
            _ => {}
        }
    }
    pieces.sort_unstable();
    pieces
}

/// Per node, the shortest chord of the cell sides through it (infinite for a node of no
/// 2D cell).
fn shortest_sides(mesh: &Mesh) -> Vec<f64> {
    let mut h = vec![f64::INFINITY; mesh.num_nodes()];
    for c in mesh.cells_of_dim(2) {
        let nodes = mesh.cell_nodes(c);
        for side in mesh.kind(c).edges() {
            let (a, b) = (mesh.coords[nodes[side[0]]], mesh.coords[nodes[side[1]]]);
            let len = (a[0] - b[0]).hypot(a[1] - b[1]);
            for &k in side.iter() {
                h[nodes[k]] = h[nodes[k]].min(len);
            }
        }
    }
    h
}

fn position(mesh: &Mesh, u: &[f64], n: usize) -> P {
    [
        mesh.coords[n][0] + u[2 * n],
        mesh.coords[n][1] + u[2 * n + 1],
    ]
}

/// The box of a set of points: (min, max).
fn bbox(points: impl Iterator<Item = P>) -> (P, P) {
    points.fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    )
}

fn disjoint(a: (P, P), b: (P, P)) -> bool {
    a.1[0] < b.0[0] || b.1[0] < a.0[0] || a.1[1] < b.0[1] || b.1[1] < a.0[1]
}

/// The boundary pieces (node pairs) of the bodies that hold `surface`'s nodes: none for a
/// rigid surface.
pub fn pieces_of_bodies(mesh: &Mesh, surface: &Surface) -> Vec<[usize; 2]> {
    let bodies = node_bodies(mesh);
    boundary_pieces(mesh, &bodies, &bodies_of(&bodies, surface))
}

/// The bodies (ids per `bodies`) that hold `surface`'s nodes.
fn bodies_of(bodies: &[usize], surface: &Surface) -> BTreeSet<usize> {
    surface
        .nodes
        .iter()
        .map(|&n| bodies[n])
        .filter(|&id| id != usize::MAX)
        .collect()
}

impl OverlapCheck {
    /// The check of every pair, both ways: each surface's nodes against the other's body.
    pub fn new(mesh: &Mesh, pairs: &[Box<dyn ContactPair>]) -> Self {
        let surfaces: Vec<(&Surface, &Surface, f64)> = pairs
            .iter()
            .map(|p| {
                let (s, m) = p.surfaces();
                (s, m, p.overlap_allowance())
            })
            .collect();
        Self::from_surfaces(mesh, &surfaces)
    }

    /// The check of (slave, master, allowance) pairs; the allowance (mortar's adjust) adds
    /// to every tolerance of its pair.
    pub fn from_surfaces(mesh: &Mesh, pairs: &[(&Surface, &Surface, f64)]) -> Self {
        let bodies = node_bodies(mesh);
        let h = shortest_sides(mesh);
        let mut sides = vec![];
        for (i, &(slave, master, allowance)) in pairs.iter().enumerate() {
            for (a, b) in [(slave, master), (master, slave)] {
                let ids = bodies_of(&bodies, b);
                let tol = a
                    .nodes
                    .iter()
                    .map(|&n| DEPTH_FRACTION * h[n] + allowance)
                    .collect();
                sides.push(Side {
                    pair: i,
                    surface: a.group.clone(),
                    other: b.group.clone(),
                    nodes: a.nodes.clone(),
                    tol,
                    allowance,
                    pieces: boundary_pieces(mesh, &bodies, &ids),
                });
            }
        }
        OverlapCheck { sides }
    }

    /// The nodes of one side too deep in the other body at some point of the motion from
    /// displacement `u0` to `u1` (linear in between).
    fn side_findings(&self, mesh: &Mesh, side: &Side, u0: &[f64], u1: &[f64]) -> Vec<Finding> {
        let ends: Vec<((P, P), (P, P))> = side
            .pieces
            .iter()
            .map(|&[a, b]| {
                (
                    (position(mesh, u0, a), position(mesh, u1, a)),
                    (position(mesh, u0, b), position(mesh, u1, b)),
                )
            })
            .collect();
        let at = |s: f64| -> Vec<(P, P)> {
            ends.iter()
                .map(|&(a, b)| (lerp(a.0, a.1, s), lerp(b.0, b.1, s)))
                .collect()
        };
        let at_end = at(1.0);
        let swept = |e: &((P, P), (P, P))| bbox([e.0 .0, e.0 .1, e.1 .0, e.1 .1].into_iter());
        let body = bbox(ends.iter().flat_map(|e| [e.0 .0, e.0 .1, e.1 .0, e.1 .1]));
        let moved = u0 != u1;
        side.nodes
            .par_iter()
            .zip(&side.tol)
            .filter_map(|(&n, &tol)| {
                let (p0, p1) = (position(mesh, u0, n), position(mesh, u1, n));
                let path = bbox([p0, p1].into_iter());
                if disjoint(path, body) {
                    return None;
                }
                // between two crossings of the boundary the node is in or out throughout:
                // the end and the middle of each stretch tell how deep it went
                let mut times = vec![0.0, 1.0];
                if moved {
                    for e in &ends {
                        if !disjoint(path, swept(e)) {
                            crossing_times(p0, p1, e.0, e.1, &mut times);
                        }
                    }
                }
                times.sort_by(f64::total_cmp);
                let mut probes = vec![1.0];
                if moved {
                    probes.extend(times.windows(2).map(|w| 0.5 * (w[0] + w[1])));
                }
                probes
                    .into_iter()
                    .filter_map(|s| {
                        let d = if s == 1.0 {
                            depth(p1, &at_end)
                        } else {
                            depth(lerp(p0, p1, s), &at(s))
                        }?;
                        (d > tol).then_some(Finding {
                            node: n,
                            depth: d,
                            tol,
                            s,
                        })
                    })
                    .max_by(|a, b| (a.depth / a.tol).total_cmp(&(b.depth / b.tol)))
            })
            .collect()
    }

    /// The worst side: (side, number of nodes too deep, the deepest relative to its
    /// tolerance).
    fn worst(&self, mesh: &Mesh, u0: &[f64], u1: &[f64]) -> Option<(&Side, usize, Finding)> {
        self.sides
            .iter()
            .filter_map(|side| {
                let f = self.side_findings(mesh, side, u0, u1);
                let worst = f
                    .iter()
                    .copied()
                    .max_by(|a, b| (a.depth / a.tol).total_cmp(&(b.depth / b.tol)))?;
                Some((side, f.len(), worst))
            })
            .max_by(|a, b| (a.2.depth / a.2.tol).total_cmp(&(b.2.depth / b.2.tol)))
    }

    /// The undeformed bodies overlapping: a message naming the pair, the nodes and the depth.
    pub fn at_start(&self, mesh: &Mesh) -> Option<String> {
        let u = vec![0.0; 2 * mesh.num_nodes()];
        let (side, count, f) = self.worst(mesh, &u, &u)?;
        Some(format!(
            "[[contact]] {}: the undeformed bodies overlap: {count} nodes of '{}' are inside \
             the body of '{}', node {} deepest at {:.3e} (more than {:.3e}, half its shortest \
             cell side{}); separate the bodies, or mesh their interference smaller than that",
            side.pair + 1,
            side.surface,
            side.other,
            f.node + 1,
            f.depth,
            f.tol,
            allowance_note(side)
        ))
    }

    /// A motion from displacement `u0` (the last converged state) to `u1` (a converged
    /// iterate) that takes contact nodes deep into the other body: a message naming the
    /// pair, the nodes and the depth.
    pub fn during_step(&self, mesh: &Mesh, u0: &[f64], u1: &[f64]) -> Option<String> {
        let (side, count, f) = self.worst(mesh, u0, u1)?;
        let when = if f.s < 1.0 {
            format!(" on the way (at {:.2e} of the step)", f.s)
        } else {
            String::new()
        };
        Some(format!(
            "[[contact]] {}: the bodies pass through each other: {count} nodes of '{}' went \
             inside the body of '{}'{when}, node {} deepest at {:.3e} (more than {:.3e}, half \
             its shortest cell side{}); contact did not hold them apart (a motion or load far \
             beyond what the contact can carry, or a step too large to see the contact)",
            side.pair + 1,
            side.surface,
            side.other,
            f.node + 1,
            f.depth,
            f.tol,
            allowance_note(side)
        ))
    }
}

fn allowance_note(side: &Side) -> &'static str {
    if side.allowance > 0.0 {
        " plus the pair's adjust"
    } else {
        ""
    }
}

#[cfg(test)]
mod tests;
