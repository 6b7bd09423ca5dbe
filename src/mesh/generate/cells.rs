//! Cell builders shared by the generators: quadtree cells through a map, plain cells,
//! boundary edge groups and point groups.

use super::super::builder::MeshBuilder;
use super::super::fasthash::FastMap;
use super::super::quadtree::Quadtree;
use super::super::CellKind;

/// Adds the cells of a quadtree (through `map`) to the builder; returns lattice → node.
pub(super) fn add_tree_cells(
    b: &mut MeshBuilder,
    tree: &Quadtree,
    map: &dyn Fn([f64; 2]) -> [f64; 2],
    quadratic: bool,
    group: &str,
    mids: &mut FastMap<(usize, usize), usize>,
) -> FastMap<(u64, u64), usize> {
    // about one corner node per leaf, two sides per cell: sized once, never rehashed
    let leaves = tree.num_leaves();
    let mut nodes: FastMap<(u64, u64), usize> = FastMap::default();
    nodes.reserve(leaves + leaves / 4);
    if quadratic {
        mids.reserve(3 * leaves);
    }
    tree.for_each_cell(|corners| {
        let n = corners.len();
        let mut all = [0usize; 8];
        for (k, &p) in corners.iter().enumerate() {
            all[k] = *nodes
                .entry(p)
                .or_insert_with(|| b.add_node(map(tree.param(p))));
        }
        if quadratic {
            for k in 0..n {
                let (pa, pb) = (corners[k], corners[(k + 1) % n]);
                let (ia, ib) = (all[k], all[(k + 1) % n]);
                all[n + k] = *mids.entry((ia.min(ib), ia.max(ib))).or_insert_with(|| {
                    b.add_node(map(tree.param(((pa.0 + pb.0) / 2, (pa.1 + pb.1) / 2))))
                });
            }
        }
        let kind = match (n, quadratic) {
            (4, false) => CellKind::Quad4,
            (4, true) => CellKind::Quad8,
            (_, false) => CellKind::Tri3,
            (_, true) => CellKind::Tri6,
        };
        let label = b_cells(b);
        let c = b.add_cell(kind, &all[..kind.num_nodes()], label);
        b.add_to_cell_group(group, c);
    });
    nodes
}

pub(super) fn b_cells(b: &MeshBuilder) -> u64 {
    b.num_cells() as u64 + 1
}

/// Adds a cell given by corner nodes (mid-side nodes created at straight-edge midpoints
/// unless the edge already has one).
pub(super) fn add_plain_cell(
    b: &mut MeshBuilder,
    corners: &[usize],
    quadratic: bool,
    group: &str,
    mids: &mut FastMap<(usize, usize), usize>,
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

pub(super) fn boundary_edges(b: &MeshBuilder, first_cell: usize) -> Vec<Edge> {
    let mut count: FastMap<(usize, usize), (Edge, usize)> = FastMap::default();
    count.reserve(3 * (b.num_cells() - first_cell));
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

pub(super) fn add_edge_cells<'a>(
    b: &mut MeshBuilder,
    first_cell: usize,
    classify: &dyn Fn([f64; 2], [f64; 2]) -> Vec<&'a str>,
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

pub(super) fn add_point(b: &mut MeshBuilder, group: &str, near: [f64; 2], first_node: usize) {
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
