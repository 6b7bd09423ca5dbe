//! Contact state at the slave nodes for output, the same for every formulation: the
//! normal gap to the master surface on the deformed geometry, and the status (open,
//! stick, slip) read off the tractions.

use crate::contact::projection::{point_and_tangent, project};
use crate::contact::surface::Surface;
use crate::mesh::Mesh;

/// Status codes written to the VTU and CSV files.
pub const OPEN: i32 = 0;
/// Closed and sticking (or closed, without friction).
pub const STICK: i32 = 1;
pub const SLIP: i32 = 2;

pub fn status_name(s: i32) -> &'static str {
    match s {
        OPEN => "open",
        STICK => "stick",
        _ => "slip",
    }
}

/// Signed normal gap of each slave node to the master surface, deformed geometry
/// (positive: open, negative: penetration): distance to the closest point of the master
/// cells, signed by the master's outward normal there.
pub fn gaps(mesh: &Mesh, u: &[f64], slave: &Surface, master: &Surface) -> Vec<(usize, f64)> {
    closest_points(mesh, u, slave, master)
        .into_iter()
        .map(|(n, g, _)| (n, g))
        .collect()
}

/// (slave node, signed gap, master outward unit normal at the closest point) for each
/// slave node, deformed geometry: the gap as `gaps` gives it, and the normal the contact
/// forces are split along: on straight (Seg2) cells the smoothed one (interpolated between
/// the vertices' averaged normals, as point-to-segment and node-to-segment use by
/// default), on curved cells the cell's own.
pub fn closest_points(
    mesh: &Mesh,
    u: &[f64],
    slave: &Surface,
    master: &Surface,
) -> Vec<(usize, f64, [f64; 2])> {
    let pos = |n: usize| {
        [
            mesh.coords[n][0] + u[2 * n],
            mesh.coords[n][1] + u[2 * n + 1],
        ]
    };
    let masters: Vec<(crate::mesh::CellKind, Vec<[f64; 2]>, bool)> = master
        .cells
        .iter()
        .zip(&master.ccw)
        .map(|(&c, &ccw)| {
            let x = mesh.cell_nodes(c).iter().map(|&n| pos(n)).collect();
            (mesh.kind(c), x, ccw)
        })
        .collect();
    let outward = |t: [f64; 2], ccw: bool| {
        let l = t[0].hypot(t[1]);
        if ccw {
            [t[1] / l, -t[0] / l]
        } else {
            [-t[1] / l, t[0] / l]
        }
    };
    // each master vertex's averaged outward normal
    let mut vertex: std::collections::HashMap<usize, [f64; 2]> = Default::default();
    for (i, &c) in master.cells.iter().enumerate() {
        let (kind, x, ccw) = &masters[i];
        for (end, xi) in [(0, -1.0), (1, 1.0)] {
            let (_, t) = point_and_tangent(*kind, x, xi);
            let nrm = outward(t, *ccw);
            let e = vertex.entry(mesh.cell_nodes(c)[end]).or_insert([0.0; 2]);
            e[0] += nrm[0];
            e[1] += nrm[1];
        }
    }
    slave
        .nodes
        .iter()
        .map(|&n| {
            let p = pos(n);
            let mut best = (f64::INFINITY, f64::INFINITY, [0.0; 2]);
            for (i, (kind, x, ccw)) in masters.iter().enumerate() {
                let xi = project(*kind, x, p).xi.clamp(-1.0, 1.0);
                let (q, t) = point_and_tangent(*kind, x, xi);
                let d = [p[0] - q[0], p[1] - q[1]];
                let dist = d[0].hypot(d[1]);
                if dist < best.0 {
                    // outward normal: right-hand normal of dx/dξ when the cell runs ccw
                    let nrm = outward(t, *ccw);
                    let sign = if d[0] * nrm[0] + d[1] * nrm[1] < 0.0 {
                        -1.0
                    } else {
                        1.0
                    };
                    let smooth = if *kind == crate::mesh::CellKind::Seg2 {
                        let ends = mesh.cell_nodes(master.cells[i]);
                        let (a, b) = (vertex[&ends[0]], vertex[&ends[1]]);
                        let v = [
                            0.5 * (1.0 - xi) * a[0] + 0.5 * (1.0 + xi) * b[0],
                            0.5 * (1.0 - xi) * a[1] + 0.5 * (1.0 + xi) * b[1],
                        ];
                        let l = v[0].hypot(v[1]);
                        if l > 0.0 {
                            [v[0] / l, v[1] / l]
                        } else {
                            nrm
                        }
                    } else {
                        nrm
                    };
                    best = (dist, sign * dist, smooth);
                }
            }
            (n, best.1, best.2)
        })
        .collect()
}

