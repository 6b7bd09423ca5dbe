//! The smoothed master normal of point-to-segment and node-to-segment on straight (Seg2)
//! master cells: n(ξ) = v/|v|, v = N₀(ξ) n̂₀ + N₁(ξ) n̂₁, where n̂ is a vertex's averaged
//! normal (the mean of its master cells' own normals, unit). A polygon standing for a curve
//! then has a normal continuous along it, so a slave node at a vertex is pushed along the
//! bisector and is paired with either cell alike (conforming meshes).
//!
//! Its variation, for the exact tangent, as the rotation rate of the frame (n, τ):
//! δn = −τ ω, δτ = n ω with ω = −τ·δv/|v| and
//!   δv = (δξ/2)(n̂₁ − n̂₀) + N₀ δn̂₀ + N₁ δn̂₁,   δn̂ = (I − n̂n̂ᵀ) Σ_c δn_c / |Σ_c n_c|,
//!   δn_c = −τ_c ω_c,  ω_c = (n_c·δt_c)/|t_c|  (each cell's own rotation rate).
//! Hand-derived (a few lines of vector algebra) rather than dual numbers: the rest of the
//! point-to-segment tangent is hand-derived with the same ω convention, so the two plug
//! together; checked by finite differences in tests/contact_tangent.rs.

use super::projection::point_and_tangent;
use super::surface::Surface;
use crate::mesh::Mesh;
use std::collections::HashMap;

/// A master cell's own inward unit normal n_c, tangent τ_c and rotation rate ω_c over dofs.
type CellFrame = ([f64; 2], [f64; 2], Vec<(usize, f64)>);

/// A master cell's own inward unit normal and tangent (τ = t/|t|) at its end `node`, and
/// its rotation rate ω_c over dofs (Seg2 and Seg3 alike: dN_a/dξ at that end).
fn cell_frame(
    mesh: &Mesh,
    master: &Surface,
    x: &dyn Fn(usize) -> [f64; 2],
    im: usize,
    node: usize,
) -> CellFrame {
    let c = master.cells[im];
    let nodes = mesh.cell_nodes(c);
    let xs: Vec<[f64; 2]> = nodes.iter().map(|&m| x(m)).collect();
    let xi = if nodes[1] == node { 1.0 } else { -1.0 };
    let (_, t) = point_and_tangent(mesh.kind(c), &xs, xi);
    let lt = t[0].hypot(t[1]);
    let tau = [t[0] / lt, t[1] / lt];
    let n = if master.ccw[im] {
        [-tau[1], tau[0]]
    } else {
        [tau[1], -tau[0]]
    };
    // dN/dξ at ξ = ±1 (Seg2: ∓½, ±½; Seg3 with the mid-side node last)
    let dn: Vec<f64> = if nodes.len() == 2 {
        vec![-0.5, 0.5]
    } else {
        vec![xi - 0.5, xi + 0.5, -2.0 * xi]
    };
    let mut omega = vec![];
    for (a, &m) in nodes.iter().enumerate() {
        for comp in 0..2 {
            omega.push((2 * m + comp, dn[a] * n[comp] / lt));
        }
    }
    (n, tau, omega)
}

/// A vertex: its averaged unit normal n̂, |Σ_c n_c|, and its cells' frames (n_c, τ_c, ω_c).
struct Vertex {
    normal: [f64; 2],
    length: f64,
    frames: Vec<CellFrame>,
}

impl Vertex {
    fn new(
        mesh: &Mesh,
        master: &Surface,
        cells_of_node: &HashMap<usize, Vec<usize>>,
        x: &dyn Fn(usize) -> [f64; 2],
        node: usize,
    ) -> Self {
        let frames: Vec<_> = cells_of_node[&node]
            .iter()
            .map(|&im| cell_frame(mesh, master, x, im, node))
            .collect();
        let v = frames
            .iter()
            .fold([0.0, 0.0], |s, f| [s[0] + f.0[0], s[1] + f.0[1]]);
        let length = v[0].hypot(v[1]);
        Vertex {
            normal: [v[0] / length, v[1] / length],
            length,
            frames,
        }
    }

    /// The coefficients of τ·δn̂ for a unit τ:
    /// τ·(I − n̂n̂ᵀ)(−τ_c ω_c)/|v| = −[τ·τ_c − (τ·n̂)(n̂·τ_c)] ω_c / |v|.
    fn turn_along(&self, t: [f64; 2]) -> Vec<(usize, f64)> {
        let nv = self.normal;
        let tn = t[0] * nv[0] + t[1] * nv[1];
        let mut coefs = vec![];
        for (_, tc, omega) in &self.frames {
            let f = -((t[0] * tc[0] + t[1] * tc[1]) - tn * (nv[0] * tc[0] + nv[1] * tc[1]))
                / self.length;
            coefs.extend(omega.iter().map(|&(d, w)| (d, f * w)));
        }
        coefs
    }
}

/// The smoothed inward normal at ξ on Seg2 master cell `im`, its tangent (oriented as the
/// cell's), and with `cxi` (the coefficients of δξ) the frame's rotation rate ω over dofs.
pub(crate) fn smoothed_frame(
    mesh: &Mesh,
    master: &Surface,
    cells_of_node: &HashMap<usize, Vec<usize>>,
    x: &dyn Fn(usize) -> [f64; 2],
    im: usize,
    xi: f64,
    cxi: Option<&[(usize, f64)]>,
) -> ([f64; 2], [f64; 2], Vec<(usize, f64)>) {
    let nodes = mesh.cell_nodes(master.cells[im]);
    let ends = [nodes[0], nodes[1]].map(|n| Vertex::new(mesh, master, cells_of_node, x, n));
    let (n0, n1) = (ends[0].normal, ends[1].normal);
    let (w0, w1) = (0.5 * (1.0 - xi), 0.5 * (1.0 + xi));
    let v = [w0 * n0[0] + w1 * n1[0], w0 * n0[1] + w1 * n1[1]];
    let lv = v[0].hypot(v[1]);
    let n = [v[0] / lv, v[1] / lv];
    let tau = if master.ccw[im] {
        [n[1], -n[0]]
    } else {
        [-n[1], n[0]]
    };
    let mut omega = vec![];
    if let Some(cxi) = cxi {
        // ω = −τ·δv/|v|
        let dn = [n1[0] - n0[0], n1[1] - n0[1]];
        let f = -0.5 * (tau[0] * dn[0] + tau[1] * dn[1]) / lv;
        omega.extend(cxi.iter().map(|&(d, c)| (d, f * c)));
        for (end, wk) in ends.iter().zip([w0, w1]) {
            let coefs = end.turn_along(tau);
            omega.extend(coefs.into_iter().map(|(d, c)| (d, -wk * c / lv)));
        }
    }
    (n, tau, omega)
}
