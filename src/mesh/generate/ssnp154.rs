//! The SSNP154 geometry: an elastic block and half-cylinder, graded quadtree meshes.

use super::super::builder::MeshBuilder;
use super::super::quadtree::{Leaf, Quadtree};
use super::super::Mesh;
use super::cells::{add_edge_cells, add_plain_cell, add_point, add_tree_cells};
use crate::error::{Error, Result};
use crate::mesh::fasthash::FastMap;

#[derive(Clone, Debug)]
pub struct Ssnp154Options {
    pub quadratic: bool,
    /// Element size at the contact (mm).
    pub size: f64,
    /// Each level splits every cell in four after generation.
    pub global_refine: usize,
}

impl Default for Ssnp154Options {
    fn default() -> Self {
        Ssnp154Options {
            quadratic: false,
            size: 1.5,
            global_refine: 0,
        }
    }
}

/// The SSNP154 geometry: block [0, 100] × [-200, 0] and half disc of radius 50 centred at
/// (0, 50), x ≥ 0, touching at the origin through two distinct nodes B (block) and C
/// (cylinder). Groups as in the reference meshes: Block, Cylinder, Top_B (block top,
/// x ≤ 30), Bottom_C (arc from C to (50, 50)), Axe (x = 0), Encast (y = -200), B, C, Force.
///
/// Both bodies come from balanced quadtrees (see `quadtree.rs`), graded with the distance
/// to the contact: squares of side ≈ `size` along Top_B (exactly `size` when 48 or 50 mm is a
/// power-of-two multiple of it), arc segments ≈ 0.4 `size` at C and no longer than `size`
/// within 8 mm of C. The block's parameter plane is stretched piecewise linearly away from
/// B to fit 100 × 200; the cylinder is meshed in conformal polar coordinates (θ, log r)
/// around its centre, down to a small core filled with triangle rings.
pub fn ssnp154(o: &Ssnp154Options) -> Result<Mesh> {
    if !(0.02..=6.0).contains(&o.size) {
        return Err(Error::model(format!(
            "ssnp154 mesh: size (element size at the contact) must lie in [0.02, 6] mm, got {}",
            o.size
        )));
    }
    if o.global_refine > 6 {
        return Err(Error::model(format!(
            "ssnp154 mesh: global_refine must be at most 6, got {}",
            o.global_refine
        )));
    }
    let mut b = MeshBuilder::new("ssnp154 generator");
    ssnp154_block(&mut b, o);
    let disc = HalfDisc {
        quadratic: o.quadratic,
        size: o.size,
        global_refine: o.global_refine,
        body: "Cylinder",
        arc: "Bottom_C",
        contact_point: "C",
        far_point: "Force",
    };
    half_disc(&mut b, &disc);
    b.finish()
}

const GROWTH: f64 = 0.2;

/// Distance from C within which the arc's cells are no larger than the block's `size`: the
/// contact zone (half-width 6.2 mm) with a margin. Without it the graded arc outgrows the
/// block top there on fine meshes, and a mortar slave finer than its master oscillates
/// where the master is coarser (`tribo study hertz`, level 4: up to 3.6 % of p0 on linear
/// cells, 55 % on quadratic ones).
const CONTACT_ZONE: f64 = 8.0;

fn ssnp154_block(b: &mut MeshBuilder, o: &Ssnp154Options) {
    let h = o.size;
    // root squares of side H = h·2^k ≤ 50: at least two roots across the width
    let k = (50.0 / h).log2().floor() as u32;
    let big = h * (1u64 << k) as f64;
    let nx = ((100.0 / big).round() as u64).max(2);
    let ny = ((200.0 / big).round() as u64).max(2);
    let stretch = move |t: f64, n: u64, len: f64| {
        if t <= big {
            t
        } else {
            big + (t - big) * (len - big) / ((n - 1) as f64 * big)
        }
    };
    let top = ny as f64 * big;
    let map = move |p: [f64; 2]| [stretch(p[0], nx, 100.0), -stretch(top - p[1], ny, 200.0)];
    let mut tree = Quadtree::new(nx, ny, big);
    tree.refine(k, &|t, leaf| {
        let (x0, y0, s) = t.bbox(leaf);
        let lo = map([x0, y0 + s]);
        let hi = map([x0 + s, y0]);
        let (xmin, xmax, ymin, ymax) = (lo[0], hi[0], hi[1].min(lo[1]), hi[1].max(lo[1]));
        let size = (xmax - xmin).max(ymax - ymin);
        let d = (xmin - 30.0).max(0.0).hypot((-ymax).max(0.0));
        size > h + GROWTH * d + 1e-9
    });
    tree.balance();
    for _ in 0..o.global_refine {
        for l in tree.leaves() {
            tree.split(l);
        }
    }
    let first_node = b.num_nodes();
    let first_cell = b.num_cells();
    let mut mids = FastMap::default();
    add_tree_cells(b, &tree, &map, o.quadratic, "Block", &mut mids);
    add_edge_cells(b, first_cell, &|p, q| {
        let mut g = vec![];
        if p[0].abs() < 1e-9 && q[0].abs() < 1e-9 {
            g.push("Axe");
        }
        if p[1].abs() < 1e-9 && q[1].abs() < 1e-9 && p[0].max(q[0]) <= 30.0 + 1e-9 {
            g.push("Top_B");
        }
        if (p[1] + 200.0).abs() < 1e-9 && (q[1] + 200.0).abs() < 1e-9 {
            g.push("Encast");
        }
        g
    });
    add_point(b, "B", [0.0, 0.0], first_node);
}