/// Status of each node from its pressure and (with friction coefficient `mu` > 0) its
/// shear: open where the pressure is not positive (below 1e-9 of the largest), slip where
/// |shear| reaches μ p (to 1e-6), stick otherwise.
pub fn statuses(pressure: &[(usize, f64)], shear: &[(usize, f64)], mu: f64) -> Vec<(usize, i32)> {
    let pmax = pressure.iter().fold(0.0f64, |m, p| m.max(p.1.abs()));
    let shear: std::collections::HashMap<usize, f64> = shear.iter().copied().collect();
    pressure
        .iter()
        .map(|&(n, p)| {
            let s = if p <= 1e-9 * pmax || pmax == 0.0 {
                OPEN
            } else if mu > 0.0
                && shear
                    .get(&n)
                    .is_some_and(|t| t.abs() >= mu * p * (1.0 - 1e-6))
            {
                SLIP
            } else {
                STICK
            };
            (n, s)
        })
        .collect()
}

/// (slave node, [normal, tangential] multiplier) of one contact pair, as the formulation
/// stores them.
pub type Multipliers = Vec<(usize, [f64; 2])>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::rectangle;
    use crate::mesh::CellKind;

    #[test]
    fn statuses_follow_the_coulomb_cone() {
        let p = [(1, 10.0), (2, 10.0), (3, 0.0), (4, 5.0)];
        let t = [(1, 0.5), (2, -1.0), (3, 0.0), (4, 0.4999999)];
        let s = statuses(&p, &t, 0.1);
        assert_eq!(s, vec![(1, STICK), (2, SLIP), (3, OPEN), (4, SLIP)]);
        // without friction every closed node sticks
        assert_eq!(statuses(&p, &t, 0.0)[1], (2, STICK));
    }

    #[test]
    fn gaps_are_signed_distances_to_the_master() {
        // master: top of a unit square; slave nodes: the top edge of a square above it,
        // lifted by 0.25 (open) and then pushed 0.1 into the lower one.
        let lower = rectangle([0.0, 0.0], 1.0, 1.0, 2, 2, CellKind::Quad8, 0.0).unwrap();
        let mut b = crate::mesh::MeshBuilder::new("t");
        b.append(&lower, |g| format!("lo_{g}"));
        let upper = rectangle([0.0, 1.25], 1.0, 1.0, 3, 1, CellKind::Quad4, 0.0).unwrap();
        b.append(&upper, |g| format!("up_{g}"));
        let mesh = b.finish().unwrap();
        let master = Surface::from_group(&mesh, "lo_Top", "master").unwrap();
        let slave = Surface::from_group(&mesh, "up_Bottom", "slave").unwrap();
        let mut u = vec![0.0; 2 * mesh.num_nodes()];
        for (_, g) in gaps(&mesh, &u, &slave, &master) {
            assert!((g - 0.25).abs() < 1e-12, "{g}");
        }
        for &n in &slave.nodes {
            u[2 * n + 1] = -0.35;
        }
        for (_, g) in gaps(&mesh, &u, &slave, &master) {
            assert!((g + 0.1).abs() < 1e-12, "{g}");
        }
    }
}
