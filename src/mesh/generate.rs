//! Built-in meshes: the SSNP154 geometry at any refinement, rectangles and rings.

use super::builder::MeshBuilder;
use super::quadtree::{Leaf, Quadtree};
use super::{CellKind, Mesh};
use crate::error::{Error, Result};
use std::collections::HashMap;

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
    ssnp154_cylinder(&mut b, o);
    b.finish()
}

/// Adds the cells of a quadtree (through `map`) to the builder; returns lattice → node.
fn add_tree_cells(
    b: &mut MeshBuilder,
    tree: &Quadtree,
    map: &dyn Fn([f64; 2]) -> [f64; 2],
    quadratic: bool,
    group: &str,
    mids: &mut HashMap<(usize, usize), usize>,
) -> HashMap<(u64, u64), usize> {
    let mut nodes: HashMap<(u64, u64), usize> = HashMap::new();
    let mut node = |b: &mut MeshBuilder, p: (u64, u64)| {
        *nodes
            .entry(p)
            .or_insert_with(|| b.add_node(map(tree.param(p))))
    };
    for corners in tree.cells() {
        let ids: Vec<usize> = corners.iter().map(|&p| node(b, p)).collect();
        let n = ids.len();
        let mut all = ids.clone();
        if quadratic {
            for k in 0..n {
                let (pa, pb) = (corners[k], corners[(k + 1) % n]);
                let key = (ids[k].min(ids[(k + 1) % n]), ids[k].max(ids[(k + 1) % n]));
                let m = *mids.entry(key).or_insert_with(|| {
                    b.add_node(map(tree.param(((pa.0 + pb.0) / 2, (pa.1 + pb.1) / 2))))
                });
                all.push(m);
            }
        }
        let kind = match (n, quadratic) {
            (4, false) => CellKind::Quad4,
            (4, true) => CellKind::Quad8,
            (_, false) => CellKind::Tri3,
            (_, true) => CellKind::Tri6,
        };
        let label = b_cells(b);
        let c = b.add_cell(kind, &all, label);
        b.add_to_cell_group(group, c);
    }
    nodes
}

fn b_cells(b: &MeshBuilder) -> u64 {
    b.num_cells() as u64 + 1
}

/// Adds a cell given by corner nodes (mid-side nodes created at straight-edge midpoints
/// unless the edge already has one).
fn add_plain_cell(
    b: &mut MeshBuilder,
    corners: &[usize],
    quadratic: bool,
    group: &str,
    mids: &mut HashMap<(usize, usize), usize>,
) {
    let n = corners.len();
    let mut all = corners.to_vec();
    if quadratic {
        for k in 0..n {
            let (a, c) = (corners[k], corners[(k + 1) % n]);
            let m = *mids.entry((a.min(c), a.max(c))).or_insert_with(|| {
                let (pa, pc) = (b.coords()[a], b.coords()[c]);
                b.add_node([0.5 * (pa[0] + pc[0]), 0.5 * (pa[1] + pc[1])])
            });
            all.push(m);
        }
    }
    let kind = match (n, quadratic) {
        (4, false) => CellKind::Quad4,
        (4, true) => CellKind::Quad8,
        (_, false) => CellKind::Tri3,
        (_, true) => CellKind::Tri6,
    };
    let label = b_cells(b);
    let c = b.add_cell(kind, &all, label);
    b.add_to_cell_group(group, c);
}

/// Boundary edges (sides of exactly one 2D cell) among `cells`, as (corner a, corner b, mid).
/// An edge as (corner, corner, mid-side node).
type Edge = (usize, usize, Option<usize>);

fn boundary_edges(b: &MeshBuilder, first_cell: usize) -> Vec<Edge> {
    let mut count: HashMap<(usize, usize), (Edge, usize)> = HashMap::new();
    for c in first_cell..b.num_cells() {
        let (kind, nodes) = b.cell(c);
        for e in kind.edges() {
            let (a, z) = (nodes[e[0]], nodes[e[1]]);
            let m = e.get(2).map(|&k| nodes[k]);
            count
                .entry((a.min(z), a.max(z)))
                .or_insert(((a, z, m), 0))
                .1 += 1;
        }
    }
    let mut out: Vec<Edge> = count
        .into_values()
        .filter(|v| v.1 == 1)
        .map(|v| v.0)
        .collect();
    out.sort_unstable();
    out
}