/// A half disc of radius 50 centred at (0, 50), x ≥ 0, resting on the origin: its cells
/// (group `body`), the lower quarter arc (`arc`), the edges on x = 0 (`Axe`) and the points
/// at the origin (`contact_point`) and at the top (`far_point`).
pub(super) struct HalfDisc<'a> {
    pub quadratic: bool,
    /// element size at the contact (the arc's cells are ≈ 0.4 of it at the origin)
    pub size: f64,
    pub global_refine: usize,
    pub body: &'a str,
    pub arc: &'a str,
    pub contact_point: &'a str,
    pub far_point: &'a str,
}

pub(super) fn half_disc(b: &mut MeshBuilder, o: &HalfDisc) {
    use std::f64::consts::PI;
    let r0 = 50.0;
    let centre = [0.0, 50.0];
    let hc = 0.4 * o.size;
    // parameters u = R(θ + π/2) ∈ [0, πR] (C at u = 0), v = R ln(R/r) ∈ [0, πR/2]:
    // 4 × 2 root squares of side πR/4; the core r < R e^{-π/2} ≈ 10.4 is filled separately.
    let big = PI * r0 / 4.0;
    let k = (big / hc).log2().round().max(1.0) as u32;
    let map = move |p: [f64; 2]| {
        let r = r0 * (-p[1] / r0).exp();
        let th = p[0] / r0 - PI / 2.0;
        [r * th.cos(), centre[1] + r * th.sin()]
    };
    let vmax = 2.0 * big;
    let touches_core = move |t: &Quadtree, leaf: Leaf| {
        let (_, y0, s) = t.bbox(leaf);
        (y0 + s - vmax).abs() < 1e-9 * vmax
    };
    let mut tree = Quadtree::new(4, 2, big);
    tree.refine(k, &|t, leaf| {
        let (x0, y0, s) = t.bbox(leaf);
        if touches_core(t, leaf) {
            return leaf.0 == 0;
        }
        let pts: [[f64; 2]; 8] = [
            (0.0, 0.0),
            (1.0, 0.0),
            (1.0, 1.0),
            (0.0, 1.0),
            (0.5, 0.0),
            (0.5, 1.0),
            (0.0, 0.5),
            (1.0, 0.5),
        ]
        .map(|(a, c)| map([x0 + a * s, y0 + c * s]));
        let size = (pts[0][0] - pts[1][0])
            .hypot(pts[0][1] - pts[1][1])
            .max((pts[0][0] - pts[3][0]).hypot(pts[0][1] - pts[3][1]));
        let d = pts
            .iter()
            .map(|p| p[0].hypot(p[1]))
            .fold(f64::INFINITY, f64::min);
        size > hc + GROWTH * d + 1e-9 || (d < CONTACT_ZONE && size > o.size + 1e-9)
    });
    // Core ring: every leaf touching the core at one level, then balance, until stable.
    loop {
        tree.balance();
        let ring: Vec<Leaf> = tree
            .leaves()
            .into_iter()
            .filter(|&l| touches_core(&tree, l))
            .collect();
        let top = ring.iter().map(|l| l.0).max().unwrap_or(0);
        let coarse: Vec<Leaf> = ring.into_iter().filter(|l| l.0 < top).collect();
        if coarse.is_empty() {
            break;
        }
        for l in coarse {
            tree.split(l);
        }
    }
    for _ in 0..o.global_refine {
        for l in tree.leaves() {
            tree.split(l);
        }
    }
    let first_node = b.num_nodes();
    let first_cell = b.num_cells();
    let mut mids = FastMap::default();
    let lattice = add_tree_cells(b, &tree, &map, o.quadratic, o.body, &mut mids);
    // Core: rings of triangles halving the node count down to 5 nodes, then a fan.
    let vmax_lattice = lattice.keys().map(|p| p.1).max().unwrap();
    let mut ring: Vec<(u64, usize)> = lattice
        .iter()
        .filter(|(p, _)| p.1 == vmax_lattice)
        .map(|(p, &n)| (p.0, n))
        .collect();
    ring.sort_unstable();
    let mut ring: Vec<usize> = ring.into_iter().map(|r| r.1).collect();
    let mut radius = r0 * (-vmax / r0).exp();
    while ring.len() > 5 && (ring.len() - 1).is_multiple_of(2) {
        // radial gap ≈ 1.3 × the outer spacing keeps the transition triangles above 30°
        let spacing = PI / (ring.len() - 1) as f64;
        radius *= 1.0 - 1.3 * spacing;
        let inner: Vec<usize> = ring
            .iter()
            .step_by(2)
            .map(|&n| {
                let p = b.coords()[n];
                let (dx, dy) = (p[0] - centre[0], p[1] - centre[1]);
                let f = radius / dx.hypot(dy);
                b.add_node([centre[0] + f * dx, centre[1] + f * dy])
            })
            .collect();
        for s in 0..inner.len() - 1 {
            let (a, m, z) = (ring[2 * s], ring[2 * s + 1], ring[2 * s + 2]);
            let (ia, iz) = (inner[s], inner[s + 1]);
            add_plain_cell(b, &[ia, a, m], o.quadratic, o.body, &mut mids);
            add_plain_cell(b, &[ia, m, iz], o.quadratic, o.body, &mut mids);
            add_plain_cell(b, &[iz, m, z], o.quadratic, o.body, &mut mids);
        }
        ring = inner;
    }
    let o_node = b.add_node(centre);
    for s in 0..ring.len() - 1 {
        add_plain_cell(
            b,
            &[o_node, ring[s], ring[s + 1]],
            o.quadratic,
            o.body,
            &mut mids,
        );
    }
    add_edge_cells(b, first_cell, &|p, q| {
        let mut g = vec![];
        if p[0].abs() < 1e-9 && q[0].abs() < 1e-9 {
            g.push("Axe");
        }
        let on_arc = |x: [f64; 2]| ((x[0] - centre[0]).hypot(x[1] - centre[1]) - r0).abs() < 1e-9;
        if on_arc(p) && on_arc(q) && p[1].max(q[1]) <= centre[1] + 1e-9 {
            g.push(o.arc);
        }
        g
    });
    add_point(b, o.contact_point, [0.0, 0.0], first_node);
    add_point(b, o.far_point, [0.0, 100.0], first_node);
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn check_ssnp154(o: &Ssnp154Options) -> Mesh {
        let m = ssnp154(o).unwrap();
        let what = format!("{o:?}");
        assert_eq!(m.reoriented, 0, "{what}");
        for g in [
            "Block", "Cylinder", "Top_B", "Bottom_C", "Axe", "Encast", "B", "C", "Force",
        ] {
            assert!(!m.cell_group(g).unwrap().is_empty(), "{what}: group {g}");
        }
        let (b, c) = (m.single_node("B").unwrap(), m.single_node("C").unwrap());
        assert_ne!(b, c);
        assert_eq!(m.coords[b], [0.0, 0.0]);
        assert!(m.coords[c][0].abs() < 1e-12 && m.coords[c][1].abs() < 1e-12);
        let f = m.coords[m.single_node("Force").unwrap()];
        assert!(f[0].abs() < 1e-12 && (f[1] - 100.0).abs() < 1e-12);
        // Top_B: edges of ~size (exact when 48 mm is a power-of-two multiple) up to x = 30
        let top: Vec<f64> = m
            .cell_group("Top_B")
            .unwrap()
            .iter()
            .map(|&e| {
                let n = m.cell_nodes(e);
                (m.coords[n[0]][0] - m.coords[n[1]][0]).abs()
            })
            .collect();
        let h_top = top.iter().cloned().fold(0.0, f64::max);
        let h = o.size / (1u64 << o.global_refine) as f64;
        assert!(
            h_top <= h * 1.0001 && h_top >= 0.5 * h,
            "{what}: Top_B edge {h_top}"
        );
        // Bottom_C: corners on the circle; the edge at C about 0.4 size, no edge longer than
        // size within the contact zone
        let h_refined = o.size / (1u64 << o.global_refine) as f64;
        for &e in m.cell_group("Bottom_C").unwrap() {
            for &n in m.cell_nodes(e) {
                let x = m.coords[n];
                assert!((x[0].hypot(x[1] - 50.0) - 50.0).abs() < 1e-9, "{what}");
            }
            let n = m.cell_nodes(e);
            let l = (m.coords[n[0]][0] - m.coords[n[1]][0])
                .hypot(m.coords[n[0]][1] - m.coords[n[1]][1]);
            if n[..2].contains(&c) {
                let expect = 0.4 * h_refined;
                assert!((l / expect - 1.0).abs() < 0.35, "{what}: edge at C {l}");
            }
            if n[..2]
                .iter()
                .all(|&k| m.coords[k][0].hypot(m.coords[k][1]) < CONTACT_ZONE)
            {
                assert!(
                    l <= h_refined * 1.0001,
                    "{what}: arc edge {l} in the contact zone"
                );
            }
        }
        // Bodies share no node; every side is shared by two cells or lies on the boundary.
        let block: std::collections::HashSet<usize> =
            m.node_group("Block").unwrap().into_iter().collect();
        assert!(m
            .node_group("Cylinder")
            .unwrap()
            .iter()
            .all(|n| !block.contains(n)));
        let mut sides: HashMap<(usize, usize), usize> = HashMap::new();
        for c in m.cells_of_dim(2) {
            let nodes = m.cell_nodes(c);
            for e in m.kind(c).edges() {
                let (a, z) = (nodes[e[0]], nodes[e[1]]);
                *sides.entry((a.min(z), a.max(z))).or_insert(0) += 1;
            }
        }
        for (&(a, z), &count) in &sides {
            assert!(count <= 2, "{what}: side shared by {count} cells");
            if count == 1 {
                let (p, q) = (m.coords[a], m.coords[z]);
                let on = |x: [f64; 2]| {
                    x[0].abs() < 1e-9
                        || (x[0] - 100.0).abs() < 1e-9
                        || (x[1] + 200.0).abs() < 1e-9
                        || (x[1].abs() < 1e-9 && x[0] >= 0.0)
                        || (x[0].hypot(x[1] - 50.0) - 50.0).abs() < 1e-9
                };
                assert!(
                    on(p) && on(q),
                    "{what}: interior side ({p:?}, {q:?}) used once: not conforming"
                );
            }
        }
        // Areas: block exact; the cylinder's polygonal arc loses a little (linear).
        let cyl_exact = std::f64::consts::PI * 2500.0 / 2.0;
        let (mut ab, mut ac) = (0.0, 0.0);
        let blk: std::collections::HashSet<usize> =
            m.cell_group("Block").unwrap().iter().copied().collect();
        for c in m.cells_of_dim(2) {
            let kind = m.kind(c);
            let (x, nn) = m.cell_coords(c);
            let rule = crate::fem::quadrature::exact_to_degree(kind, 8);
            let a: f64 = rule
                .points
                .iter()
                .zip(&rule.weights)
                .map(|(&xi, w)| w * crate::fem::element::jacobian_det(kind, &x[..nn], xi))
                .sum();
            if blk.contains(&c) {
                ab += a;
            } else {
                ac += a;
            }
        }
        assert!((ab - 20000.0).abs() < 1e-8, "{what}: block area {ab}");
        if o.quadratic {
            assert!(
                (ac - cyl_exact).abs() < 1e-5 * cyl_exact,
                "{what}: cylinder area {ac}"
            );
        } else {
            // chords of the arc: the half disc minus one circular segment per arc side
            let on_arc = |x: [f64; 2]| (x[0].hypot(x[1] - 50.0) - 50.0).abs() < 1e-9;
            let lost: f64 = sides
                .iter()
                .filter(|(&(a, z), &count)| {
                    count == 1 && on_arc(m.coords[a]) && on_arc(m.coords[z])
                })
                .map(|(&(a, z), _)| {
                    let (p, q) = (m.coords[a], m.coords[z]);
                    let phi = 2.0 * ((p[0] - q[0]).hypot(p[1] - q[1]) / 100.0).asin();
                    1250.0 * (phi - phi.sin())
                })
                .sum();
            assert!(
                (ac - (cyl_exact - lost)).abs() < 1e-9 * cyl_exact,
                "{what}: cylinder area {ac}"
            );
        }
        let q = crate::mesh::quality::quality(&m).unwrap();
        assert!(
            q.min_angle_deg >= 30.0,
            "{what}: min angle {}",
            q.min_angle_deg
        );
        assert!(
            q.max_aspect_ratio <= 5.0,
            "{what}: aspect {}",
            q.max_aspect_ratio
        );
        m
    }

    #[test]
    fn ssnp154_meshes_are_conforming_graded_and_of_good_quality() {
        for quadratic in [false, true] {
            for size in [3.0, 1.5, 0.75, 0.375] {
                let m = check_ssnp154(&Ssnp154Options {
                    quadratic,
                    size,
                    global_refine: 0,
                });
                if size == 1.5 && !quadratic {
                    let counts = m.kind_counts();
                    println!("default linear: {} nodes, {counts:?}", m.num_nodes());
                }
            }
        }
        let fine = check_ssnp154(&Ssnp154Options {
            quadratic: false,
            size: 1.5,
            global_refine: 1,
        });
        assert!(fine.num_nodes() > 3 * check_ssnp154(&Ssnp154Options::default()).num_nodes());
    }
}
