//! Uniform refinement: every cell split into n × n cells of its own kind (a triangle into
//! n² triangles, a segment into n segments), groups kept (each child in its parent's
//! groups). New nodes are placed by the parent's shape functions, so curved quadratic
//! edges stay on their curves, and the original nodes keep their numbers and positions.
//!
//! Points are named on a lattice of step 1/(2n) of each parent's reference cell (half
//! steps hold quadratic children's mid-side nodes): a point on a parent vertex is that
//! vertex, one on a parent edge is (lower vertex, higher vertex, steps from the lower), so
//! the two cells sharing an edge (and the edge's own segment) create its nodes once.

use super::{CellKind, Mesh, MeshBuilder};
use crate::error::{Error, Result};
use crate::fem::element::{reference_nodes, shape, MAX_NODES};
use std::collections::HashMap;

/// Refinement factors accepted (n² times the cells: 8 already makes 64×).
pub const MAX_SPLIT: usize = 16;

#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Key {
    Vertex(usize),
    /// lower vertex, higher vertex, lattice steps from the lower (0 < k < 2n)
    Edge(usize, usize, usize),
    /// parent cell, lattice point
    Interior(usize, usize, usize),
}

/// The children of one cell as lattice points (steps of 1/(2n)) in their node order.
fn children(kind: CellKind, n: usize) -> Vec<Vec<[usize; 2]>> {
    let r = reference_nodes(kind);
    // a reference coordinate of a child node in half steps: quads and segments from −1,
    // triangles from 0
    let quad = |c: f64| (c + 1.0).round() as usize;
    let tri = |c: f64| (2.0 * c).round() as usize;
    let mut out = vec![];
    match kind {
        CellKind::Seg2 | CellKind::Seg3 => {
            for i in 0..n {
                out.push(r.iter().map(|p| [2 * i + quad(p[0]), 0]).collect());
            }
        }
        CellKind::Quad4 | CellKind::Quad8 => {
            for j in 0..n {
                for i in 0..n {
                    out.push(
                        r.iter()
                            .map(|p| [2 * i + quad(p[0]), 2 * j + quad(p[1])])
                            .collect(),
                    );
                }
            }
        }
        CellKind::Tri3 | CellKind::Tri6 => {
            for j in 0..n {
                for i in 0..n - j {
                    // upward: (i, j), (i+1, j), (i, j+1)
                    out.push(
                        r.iter()
                            .map(|p| [2 * i + tri(p[0]), 2 * j + tri(p[1])])
                            .collect(),
                    );
                    if i + j + 1 < n {
                        // downward: (i+1, j), (i+1, j+1), (i, j+1); reference (r, s)
                        // goes to V0 + r (V1 − V0) + s (V2 − V0)
                        out.push(
                            r.iter()
                                .map(|p| {
                                    let (a, c) = (tri(p[0]), tri(p[1]));
                                    [2 * i + 2 - c, 2 * j + a + c]
                                })
                                .collect(),
                        );
                    }
                }
            }
        }
        CellKind::Point1 => out.push(vec![[0, 0]]),
    }
    out
}

/// Where lattice point `p` of a parent of kind `kind` with vertices `v` lies.
fn key(kind: CellKind, cell: usize, v: &[usize], p: [usize; 2], n: usize) -> Key {
    let m = 2 * n;
    let (i, j) = (p[0], p[1]);
    // (local vertex a, local vertex b, steps from a), or a vertex, or inside
    let on: Option<(usize, usize, usize)> = match kind {
        CellKind::Seg2 | CellKind::Seg3 => Some((0, 1, i)),
        CellKind::Quad4 | CellKind::Quad8 => {
            if j == 0 {
                Some((0, 1, i))
            } else if i == m {
                Some((1, 2, j))
            } else if j == m {
                Some((2, 3, m - i))
            } else if i == 0 {
                Some((3, 0, m - j))
            } else {
                None
            }
        }
        CellKind::Tri3 | CellKind::Tri6 => {
            if j == 0 {
                Some((0, 1, i))
            } else if i + j == m {
                Some((1, 2, j))
            } else if i == 0 {
                Some((2, 0, m - j))
            } else {
                None
            }
        }
        CellKind::Point1 => return Key::Vertex(v[0]),
    };
    match on {
        Some((a, _, 0)) => Key::Vertex(v[a]),
        Some((_, b, k)) if k == m => Key::Vertex(v[b]),
        Some((a, b, k)) if v[a] < v[b] => Key::Edge(v[a], v[b], k),
        Some((a, b, k)) => Key::Edge(v[b], v[a], m - k),
        None => Key::Interior(cell, i, j),
    }
}