fn add_edge_cells(
    b: &mut MeshBuilder,
    first_cell: usize,
    classify: &dyn Fn([f64; 2], [f64; 2]) -> Vec<&'static str>,
) {
    for (a, z, m) in boundary_edges(b, first_cell) {
        let groups = classify(b.coords()[a], b.coords()[z]);
        if groups.is_empty() {
            continue;
        }
        let (kind, nodes) = match m {
            Some(m) => (CellKind::Seg3, vec![a, z, m]),
            None => (CellKind::Seg2, vec![a, z]),
        };
        let label = b_cells(b);
        let c = b.add_cell(kind, &nodes, label);
        for g in groups {
            b.add_to_cell_group(g, c);
        }
    }
}

fn add_point(b: &mut MeshBuilder, group: &str, near: [f64; 2], first_node: usize) {
    let n = (first_node..b.num_nodes())
        .min_by(|&i, &j| {
            let (p, q) = (b.coords()[i], b.coords()[j]);
            let dp = (p[0] - near[0]).hypot(p[1] - near[1]);
            let dq = (q[0] - near[0]).hypot(q[1] - near[1]);
            dp.total_cmp(&dq)
        })
        .expect("body has nodes");
    let label = b_cells(b);
    let c = b.add_cell(CellKind::Point1, &[n], label);
    b.add_to_cell_group(group, c);
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
        let leaves: Vec<Leaf> = tree.leaves.iter().copied().collect();
        for l in leaves {
            tree.split(l);
        }
    }
    let first_node = b.num_nodes();
    let first_cell = b.num_cells();
    let mut mids = HashMap::new();
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

fn ssnp154_cylinder(b: &mut MeshBuilder, o: &Ssnp154Options) {
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
        let pts: Vec<[f64; 2]> = [
            (0.0, 0.0),
            (1.0, 0.0),
            (1.0, 1.0),
            (0.0, 1.0),
            (0.5, 0.0),
            (0.5, 1.0),
            (0.0, 0.5),
            (1.0, 0.5),
        ]
        .iter()
        .map(|&(a, c)| map([x0 + a * s, y0 + c * s]))
        .collect();
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
            .leaves
            .iter()
            .copied()
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
        let leaves: Vec<Leaf> = tree.leaves.iter().copied().collect();
        for l in leaves {
            tree.split(l);
        }
    }
    let first_node = b.num_nodes();
    let first_cell = b.num_cells();
    let mut mids = HashMap::new();
    let lattice = add_tree_cells(b, &tree, &map, o.quadratic, "Cylinder", &mut mids);
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
            add_plain_cell(b, &[ia, a, m], o.quadratic, "Cylinder", &mut mids);
            add_plain_cell(b, &[ia, m, iz], o.quadratic, "Cylinder", &mut mids);
            add_plain_cell(b, &[iz, m, z], o.quadratic, "Cylinder", &mut mids);
        }
        ring = inner;
    }
    let o_node = b.add_node(centre);
    for s in 0..ring.len() - 1 {
        add_plain_cell(
            b,
            &[o_node, ring[s], ring[s + 1]],
            o.quadratic,
            "Cylinder",
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
            g.push("Bottom_C");
        }
        g
    });
    add_point(b, "C", [0.0, 0.0], first_node);
    add_point(b, "Force", [0.0, 100.0], first_node);
}

