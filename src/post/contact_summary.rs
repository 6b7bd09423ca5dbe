//! Per contact pair and per state: the nodal contact values of the slave nodes (pressure,
//! shear, gap, status, force) and what they add up to: normal and tangential resultants,
//! contact length (axisymmetric: area), centre of pressure, peak pressure, and the numbers
//! of stick, slip and open nodes. The same for every formulation: the forces are those the
//! pair applies to the slave nodes (the contact terms of the residual), so that they balance
//! the loads and reactions exactly as the solve does.

use super::contact_state::{closest_points, statuses, OPEN, SLIP, STICK};
use crate::contact::projection::{point_and_tangent, seg_shape};
use crate::contact::surface::Surface;
use crate::fem::quadrature::gauss_legendre;
use crate::mesh::Mesh;
use std::collections::HashMap;

/// The contact values at one slave node.
#[derive(Clone, Debug)]
pub struct NodeContact {
    pub node: usize,
    /// Pressure and shear from the multipliers (stress units; exactly 0 when open).
    pub pressure: f64,
    pub shear: f64,
    /// Signed normal gap to the master (deformed geometry; negative: penetration).
    pub gap: f64,
    /// `OPEN`, `STICK` or `SLIP`.
    pub status: i32,
    /// Force of the master on the node (per unit thickness in plane models; total over
    /// 2πr in axisymmetry, as the reactions).
    pub force: [f64; 2],
    /// Master outward unit normal at the node's closest point (deformed geometry, or the
    /// initial one where the formulation's normals are).
    pub normal: [f64; 2],
}

/// What the nodes of a pair add up to. The force f on a slave node splits into its normal
/// part (f·n) n, n the master's outward normal at the node's closest point, and the rest,
/// tangential; without friction the whole force is normal (the formulation applies it
/// along the normals of its own integration points, which n only approximates).
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct PairSummary {
    /// Σ of the normal parts, [x, y], and its magnitude.
    pub normal_force: [f64; 2],
    pub normal_resultant: f64,
    /// Σ of the tangential parts, [x, y], and its magnitude.
    pub tangential_force: [f64; 2],
    pub tangential_resultant: f64,
    /// Σ f: the resultant of the contact forces on the slave body, [x, y].
    pub force: [f64; 2],
    /// The closed nodes' shares of the slave surface: a length in plane models, the area
    /// ∫ 2πr ds in axisymmetry.
    pub contact_length: f64,
    /// Σ (f·n) x / Σ f·n over the slave nodes' positions (None without load).
    pub centre_of_pressure: Option<[f64; 2]>,
    /// Largest nodal pressure, its node (1-based) and the node's position.
    pub peak_pressure: f64,
    pub peak_node: Option<usize>,
    pub peak_at: Option<[f64; 2]>,
    pub stick: usize,
    pub slip: usize,
    pub open: usize,
}

/// The nodal values and the summary of one pair.
#[derive(Clone, Debug)]
pub struct PairResult {
    pub nodes: Vec<NodeContact>,
    pub summary: PairSummary,
}

/// What a pair's outputs are made of.
pub struct PairInput<'a> {
    pub mesh: &'a Mesh,
    /// Displacements (full dofs).
    pub u: &'a [f64],
    pub slave: &'a Surface,
    pub master: &'a Surface,
    /// (slave node, pressure) and (slave node, shear) from the multipliers, open nodes 0.
    pub pressure: &'a [(usize, f64)],
    pub shear: &'a [(usize, f64)],
    pub mu: f64,
    /// The pair's contact terms of the residual (full dofs): the force on a node is minus
    /// its entry (residual = internal − external + contact).
    pub residual: &'a [f64],
    pub axisymmetric: bool,
    /// Large kinematics: lengths and positions on the deformed geometry (else on the
    /// initial one, the small-strain model's; gaps are always on the deformed geometry).
    pub large: bool,
    /// The formulation's forces act along normals of the initial geometry (else of the
    /// deformed one).
    pub reference_normals: bool,
    /// A gap the pair keeps closed (mortar's `adjust`), added to the open-gap tolerance.
    pub gap_allowance: f64,
}

