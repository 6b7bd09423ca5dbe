//! The nodal weighted gaps against the exact ones: a straight slave surface tilted over a
//! straight master has a linear pointwise gap, which the dual basis weights exactly
//! (∫ Φ_j g = D_j g(x_j)) wherever a node's whole support faces the master.

use super::*;
use crate::contact::pair::ContactPair;
use crate::mesh::generate::rectangle;
use crate::mesh::{CellKind, MeshBuilder};

/// A 1.4 × 0.5 block (cells of side 0.1, groups `Upper…`) on a 2 × 1 foundation (cells of
/// side 0.1, groups `Lower…`); the block's nodes come last.
fn block_over_foundation(kind: CellKind) -> (Mesh, usize) {
    let lower = rectangle([0.0, -1.0], 2.0, 1.0, 20, 4, kind, 0.0).unwrap();
    let upper = rectangle([0.3, 0.0], 1.4, 0.5, 14, 4, kind, 0.0).unwrap();
    lower_and_upper(&lower, &upper)
}

/// The two bodies in one mesh (groups `Lower…`, `Upper…`), and the first upper node.
fn lower_and_upper(lower: &Mesh, upper: &Mesh) -> (Mesh, usize) {
    let mut b = MeshBuilder::new("block over foundation");
    b.append(lower, |g| format!("Lower{g}"));
    b.append(upper, |g| format!("Upper{g}"));
    (b.finish().unwrap(), lower.num_nodes())
}

/// The mortar pair of the upper body's bottom (slave) on the lower body's top, initialised.
fn upper_on_lower(mesh: &Mesh) -> Mortar {
    let slave = Surface::from_group(mesh, "UpperBottom", "slave").unwrap();
    let master = Surface::from_group(mesh, "LowerTop", "master").unwrap();
    let mut m = Mortar::new(
        mesh,
        slave,
        master,
        1e3,
        Modelisation::PlaneStrain,
        1.0,
        false,
    );
    m.initialise(mesh);
    m
}

/// Nodes facing the master have the exact weighted gap D_j g(x_j); nodes within a cell's
/// reach of it face it; the rest (whose cells the candidate search only partly covers,
/// or not at all) do not, whatever their gap came out as.
#[test]
fn a_facing_node_has_the_weighted_gap_of_its_whole_support() {
    for kind in [CellKind::Quad4, CellKind::Quad8] {
        let (mesh, first_upper) = block_over_foundation(kind);
        let mut m = upper_on_lower(&mesh);
        // the block turned by θ about its bottom-left corner (0.3, 0), then sunk by δ:
        // along its bottom, at distance s from that corner, the gap is
        // (s sin θ − δ) / cos θ, open by 3.4 cells at the far end
        let (theta, delta) = (0.25f64, 0.01);
        let mut u = vec![0.0; 2 * mesh.num_nodes()];
        for n in first_upper..mesh.num_nodes() {
            let [x, y] = mesh.coords[n];
            let (dx, dy) = (x - 0.3, y);
            let (c, s) = (theta.cos(), theta.sin());
            u[2 * n] = 0.3 + c * dx - s * dy - x;
            u[2 * n + 1] = s * dx + c * dy - delta - y;
        }
        let lam = vec![0.0; m.num_multipliers()];
        m.update_status(&mesh, &u, &lam);
        let (g, d, facing, _) = m.gaps(&mesh, &u);
        let exact = |k: usize| {
            let s = mesh.coords[m.mult_nodes[k]][0] - 0.3;
            (s * theta.sin() - delta) / theta.cos()
        };
        let mut partly = 0;
        for k in 0..g.len() {
            if facing[k] {
                let err = (g[k] / d[k] - exact(k)).abs();
                assert!(
                    err < 1e-9,
                    "{kind} node {k}: gap {} for {}",
                    g[k] / d[k],
                    exact(k)
                );
            } else {
                // (any node within a tenth of a cell of the master faces it)
                assert!(
                    exact(k) > 0.01,
                    "{kind} node {k} (gap {}) faces nothing",
                    exact(k)
                );
            }
            // nodes whose support the search covers in part: the case in point
            let near: bool = m
                .candidates
                .iter()
                .zip(&m.cell_mults)
                .any(|(c, mults)| mults.contains(&k) && !c.is_empty());
            partly += usize::from(near && !facing[k]);
        }
        assert!(
            partly > 0,
            "{kind}: every node's support was searched in full"
        );
    }
}

/// A master end on the far corner of a slave node's cell lies within that cell: the
/// master (a foundation's top, x in [0, 2]) ends at x = 0, under the corner of a block
/// whose bottom runs from x = −0.5; the block's node at x = 0.1 is one cell from it. Sunk
/// or lifted by a thousandth of a cell, the end is a hair beyond the cell's length from
/// that node; it is under the node's cell all the same, and the node, active, faces.
#[test]
fn a_master_end_on_a_cells_far_corner_is_under_the_cell() {
    let lower = rectangle([0.0, -1.0], 2.0, 1.0, 20, 4, CellKind::Quad4, 0.0).unwrap();
    let upper = rectangle([-0.5, 0.0], 1.0, 0.5, 10, 2, CellKind::Quad4, 0.0).unwrap();
    let (mesh, first_upper) = lower_and_upper(&lower, &upper);
    let mut m = upper_on_lower(&mesh);
    let k = (0..m.mult_nodes.len())
        .find(|&k| {
            let [x, y] = mesh.coords[m.mult_nodes[k]];
            (x - 0.1).abs() < 1e-12 && y.abs() < 1e-12
        })
        .unwrap();
    for shift in [-1e-4, 1e-4] {
        let mut u = vec![0.0; 2 * mesh.num_nodes()];
        for n in first_upper..mesh.num_nodes() {
            u[2 * n + 1] = shift;
        }
        assert!(
            m.under_master_end(&mesh, &u, k),
            "shifted by {shift}: the master end is under the node's cell"
        );
        m.active[k] = true;
        let terms = m.all_cell_terms(&mesh, &u);
        let (_, d, _, _) = m.gaps(&mesh, &u);
        assert!(
            m.facing(&mesh, &u, &terms, &d)[k],
            "shifted by {shift}: the active node faces"
        );
    }
}