/// Structured grid of nx × ny cells of `kind` over a parametric square mapped by `map`
/// (s, t) ∈ [0,1]² → (x, y); `mid` places mid-side nodes from the parametric midpoint.
/// Edge groups Bottom (t=0), Right (s=1), Top (t=1), Left (s=0); corner point groups.
fn grid(
    nx: usize,
    ny: usize,
    kind: CellKind,
    map: &dyn Fn(f64, f64) -> [f64; 2],
    source: &str,
) -> Result<Mesh> {
    if nx == 0 || ny == 0 {
        return Err(Error::model(format!(
            "{source}: cell counts must be positive, got {nx} x {ny}"
        )));
    }
    if kind.dim() != 2 {
        return Err(Error::model(format!(
            "{source}: cell kind {kind} is not a 2D kind (Tri3, Tri6, Quad4, Quad8)"
        )));
    }
    let quadratic = kind.is_quadratic();
    let mut b = MeshBuilder::new(source);
    let mut corner = vec![vec![0usize; ny + 1]; nx + 1];
    for (i, col) in corner.iter_mut().enumerate() {
        for (j, slot) in col.iter_mut().enumerate() {
            *slot = b.add_node(map(i as f64 / nx as f64, j as f64 / ny as f64));
        }
    }
    // mid-side nodes keyed by the doubled parametric grid position
    let mut mids: HashMap<(usize, usize), usize> = HashMap::new();
    let mut mid = |b: &mut MeshBuilder, i2: usize, j2: usize| -> usize {
        *mids.entry((i2, j2)).or_insert_with(|| {
            b.add_node(map(
                i2 as f64 / (2 * nx) as f64,
                j2 as f64 / (2 * ny) as f64,
            ))
        })
    };
    let mut label = 1;
    for i in 0..nx {
        for j in 0..ny {
            let (n0, n1, n2, n3) = (
                corner[i][j],
                corner[i + 1][j],
                corner[i + 1][j + 1],
                corner[i][j + 1],
            );
            let cells: Vec<(CellKind, Vec<usize>)> = match kind {
                CellKind::Quad4 => vec![(kind, vec![n0, n1, n2, n3])],
                CellKind::Quad8 => {
                    let m = [
                        mid(&mut b, 2 * i + 1, 2 * j),
                        mid(&mut b, 2 * i + 2, 2 * j + 1),
                        mid(&mut b, 2 * i + 1, 2 * j + 2),
                        mid(&mut b, 2 * i, 2 * j + 1),
                    ];
                    vec![(kind, vec![n0, n1, n2, n3, m[0], m[1], m[2], m[3]])]
                }
                CellKind::Tri3 => vec![(kind, vec![n0, n1, n2]), (kind, vec![n0, n2, n3])],
                _ => {
                    let m01 = mid(&mut b, 2 * i + 1, 2 * j);
                    let m12 = mid(&mut b, 2 * i + 2, 2 * j + 1);
                    let m23 = mid(&mut b, 2 * i + 1, 2 * j + 2);
                    let m30 = mid(&mut b, 2 * i, 2 * j + 1);
                    let mc = mid(&mut b, 2 * i + 1, 2 * j + 1);
                    vec![
                        (kind, vec![n0, n1, n2, m01, m12, mc]),
                        (kind, vec![n0, n2, n3, mc, m23, m30]),
                    ]
                }
            };
            for (k, nodes) in cells {
                let c = b.add_cell(k, &nodes, label);
                label += 1;
                b.add_to_cell_group("Body", c);
            }
        }
    }
    let edge = if quadratic {
        CellKind::Seg3
    } else {
        CellKind::Seg2
    };
    let add_edge = |b: &mut MeshBuilder,
                    group: &str,
                    a: usize,
                    c: usize,
                    m: Option<usize>,
                    label: &mut u64| {
        let nodes: Vec<usize> = match m {
            Some(m) => vec![a, c, m],
            None => vec![a, c],
        };
        let cell = b.add_cell(edge, &nodes, *label);
        *label += 1;
        b.add_to_cell_group(group, cell);
    };
    for i in 0..nx {
        let m = quadratic.then(|| mid(&mut b, 2 * i + 1, 0));
        add_edge(
            &mut b,
            "Bottom",
            corner[i][0],
            corner[i + 1][0],
            m,
            &mut label,
        );
        let m = quadratic.then(|| mid(&mut b, 2 * i + 1, 2 * ny));
        add_edge(
            &mut b,
            "Top",
            corner[i + 1][ny],
            corner[i][ny],
            m,
            &mut label,
        );
    }
    for j in 0..ny {
        let m = quadratic.then(|| mid(&mut b, 2 * nx, 2 * j + 1));
        add_edge(
            &mut b,
            "Right",
            corner[nx][j],
            corner[nx][j + 1],
            m,
            &mut label,
        );
        let m = quadratic.then(|| mid(&mut b, 0, 2 * j + 1));
        add_edge(
            &mut b,
            "Left",
            corner[0][j + 1],
            corner[0][j],
            m,
            &mut label,
        );
    }
    for (name, n) in [
        ("BottomLeft", corner[0][0]),
        ("BottomRight", corner[nx][0]),
        ("TopRight", corner[nx][ny]),
        ("TopLeft", corner[0][ny]),
    ] {
        let c = b.add_cell(CellKind::Point1, &[n], label);
        label += 1;
        b.add_to_cell_group(name, c);
    }
    b.finish()
}

