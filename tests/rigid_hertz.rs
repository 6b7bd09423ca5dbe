//! A rigid circle (`[[rigid]] circle`) pressed by a force into an elastic block, plane
//! strain, half model: Hertz's rigid cylinder on a half-space, a = √(4PR/(πE*)),
//! p0 = 2P/(πa) = E* a / (2R), E* = E/(1 − ν²).
//!
//! Error budget: the block is 20a wide (half) and 20a deep, graded from cells of a/25.6
//! (or a/12.8) under the contact; the circle is a polygon of chords h/4 (its sag,
//! h²/(128R), is 1e-7 of a). The finite block departs from the half-space by O((a/H)²)
//! = 0.25 %; the contact edge is resolved to a cell. Measured: p0 −0.36 % (mortar) and
//! −0.34 / −0.36 % (point-to-segment, nodal) at the two sizes (they differ by 0.02 % at
//! most: the mesh is converged, what is left is the finite block), the edge within 0.6
//! cell of a. The test asserts p0 within 1 % at both
//! sizes and the two within 0.5 % of each other, the contact edge within one cell of a,
//! and the load balance to 1e-8.

mod common;

use common::case_head;
use std::collections::HashMap;
use tribo::case::{run, schema::CaseFile};
use tribo::mesh::quadtree::Quadtree;
use tribo::mesh::{CellKind, Mesh, MeshBuilder};

const E: f64 = 1000.0;
const NU: f64 = 0.3;
const R: f64 = 10.0;
const A: f64 = 0.5;

/// The block [0, 10] × [−10, 0] graded to cells of 1.25 / 2^level within 2a of the origin
/// (groups `Body`, `Top` edges, `Left` and `Bottom` nodes).
fn graded_block(level: u32) -> Mesh {
    let (w, root) = (10.0, 1.25);
    let mut q = Quadtree::new(8, 8, root);
    q.refine(level, &|q: &Quadtree, leaf| {
        let (x0, y0, s) = q.bbox(leaf);
        // distance from the origin (the top-left corner, y = w in the parameter plane)
        let dx = x0.max(0.0);
        let dy = (w - (y0 + s)).max(0.0);
        dx.hypot(dy) < 2.0 * A + s
    });
    q.balance();
    let mut b = MeshBuilder::new("graded block");
    let mut index: HashMap<(u64, u64), usize> = HashMap::new();
    let mut node = |b: &mut MeshBuilder, p: (u64, u64)| {
        *index.entry(p).or_insert_with(|| {
            let x = q.param(p);
            b.add_node([x[0], x[1] - w])
        })
    };
    let cells = q.cells();
    let ymax = cells.iter().flatten().map(|p| p.1).max().unwrap();
    for corners in &cells {
        let nodes: Vec<usize> = corners.iter().map(|&p| node(&mut b, p)).collect();
        let kind = if nodes.len() == 4 {
            CellKind::Quad4
        } else {
            CellKind::Tri3
        };
        let c = b.add_cell(kind, &nodes, 0);
        b.add_to_cell_group("Body", c);
        for k in 0..corners.len() {
            let (p, r) = (corners[k], corners[(k + 1) % corners.len()]);
            if p.1 == ymax && r.1 == ymax {
                let e = b.add_cell(CellKind::Seg2, &[nodes[k], nodes[(k + 1) % nodes.len()]], 0);
                b.add_to_cell_group("Top", e);
            }
        }
    }
    let mut sorted: Vec<(&(u64, u64), &usize)> = index.iter().collect();
    sorted.sort();
    for (p, &n) in sorted {
        if p.0 == 0 {
            b.add_to_node_group("Left", n);
        }
        if p.1 == 0 {
            b.add_to_node_group("Bottom", n);
        }
    }
    b.finish().unwrap()
}

/// (peak pressure / p0 − 1, contact edge − a, the cell size there, load balance error).
fn indent(level: u32, formulation: &str) -> (f64, f64, f64, f64) {
    let mesh = graded_block(level);
    let e_star = E / (1.0 - NU * NU);
    let p = std::f64::consts::PI * e_star * A * A / (4.0 * R);
    let text = format!(
        r#"{}
[solver]
steps = 2
tolerance = 1e-12
[[displacement]]
group = "Bottom"
dy = 0.0
[[displacement]]
group = "Left"
dx = 0.0
[[rigid]]
name = "cylinder"
circle = {{ center = [0.0, {R}], radius = {R} }}
reference = [0.0, {R}]
fy = {fy}
[[contact]]
slave = "Top"
master = "cylinder"
formulation = "{formulation}"
{integration}"#,
        case_head(&[("Body", E, NU)]),
        fy = -0.5 * p,
        // (nodal pressures: Gauss points would spread some onto the first open node)
        integration = if formulation == "mortar" {
            ""
        } else {
            "integration = \"nodal\"\n"
        }
    );
    let case: CaseFile = toml::from_str(&text).unwrap();
    let out = run(&case, &mesh, false).unwrap_or_else(|e| panic!("{formulation}: {e}"));
    let p0 = e_star * A / (2.0 * R);
    let nodes = &out.contact[0].nodes;
    let peak = nodes.iter().map(|c| c.pressure).fold(0.0, f64::max);
    let edge = nodes
        .iter()
        .filter(|c| c.pressure > 0.0)
        .map(|c| mesh.coords[c.node][0])
        .fold(0.0, f64::max);
    let h = 1.25 / f64::from(1u32 << level);
    let balance = (out.rigid[0].reaction[1] + 0.5 * p).abs() / (0.5 * p);
    (peak / p0 - 1.0, edge - A, h, balance)
}

#[test]
fn rigid_cylinder_on_a_block_matches_hertz() {
    for formulation in ["mortar", "point-to-segment"] {
        let (e5, d5, h5, b5) = indent(5, formulation);
        let (e6, d6, h6, b6) = indent(6, formulation);
        println!(
            "{formulation}: h = a/{:.1}: p0 error {e5:+.4}, edge - a = {d5:+.4} (h {h5}); \
             h = a/{:.1}: p0 error {e6:+.4}, edge - a = {d6:+.4} (h {h6}); balance {b5:.1e} {b6:.1e}",
            A / h5,
            A / h6
        );
        assert!(b5 < 1e-8 && b6 < 1e-8, "{formulation}: load balance");
        assert!(
            e5.abs() < 0.01 && e6.abs() < 0.01,
            "{formulation}: p0 off by {e5}, {e6}"
        );
        assert!((e6 - e5).abs() < 0.005, "{formulation}: not converged in h");
        assert!(
            d5.abs() <= h5 && d6.abs() <= h6,
            "{formulation}: contact edge off"
        );
    }
}
