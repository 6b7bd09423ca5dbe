//! Where the mortar terms are evaluated: positions, the slave and master normal fields
//! (nodal normals averaged over the adjacent cells), the measure of the surface element.
//! The normals and the measure are generic over the number type, so that the tangent
//! differentiates them exactly.

use super::super::projection::{point_and_tangent, step_settled};
use super::super::real::{constant, value, values, Real};
use super::super::surface::Surface;
use super::Mortar;
use crate::fem::element::{shape, MAX_NODES};
use crate::mesh::{CellKind, Mesh};
use std::collections::HashMap;

pub(super) fn cross<T: Real>(a: [T; 2], b: [T; 2]) -> T {
    a[0] * b[1] - a[1] * b[0]
}

/// The coordinate ξ on a master cell (node positions xm) where the line through `p` along
/// `n` crosses it: Newton from ξ = 0, and whether it settled within 30 steps.
pub(super) fn project_along<T: Real>(
    kind: CellKind,
    xm: &[[T; 2]],
    p: [T; 2],
    n: [T; 2],
) -> (T, bool) {
    let mut xi = constant(0.0);
    for _ in 0..30 {
        let (pm, tm) = point_and_tangent(kind, xm, xi);
        let step = cross([pm[0] - p[0], pm[1] - p[1]], n) / cross(tm, n);
        xi -= step;
        if step_settled(value(step), 1e-13, values(pm), values(tm)) {
            return (xi, true);
        }
    }
    (xi, false)
}

/// Euclidean length of a 2-vector.
pub(super) fn norm<T: Real>(a: [T; 2]) -> T {
    (a[0] * a[0] + a[1] * a[1]).sqrt()
}

/// Outward unit normal at ξ of a segment with node positions x (`ccw`: the body lies to
/// the left of the segment's direction).
pub(super) fn unit_normal<T: Real>(kind: CellKind, x: &[[T; 2]], ccw: bool, xi: T) -> [T; 2] {
    let (_, t) = point_and_tangent(kind, x, xi);
    let l = norm(t);
    if ccw {
        [t[1] / l, -t[0] / l]
    } else {
        [-t[1] / l, t[0] / l]
    }
}

impl Mortar {
    pub(super) fn pos(mesh: &Mesh, u: &[f64], n: usize) -> [f64; 2] {
        [
            mesh.coords[n][0] + u[2 * n],
            mesh.coords[n][1] + u[2 * n + 1],
        ]
    }

    /// Where the geometry (normals, projections, Jacobians) is evaluated: the current
    /// position for large kinematics, the reference one for small kinematics (whose
    /// multipliers are then pressures on the reference surface, like the loads).
    pub(super) fn geo(&self, mesh: &Mesh, u: &[f64], n: usize) -> [f64; 2] {
        if self.small {
            mesh.coords[n]
        } else {
            Self::pos(mesh, u, n)
        }
    }

    /// Outward unit normal of slave cell ic at ξ.
    pub(super) fn cell_normal(&self, mesh: &Mesh, u: &[f64], ic: usize, xi: f64) -> [f64; 2] {
        self.edge_normal(mesh, u, &self.slave, ic, xi)
    }

    /// Outward unit normal of cell ic of surface `surf` at ξ.
    pub(super) fn edge_normal(
        &self,
        mesh: &Mesh,
        u: &[f64],
        surf: &Surface,
        ic: usize,
        xi: f64,
    ) -> [f64; 2] {
        let c = surf.cells[ic];
        let x: Vec<[f64; 2]> = mesh
            .cell_nodes(c)
            .iter()
            .map(|&n| self.geo(mesh, u, n))
            .collect();
        unit_normal(mesh.kind(c), &x, surf.ccw[ic], xi)
    }

    /// Averaged outward unit normal at a slave corner node.
    pub(super) fn node_normal(&self, mesh: &Mesh, u: &[f64], n: usize) -> [f64; 2] {
        self.averaged_normal(mesh, u, &self.slave, &self.cells_of_node, n)
    }

    /// Outward unit normal at corner node n of `surf`, averaged over the cells sharing it.
    pub(super) fn averaged_normal(
        &self,
        mesh: &Mesh,
        u: &[f64],
        surf: &Surface,
        cells_of_node: &HashMap<usize, Vec<usize>>,
        n: usize,
    ) -> [f64; 2] {
        averaged_normal_at(mesh, surf, &cells_of_node[&n], n, &|m| self.geo(mesh, u, m))
    }
    /// The master's normal field on master cell im at ξ: its averaged nodal normals
    /// interpolated (the cell's own normal at a mid-side node), normalised.
    pub(super) fn master_normal(&self, mesh: &Mesh, u: &[f64], im: usize, xi: f64) -> [f64; 2] {
        let mc = self.master.cells[im];
        let kind = mesh.kind(mc);
        let nodes = mesh.cell_nodes(mc);
        let mut nv = [0.0; MAX_NODES];
        shape(kind, [xi, 0.0], &mut nv);
        let mut acc = [0.0; 2];
        for (a, &n) in nodes.iter().enumerate() {
            let v = if a < 2 {
                self.averaged_normal(mesh, u, &self.master, &self.master_cells_of_node, n)
            } else {
                self.edge_normal(mesh, u, &self.master, im, 0.0)
            };
            acc[0] += nv[a] * v[0];
            acc[1] += nv[a] * v[1];
        }
        let l = acc[0].hypot(acc[1]);
        [acc[0] / l, acc[1] / l]
    }