/// Deterministic pseudo-random number in [-1, 1] from two indices.
fn wiggle(i: u64, j: u64, salt: u64) -> f64 {
    let mut h = i.wrapping_mul(0x9E3779B97F4A7C15) ^ j.wrapping_mul(0xC2B2AE3D27D4EB4F) ^ salt;
    h ^= h >> 31;
    h = h.wrapping_mul(0xBF58476D1CE4E5B9);
    h ^= h >> 29;
    (h % 2_000_001) as f64 / 1_000_000.0 - 1.0
}

/// Rectangle [x0, x0 + width] × [y0, y0 + height] in nx × ny cells (Tri kinds: each
/// square split in two). `distortion` < 0.3 moves interior grid points pseudo-randomly by up
/// to that fraction of a cell (boundary points along their side only); cells stay straight-sided.
pub fn rectangle(
    origin: [f64; 2],
    width: f64,
    height: f64,
    nx: usize,
    ny: usize,
    kind: CellKind,
    distortion: f64,
) -> Result<Mesh> {
    if !(width > 0.0 && height > 0.0) {
        return Err(Error::model(format!(
            "rectangle: width and height must be positive, got {width} x {height}"
        )));
    }
    if !(0.0..0.3).contains(&distortion) {
        return Err(Error::model(format!(
            "rectangle: distortion must lie in [0, 0.3), got {distortion}"
        )));
    }
    let (hx, hy) = (1.0 / nx.max(1) as f64, 1.0 / ny.max(1) as f64);
    let map = |s: f64, t: f64| -> [f64; 2] {
        // Distort the corner grid only (mid-side points interpolate their corners).
        let (fi, fj) = (s / hx, t / hy);
        let on_grid = |f: f64| (f - f.round()).abs() < 1e-9;
        let (mut ss, mut tt) = (s, t);
        if distortion > 0.0 {
            let corner = |fi: f64, fj: f64| -> [f64; 2] {
                let (i, j) = (fi.round() as u64, fj.round() as u64);
                let mut c = [fi * hx, fj * hy];
                let interior_s = i > 0 && i < nx as u64;
                let interior_t = j > 0 && j < ny as u64;
                if interior_s {
                    c[0] += distortion * hx * wiggle(i, j, 1);
                }
                if interior_t {
                    c[1] += distortion * hy * wiggle(i, j, 2);
                }
                c
            };
            if on_grid(fi) && on_grid(fj) {
                [ss, tt] = corner(fi, fj);
            } else {
                // a mid-side point (or the Tri6 diagonal's, (i0,j0)-(i1,j1)) sits halfway
                // between its two grid corners, keeping the sides straight
                let span = |f: f64| {
                    if on_grid(f) {
                        (f.round(), f.round())
                    } else {
                        (f.floor(), f.ceil())
                    }
                };
                let ((i0, i1), (j0, j1)) = (span(fi), span(fj));
                let (p, q) = (corner(i0, j0), corner(i1, j1));
                [ss, tt] = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
            }
        }
        [origin[0] + width * ss, origin[1] + height * tt]
    };
    grid(nx, ny, kind, &map, "rectangle")
}