/// The parent's reference coordinates of lattice point p.
fn reference_point(kind: CellKind, p: [usize; 2], n: usize) -> [f64; 2] {
    let m = (2 * n) as f64;
    match kind {
        CellKind::Tri3 | CellKind::Tri6 => [p[0] as f64 / m, p[1] as f64 / m],
        _ => [2.0 * p[0] as f64 / m - 1.0, 2.0 * p[1] as f64 / m - 1.0],
    }
}

/// `mesh` with every cell split n × n (see the module header).
pub fn split(mesh: &Mesh, n: usize) -> Result<Mesh> {
    if n == 0 || n > MAX_SPLIT {
        return Err(Error::model(format!(
            "mesh refine: --split must be between 1 and {MAX_SPLIT}, got {n}"
        )));
    }
    // n² cells per 2D cell and about n² nodes per node: checked before they are made
    let n2 = (n * n) as u64;
    let cells: u64 = (0..mesh.num_cells())
        .map(|c| match mesh.kind(c).dim() {
            2 => n2,
            1 => n as u64,
            _ => 1,
        })
        .sum();
    let nodes = (mesh.num_nodes() as u64).saturating_mul(n2);
    let per_cell = mesh
        .kind_counts()
        .keys()
        .map(|k| k.num_nodes())
        .max()
        .unwrap_or(0);
    crate::memory::check(
        &format!("mesh refine --split {n} (about {nodes} nodes, {cells} cells)"),
        crate::memory::mesh_bytes(nodes, cells, per_cell),
    )?;
    let mut b = MeshBuilder::new("refined mesh");
    let mut nodes: HashMap<Key, usize> = HashMap::new();
    for (i, &x) in mesh.coords.iter().enumerate() {
        b.add_node(x);
        nodes.insert(Key::Vertex(i), i);
    }
    // a quadratic parent's mid-side nodes are its edges' middle lattice points
    for c in 0..mesh.num_cells() {
        let kind = mesh.kind(c);
        let v = mesh.cell_nodes(c);
        for (e, &[a, bv]) in kind.midside_corners().iter().enumerate() {
            let mid = v[kind.num_corners() + e];
            let (lo, hi) = (v[a].min(v[bv]), v[a].max(v[bv]));
            nodes.insert(Key::Edge(lo, hi, n), mid);
        }
    }
    let mut children_of: Vec<Vec<usize>> = vec![vec![]; mesh.num_cells()];
    for c in 0..mesh.num_cells() {
        let kind = mesh.kind(c);
        let (x, nn) = mesh.cell_coords(c);
        let v = &mesh.cell_nodes(c)[..kind.num_corners()];
        for child in children(kind, n) {
            let mut conn = Vec::with_capacity(child.len());
            for &p in &child {
                let k = key(kind, c, v, p, n);
                let id = *nodes.entry(k).or_insert_with(|| {
                    let xi = reference_point(kind, p, n);
                    let mut nv = [0.0; MAX_NODES];
                    shape(kind, xi, &mut nv);
                    let mut q = [0.0; 2];
                    for a in 0..nn {
                        q[0] += nv[a] * x[a][0];
                        q[1] += nv[a] * x[a][1];
                    }
                    b.add_node(q)
                });
                conn.push(id);
            }
            children_of[c].push(b.add_cell(kind, &conn, c as u64 + 1));
        }
    }
    for (name, cells) in &mesh.cell_groups {
        for &c in cells {
            for &k in &children_of[c] {
                b.add_to_cell_group(name, k);
            }
        }
    }
    for (name, group) in &mesh.node_groups {
        for &nd in group {
            b.add_to_node_group(name, nd);
        }
    }
    b.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::{area, rectangle, ring};

    /// Total length of an edge group.
    fn length(m: &Mesh, group: &str) -> f64 {
        let mut total = 0.0;
        for &c in m.cell_group(group).unwrap() {
            let (x, nn) = m.cell_coords(c);
            let (gp, gw) = crate::fem::quadrature::gauss_legendre(6);
            for (q, &xi) in gp.iter().enumerate() {
                let (_, t) = crate::contact::projection::point_and_tangent(m.kind(c), &x[..nn], xi);
                total += gw[q] * t[0].hypot(t[1]);
            }
        }
        total
    }

    fn distinct_nodes(m: &Mesh) -> bool {
        let mut keys: Vec<(i64, i64)> = m
            .coords
            .iter()
            .map(|x| ((x[0] * 1e9).round() as i64, (x[1] * 1e9).round() as i64))
            .collect();
        keys.sort_unstable();
        keys.windows(2).all(|w| w[0] != w[1])
    }

    /// Splitting keeps the area and the edge lengths exactly (the children reproduce the
    /// parent's map, curved quadratic sides included), shares every node once, multiplies
    /// the cells by n² (segments by n), keeps the original nodes where they were.
    #[test]
    fn split_keeps_geometry_groups_and_nodes() {
        for kind in [
            CellKind::Quad4,
            CellKind::Tri3,
            CellKind::Quad8,
            CellKind::Tri6,
        ] {
            for base in [
                rectangle([0.0, 0.0], 3.0, 2.0, 3, 2, kind, 0.2).unwrap(),
                ring(1.0, 2.0, 2, 5, 90.0, kind).unwrap(),
            ] {
                for n in 1..=4 {
                    let m = split(&base, n).unwrap();
                    let what = format!("{kind} split {n}");
                    assert!(
                        (area(&m) - area(&base)).abs() < 1e-12 * area(&base),
                        "{what}"
                    );
                    for g in base.group_names() {
                        let (b, r) = (base.cell_group(&g).unwrap(), m.cell_group(&g).unwrap());
                        let per = match base.group_dim(&g) {
                            Some(2) => n * n,
                            Some(1) => n,
                            _ => 1,
                        };
                        assert_eq!(r.len(), per * b.len(), "{what}: group {g}");
                        if base.group_dim(&g) == Some(1) {
                            let (lb, lr) = (length(&base, &g), length(&m, &g));
                            assert!((lb - lr).abs() < 1e-12 * lb, "{what}: length of {g}");
                        }
                    }
                    assert!(distinct_nodes(&m), "{what}: a node made twice");
                    assert_eq!(&m.coords[..base.num_nodes()], &base.coords[..], "{what}");
                    // every node belongs to some 2D cell
                    let mut used = vec![false; m.num_nodes()];
                    for c in m.cells_of_dim(2) {
                        for &v in m.cell_nodes(c) {
                            used[v] = true;
                        }
                    }
                    assert!(used.iter().all(|&u| u), "{what}: a node in no cell");
                }
            }
        }
    }

    #[test]
    fn a_grid_split_is_the_finer_grid() {
        let base = rectangle([0.0, 0.0], 3.0, 2.0, 3, 2, CellKind::Quad4, 0.0).unwrap();
        let m = split(&base, 3).unwrap();
        assert_eq!(m.num_nodes(), 10 * 7);
        let q = rectangle([0.0, 0.0], 3.0, 2.0, 3, 2, CellKind::Quad8, 0.0).unwrap();
        // Quad8: (2·9+1)(2·6+1) lattice points less the 9·6 cell centres
        assert_eq!(split(&q, 3).unwrap().num_nodes(), 19 * 13 - 54);
    }

    #[test]
    fn bad_factors_are_errors() {
        let base = rectangle([0.0, 0.0], 1.0, 1.0, 1, 1, CellKind::Quad4, 0.0).unwrap();
        for n in [0, MAX_SPLIT + 1] {
            let e = split(&base, n).unwrap_err().to_string();
            assert!(e.contains("--split must be between 1 and 16"), "{e}");
        }
    }
}
