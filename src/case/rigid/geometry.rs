//! The mesh a case with rigid surfaces is solved on: the given one, plus the edges of the
//! lines and circles of `[[rigid]]` (Seg2 cells whose right-hand normal points out of the
//! rigid body; a line over the bodies' extent and as much again on each side, in chords
//! of the shortest cell side; a circle in chords of a quarter of it) and a node for each reference point and each rotation. The added nodes come
//! after the given ones, so that results cut back to the given mesh keep their numbering.

use super::super::schema::{CaseFile, RigidSpec};
use super::{name_of, reference_group, rotation_group};
use crate::error::{Error, Result};
use crate::mesh::topology::{edge_parent, edge_parents};
use crate::mesh::{CellKind, Mesh, MeshBuilder};
use std::f64::consts::PI;

/// Circles are polygons of at least this many chords (and at most `MAX_SEGMENTS`).
const MIN_SEGMENTS: usize = 360;
const MAX_SEGMENTS: usize = 100_000;

fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// Checks an entry against the given mesh: one surface, one reference point, a group of
/// edges that bound no 2D cell.
fn check_entry(spec: &RigidSpec, what: &str, mesh: &Mesh, in_2d: &[bool]) -> Result<()> {
    let given = [
        spec.group.is_some(),
        spec.line.is_some(),
        spec.circle.is_some(),
    ];
    if given.iter().filter(|&&g| g).count() != 1 {
        return Err(Error::model(format!(
            "{what}: give exactly one of group (an edge group of the mesh), line = {{ point, \
             normal }} or circle = {{ center, radius }}"
        )));
    }
    match (&spec.reference, &spec.reference_node) {
        (None, None) => {
            return Err(Error::model(format!(
                "{what} has no reference point: give reference = [x, y] or reference_node = \
                 \"GROUP\" (a one-node group of no 2D cell); its motion and loads, and its \
                 reaction, are those of that point"
            )))
        }
        (Some(_), Some(_)) => {
            return Err(Error::model(format!(
                "{what}: give reference or reference_node, not both"
            )))
        }
        (Some(r), None) if !finite(r) => {
            return Err(Error::model(format!("{what}: reference must be finite")))
        }
        (None, Some(g)) => {
            let n = mesh
                .single_node(g)
                .map_err(|e| Error::model(format!("{what}: reference_node: {e}")))?;
            if in_2d[n] {
                return Err(Error::model(format!(
                    "{what}: reference_node '{g}' is node {}, a node of a 2D cell: the \
                     reference point of a rigid surface is a point of no body (a node of no \
                     2D cell, or reference = [x, y])",
                    n + 1
                )));
            }
        }
        _ => {}
    }
    if let Some(l) = &spec.line {
        if !finite(&l.point) || !finite(&l.normal) || l.normal[0].hypot(l.normal[1]) == 0.0 {
            return Err(Error::model(format!(
                "{what}: line needs a finite point and a finite, non-zero normal"
            )));
        }
    }
    if let Some(c) = &spec.circle {
        if !(finite(&c.center) && c.radius.is_finite() && c.radius > 0.0) {
            return Err(Error::model(format!(
                "{what}: circle needs a finite center and a positive radius, got radius {}",
                c.radius
            )));
        }
        if let Some(n) = c.segments.filter(|n| !(8..=MAX_SEGMENTS).contains(n)) {
            return Err(Error::model(format!(
                "{what}: circle segments must be 8 to {MAX_SEGMENTS}, got {n}"
            )));
        }
    }
    if let Some(g) = &spec.group {
        let cells = mesh
            .cell_group(g)
            .map_err(|e| Error::model(format!("{what}: {e}")))?;
        let parents = edge_parents(mesh);
        for &c in cells {
            let kind = mesh.kind(c);
            if kind.dim() != 1 {
                return Err(Error::model(format!(
                    "{what}: group '{g}' holds a {kind} cell; a rigid surface is a group of \
                     Seg2/Seg3 edges"
                )));
            }
            if let Some((p, _)) = edge_parent(mesh, &parents, c) {
                return Err(Error::model(format!(
                    "{what}: edge cell {} of group '{g}' is a side of the 2D cell {}: a rigid \
                     surface is an edge group that bounds no body of the mesh",
                    c + 1,
                    p + 1
                )));
            }
            if let Some(&n) = mesh.cell_nodes(c).iter().find(|&&n| in_2d[n]) {
                return Err(Error::model(format!(
                    "{what}: node {} of group '{g}' is a node of a 2D cell: a rigid surface \
                     shares no node with the bodies",
                    n + 1
                )));
            }
        }
    }
    Ok(())
}