/// Annular sector r ∈ [r_in, r_out], θ ∈ [0, angle] degrees, n_r × n_theta cells; every
/// node (mid-side ones too) is placed in polar coordinates, so curved sides follow the
/// circles. Edge groups Inner, Outer, Start (θ = 0), End (θ = angle).
pub fn ring(
    r_in: f64,
    r_out: f64,
    n_r: usize,
    n_theta: usize,
    angle_deg: f64,
    kind: CellKind,
) -> Result<Mesh> {
    if !(r_in > 0.0 && r_out > r_in) {
        return Err(Error::model(format!(
            "ring: need 0 < r_in < r_out, got r_in = {r_in}, r_out = {r_out}"
        )));
    }
    if !(angle_deg > 0.0 && angle_deg < 360.0) {
        return Err(Error::model(format!(
            "ring: angle must lie in (0, 360) degrees, got {angle_deg}"
        )));
    }
    let a = angle_deg.to_radians();
    let map = |s: f64, t: f64| -> [f64; 2] {
        let r = r_in + (r_out - r_in) * s;
        let th = a * t;
        [r * th.cos(), r * th.sin()]
    };
    let m = grid(n_r, n_theta, kind, &map, "ring")?;
    // grid names: s = radius, t = angle → Left = inner, Right = outer, Bottom = start, Top = end
    let mut b = MeshBuilder::new("ring");
    b.append(&m, |g| {
        match g {
            "Left" => "Inner",
            "Right" => "Outer",
            "Bottom" => "Start",
            "Top" => "End",
            other => other,
        }
        .to_string()
    });
    b.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(m: &Mesh) -> f64 {
        let mut total = 0.0;
        for c in m.cells_of_dim(2) {
            let kind = m.kind(c);
            let (x, nn) = m.cell_coords(c);
            let rule = crate::fem::quadrature::exact_to_degree(kind, 8);
            for (q, &xi) in rule.points.iter().enumerate() {
                total += rule.weights[q] * crate::fem::element::jacobian_det(kind, &x[..nn], xi);
            }
        }
        total
    }

    #[test]
    fn rectangle_areas_and_groups() {
        for kind in [
            CellKind::Tri3,
            CellKind::Tri6,
            CellKind::Quad4,
            CellKind::Quad8,
        ] {
            let m = rectangle([1.0, 2.0], 3.0, 2.0, 6, 4, kind, 0.2).unwrap();
            assert!((area(&m) - 6.0).abs() < 1e-12, "{kind}");
            assert_eq!(m.cell_group("Bottom").unwrap().len(), 6);
            assert_eq!(m.cell_group("Left").unwrap().len(), 4);
            assert_eq!(
                m.node_group("Bottom").unwrap().len(),
                if kind.is_quadratic() { 13 } else { 7 }
            );
            assert_eq!(m.coords[m.single_node("TopRight").unwrap()], [4.0, 4.0]);
            assert_eq!(m.reoriented, 0);
        }
    }

    #[test]
    fn ring_areas_and_groups() {
        let exact = std::f64::consts::PI / 4.0 * (4.0 - 1.0);
        let lin = ring(1.0, 2.0, 4, 16, 90.0, CellKind::Quad4).unwrap();
        assert!((area(&lin) - exact).abs() < 2e-2 * exact);
        for kind in [CellKind::Quad8, CellKind::Tri6] {
            let quad = ring(1.0, 2.0, 4, 16, 90.0, kind).unwrap();
            assert!(
                (area(&quad) - exact).abs() < 1e-5 * exact,
                "{kind}: {}",
                area(&quad)
            );
            for n in quad.node_group("Inner").unwrap() {
                let x = quad.coords[n];
                assert!((x[0].hypot(x[1]) - 1.0).abs() < 1e-14);
            }
        }
        assert_eq!(lin.cell_group("Outer").unwrap().len(), 16);
        assert_eq!(lin.cell_group("Start").unwrap().len(), 4);
    }

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

    #[test]
    fn bad_arguments_are_errors() {
        assert!(rectangle([0.0, 0.0], -1.0, 1.0, 2, 2, CellKind::Quad4, 0.0).is_err());
        assert!(rectangle([0.0, 0.0], 1.0, 1.0, 0, 2, CellKind::Quad4, 0.0).is_err());
        assert!(rectangle([0.0, 0.0], 1.0, 1.0, 2, 2, CellKind::Seg2, 0.0).is_err());
        assert!(ring(2.0, 1.0, 2, 2, 90.0, CellKind::Quad4).is_err());
    }
}