/// A closed node farther from the master than this fraction of its cells' mean length is
/// open whatever its multiplier: point-to-segment leaves decaying multipliers (1e-5 … 1e-8
/// of the peak) on nodes a quarter of a cell and more off the master.
const GAP_TOLERANCE: f64 = 0.1;

/// The nodal values of a pair and their sums; the pressure and shear of open nodes are
/// exactly 0.
pub fn pair_result(inp: &PairInput) -> PairResult {
    let mesh = inp.mesh;
    let zero = vec![0.0; inp.u.len()];
    // the geometry of the measures
    let u = if inp.large { inp.u } else { &zero[..] };
    let pos = |n: usize| {
        [
            mesh.coords[n][0] + u[2 * n],
            mesh.coords[n][1] + u[2 * n + 1],
        ]
    };
    let pressure: HashMap<usize, f64> = inp.pressure.iter().copied().collect();
    let shear: HashMap<usize, f64> = inp.shear.iter().copied().collect();
    // slave nodes without a multiplier (excluded from contact) are open
    let all_p: Vec<(usize, f64)> = inp
        .slave
        .nodes
        .iter()
        .map(|&n| (n, pressure.get(&n).copied().unwrap_or(0.0)))
        .collect();
    let status: HashMap<usize, i32> = statuses(&all_p, inp.shear, inp.mu).into_iter().collect();
    let size = node_sizes(mesh, inp.u, inp.slave);
    let normals: HashMap<usize, [f64; 2]> = if !inp.reference_normals {
        HashMap::new()
    } else {
        closest_points(mesh, &zero, inp.slave, inp.master)
            .into_iter()
            .map(|(n, _, normal)| (n, normal))
            .collect()
    };
    let nodes: Vec<NodeContact> = closest_points(mesh, inp.u, inp.slave, inp.master)
        .into_iter()
        .map(|(n, gap, normal)| {
            let normal = normals.get(&n).copied().unwrap_or(normal);
            let mut status = status[&n];
            if gap > GAP_TOLERANCE * size[&n] + inp.gap_allowance {
                status = OPEN;
            }
            let open = status == OPEN;
            let value = |m: &HashMap<usize, f64>| {
                if open {
                    0.0
                } else {
                    m.get(&n).copied().unwrap_or(0.0)
                }
            };
            NodeContact {
                node: n,
                pressure: value(&pressure),
                shear: value(&shear),
                gap,
                status,
                force: [-inp.residual[2 * n], -inp.residual[2 * n + 1]],
                normal,
            }
        })
        .collect();
    let mut s = PairSummary::default();
    let (mut moment, mut weight) = ([0.0; 2], 0.0);
    for c in &nodes {
        let (f, n) = (c.force, c.normal);
        let fn_ = f[0] * n[0] + f[1] * n[1];
        let normal = if inp.mu > 0.0 {
            [fn_ * n[0], fn_ * n[1]]
        } else {
            f
        };
        for k in 0..2 {
            s.normal_force[k] += normal[k];
            s.tangential_force[k] += f[k] - normal[k];
            s.force[k] += f[k];
        }
        let x = pos(c.node);
        moment[0] += fn_ * x[0];
        moment[1] += fn_ * x[1];
        weight += fn_;
        match c.status {
            OPEN => s.open += 1,
            STICK => s.stick += 1,
            SLIP => s.slip += 1,
            _ => {}
        }
        if c.pressure > s.peak_pressure {
            s.peak_pressure = c.pressure;
            s.peak_node = Some(c.node + 1);
            s.peak_at = Some(x);
        }
    }
    s.normal_resultant = s.normal_force[0].hypot(s.normal_force[1]);
    s.tangential_resultant = s.tangential_force[0].hypot(s.tangential_force[1]);
    if weight != 0.0 {
        s.centre_of_pressure = Some([moment[0] / weight, moment[1] / weight]);
    }
    let closed: HashMap<usize, bool> = nodes.iter().map(|c| (c.node, c.status != OPEN)).collect();
    s.contact_length = surface_shares(mesh, u, inp.slave, inp.axisymmetric)
        .into_iter()
        .filter(|(n, _)| closed[n])
        .map(|(_, w)| w)
        .sum();
    PairResult { nodes, summary: s }
}