    /// With `adjust`, the step from master cell im (node positions xm) at ξ to the smooth
    /// curve its nodes lie on: through its nodes and tangent at its ends to the averaged
    /// nodal normals (a cubic on a Seg2, a quartic on a Seg3: for cells inscribed in a
    /// circle, the arc to within O(h³/R²) and O(h⁵/R⁴)). The initial offsets remove the
    /// mismatch where each slave node starts; a slave sliding along the master meets
    /// other parts of its cells, so the gap is measured to the curve. The tangent holds the
    /// nodal normals fixed in the cell's chord frame: exact for a rigid rotation, leaving
    /// out their turn relative to the cell (of the order of the strains).
    pub(super) fn cell_to_curve<T: Real>(
        &self,
        mesh: &Mesh,
        u: &[f64],
        im: usize,
        xm: &[[T; 2]],
        xi: T,
    ) -> [T; 2] {
        let mc = self.master.cells[im];
        let (kind, nodes) = (mesh.kind(mc), mesh.cell_nodes(mc));
        let chord = [xm[1][0] - xm[0][0], xm[1][1] - xm[0][1]];
        let l = norm(chord);
        let e = [chord[0] / l, chord[1] / l];
        let nu = unit_normal(CellKind::Seg2, xm, self.master.ccw[im], constant(0.0));
        // a nodal normal in the chord's frame (its components there constant in the
        // tangent: a rigid rotation turns it with the cell)
        let normal = |n| {
            let v = self.averaged_normal(mesh, u, &self.master, &self.master_cells_of_node, n);
            let (a, b) = (
                v[0] * value(nu[0]) + v[1] * value(nu[1]),
                v[0] * value(e[0]) + v[1] * value(e[1]),
            );
            [nu[0] * a + e[0] * b, nu[1] * a + e[1] * b]
        };
        // the curve's slopes against the cell's own tangent at its ends, from n ⊥ tangent
        let slope = |end: f64, n: [T; 2]| {
            let (_, t) = point_and_tangent(kind, xm, constant(end));
            -(t[0] * n[0] + t[1] * n[1]) / norm(t)
        };
        let (sa, sb) = (slope(-1.0, normal(nodes[0])), slope(1.0, normal(nodes[1])));
        let s = (xi + 1.0) * 0.5;
        let r = -s + 1.0;
        let h = if kind == CellKind::Seg3 {
            // zero at the mid-side node too
            let (a, b) = (l * sa, l * (sb - sa));
            s * r * (-s * 2.0 + 1.0) * (a + b * s)
        } else {
            l * (sa * s * r * r - sb * s * s * r)
        };
        let nu = unit_normal(kind, xm, self.master.ccw[im], xi);
        [h * nu[0], h * nu[1]]
    }

    /// The measure of the surface element per unit length at p: 2πr in axisymmetry, the
    /// thickness otherwise.
    pub(super) fn measure<T: Real>(&self, p: [T; 2]) -> T {
        if self.axisymmetric {
            p[0] * (2.0 * std::f64::consts::PI)
        } else {
            constant(self.thickness)
        }
    }
}

/// The unit normal at corner node n of `surf` averaged over its cells `cells` (indices in
/// the surface), with the node positions given by `pos`.
pub(super) fn averaged_normal_at<T: Real>(
    mesh: &Mesh,
    surf: &Surface,
    cells: &[usize],
    n: usize,
    pos: &impl Fn(usize) -> [T; 2],
) -> [T; 2] {
    let mut acc = [constant::<T>(0.0); 2];
    for &ic in cells {
        let c = surf.cells[ic];
        let nodes = mesh.cell_nodes(c);
        let x: Vec<[T; 2]> = nodes.iter().map(|&m| pos(m)).collect();
        let xi = if nodes[0] == n { -1.0 } else { 1.0 };
        let v = unit_normal(mesh.kind(c), &x, surf.ccw[ic], constant(xi));
        acc[0] += v[0];
        acc[1] += v[1];
    }
    let l = norm(acc);
    [acc[0] / l, acc[1] / l]
}