/// The given mesh with the rigid surfaces' added edges and nodes; None without `[[rigid]]`.
pub fn augment(case: &CaseFile, mesh: &Mesh) -> Result<Option<Mesh>> {
    if case.rigid.is_empty() {
        return Ok(None);
    }
    let mut in_2d = vec![false; mesh.num_nodes()];
    let mut h_min = f64::INFINITY;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for c in mesh.cells_of_dim(2) {
        let nodes = mesh.cell_nodes(c);
        for &n in nodes {
            in_2d[n] = true;
            for k in 0..2 {
                lo[k] = lo[k].min(mesh.coords[n][k]);
                hi[k] = hi[k].max(mesh.coords[n][k]);
            }
        }
        let corners = mesh.kind(c).num_corners();
        for k in 0..corners {
            let (a, b) = (mesh.coords[nodes[k]], mesh.coords[nodes[(k + 1) % corners]]);
            h_min = h_min.min((a[0] - b[0]).hypot(a[1] - b[1]));
        }
    }
    let mut b = MeshBuilder::new("[[rigid]]");
    b.append(mesh, |s| s.to_string());
    let mut names: Vec<String> = vec![];
    for (i, spec) in case.rigid.iter().enumerate() {
        let name = name_of(spec, i)?;
        let what = format!("[[rigid]] '{name}'");
        if names.contains(&name) {
            return Err(Error::model(format!(
                "{what} is defined twice: names of [[rigid]] entries are unique"
            )));
        }
        check_entry(spec, &what, mesh, &in_2d)?;
        let made = spec.group.is_none();
        if made && (mesh.cell_groups.contains_key(&name) || mesh.node_groups.contains_key(&name)) {
            return Err(Error::model(format!(
                "{what}: the mesh already has a group '{name}'; name the line or circle \
                 otherwise"
            )));
        }
        if let (Some(g), Some(n)) = (&spec.group, &spec.name) {
            if g != n {
                return Err(Error::model(format!(
                    "{what}: name and group differ ('{n}', '{g}'); a [[contact]] names the \
                     group of a rigid surface of the mesh: drop name"
                )));
            }
        }
        // the polyline of a made surface, in the order that puts the outward normal on
        // the right of each chord
        let mut points: Vec<[f64; 2]> = vec![];
        let mut closed = false;
        if let Some(l) = &spec.line {
            let len = l.normal[0].hypot(l.normal[1]);
            let t = [-l.normal[1] / len, l.normal[0] / len];
            // over the bodies' extent along the line and that extent again on each side
            let corners = [lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]];
            let s: Vec<f64> = corners
                .iter()
                .map(|c| (c[0] - l.point[0]) * t[0] + (c[1] - l.point[1]) * t[1])
                .collect();
            let (s0, s1) = s
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            let w = (s1 - s0).max(h_min);
            // chords of the shortest cell side: mortar projects each master chord's ends on
            // the slave cells and needs them within a few cells
            let n = ((3.0 * w / h_min).ceil() as usize).clamp(1, MAX_SEGMENTS);
            for k in 0..=n {
                let sv = s0 - w + 3.0 * w * k as f64 / n as f64;
                points.push([l.point[0] + sv * t[0], l.point[1] + sv * t[1]]);
            }
        }
        if let Some(c) = &spec.circle {
            // (by default a multiple of 4: vertices at the circle's extreme points, where a
            // circle set on a flat touches it; a chord there would leave a gap)
            let n = c.segments.unwrap_or_else(|| {
                let chord = 0.25 * h_min;
                let n = (2.0 * PI * c.radius / chord).ceil() as usize;
                n.div_ceil(4)
                    .saturating_mul(4)
                    .clamp(MIN_SEGMENTS, MAX_SEGMENTS)
            });
            for k in 0..n {
                // counter-clockwise: the right-hand normal points out of the disc
                let a = 2.0 * PI * k as f64 / n as f64 * if c.inside { -1.0 } else { 1.0 };
                points.push([
                    c.center[0] + c.radius * a.cos(),
                    c.center[1] + c.radius * a.sin(),
                ]);
            }
            closed = true;
        }
        if made {
            let first = b.num_nodes();
            for &p in &points {
                b.add_node(p);
            }
            let n = points.len();
            let chords = if closed { n } else { n - 1 };
            for k in 0..chords {
                let cell = b.add_cell(
                    CellKind::Seg2,
                    &[first + k, first + (k + 1) % n],
                    (b.num_cells() + 1) as u64,
                );
                b.add_to_cell_group(&name, cell);
            }
        }
        if let Some(r) = spec.reference {
            let n = b.add_node(r);
            b.add_to_node_group(&reference_group(&name), n);
        }
        let r = match (spec.reference, &spec.reference_node) {
            (Some(r), _) => r,
            (None, Some(g)) => mesh.coords[mesh.single_node(g)?],
            (None, None) => unreachable!("checked above"),
        };
        let n = b.add_node(r);
        b.add_to_node_group(&rotation_group(&name), n);
        names.push(name);
    }
    let mut out = b.finish()?;
    out.reoriented = mesh.reoriented;
    Ok(Some(out))
}