/// Mean length (end to end, deformed) of the surface cells around each node.
fn node_sizes(mesh: &Mesh, u: &[f64], surface: &Surface) -> HashMap<usize, f64> {
    let mut acc: HashMap<usize, (f64, f64)> = HashMap::new();
    for &c in &surface.cells {
        let nodes = mesh.cell_nodes(c);
        let p = |n: usize| {
            [
                mesh.coords[n][0] + u[2 * n],
                mesh.coords[n][1] + u[2 * n + 1],
            ]
        };
        let (a, b) = (p(nodes[0]), p(nodes[1]));
        let l = (b[0] - a[0]).hypot(b[1] - a[1]);
        for &n in nodes {
            let e = acc.entry(n).or_default();
            e.0 += l;
            e.1 += 1.0;
        }
    }
    acc.into_iter().map(|(n, (l, k))| (n, l / k)).collect()
}

/// Each node's share ∫ N_a ds of the deformed surface (axisymmetric: ∫ N_a 2πr ds), by
/// 3-point Gauss rules, exact for the shares of straight cells.
pub fn surface_shares(
    mesh: &Mesh,
    u: &[f64],
    surface: &Surface,
    axisymmetric: bool,
) -> Vec<(usize, f64)> {
    let (pts, wts) = gauss_legendre(3);
    let mut share: std::collections::BTreeMap<usize, f64> = Default::default();
    for &c in &surface.cells {
        let kind = mesh.kind(c);
        let nodes = mesh.cell_nodes(c);
        let x: Vec<[f64; 2]> = nodes
            .iter()
            .map(|&n| {
                [
                    mesh.coords[n][0] + u[2 * n],
                    mesh.coords[n][1] + u[2 * n + 1],
                ]
            })
            .collect();
        for (&xi, &w) in pts.iter().zip(&wts) {
            let (p, t) = point_and_tangent(kind, &x, xi);
            let (shape, _) = seg_shape(kind, xi);
            let measure = if axisymmetric {
                2.0 * std::f64::consts::PI * p[0]
            } else {
                1.0
            };
            let ds = w * t[0].hypot(t[1]) * measure;
            for (a, &n) in nodes.iter().enumerate() {
                *share.entry(n).or_insert(0.0) += shape[a] * ds;
            }
        }
    }
    share.into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::rectangle;
    use crate::mesh::CellKind;

    #[test]
    fn shares_add_up_to_the_length_and_the_area() {
        // the top edge of [1, 3] × [0, 1]: length 2, area π (3² − 1²) = 8π
        for kind in [CellKind::Quad4, CellKind::Quad8] {
            let m = rectangle([1.0, 0.0], 2.0, 1.0, 3, 1, kind, 0.0).unwrap();
            let top = Surface::from_group(&m, "Top", "test").unwrap();
            let u = vec![0.0; 2 * m.num_nodes()];
            let l: f64 = surface_shares(&m, &u, &top, false)
                .iter()
                .map(|s| s.1)
                .sum();
            let a: f64 = surface_shares(&m, &u, &top, true).iter().map(|s| s.1).sum();
            assert!((l - 2.0).abs() < 1e-14, "{l}");
            assert!((a - 8.0 * std::f64::consts::PI).abs() < 1e-12, "{a}");
        }
    }
}
