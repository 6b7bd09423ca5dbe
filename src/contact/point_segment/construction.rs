//! Building the pair: its contact points (Gauss or nodal, or one per slave node), their
//! weights, the multipliers and their weights; counts of multipliers and active points.

use super::super::projection::point_and_tangent;
use super::super::surface::Surface;
use super::{
    pattern_candidates_within, Integration, Options, Point, PointToSegment, CANDIDATE_MARGIN,
};
use crate::fem::element::{shape, MAX_NODES};
use crate::fem::material::Modelisation;
use crate::fem::quadrature::gauss_legendre;
use crate::mesh::Mesh;
use std::collections::HashMap;

impl PointToSegment {
    pub fn new(
        mesh: &Mesh,
        slave: Surface,
        master: Surface,
        mut opts: Options,
        model: Modelisation,
        thickness: f64,
    ) -> Self {
        let mut mult_nodes = slave.nodes.clone();
        mult_nodes.sort_unstable();
        let mult_of: HashMap<usize, usize> = mult_nodes
            .iter()
            .enumerate()
            .map(|(k, &n)| (n, k))
            .collect();
        let measure_at = |p: [f64; 2]| match model {
            Modelisation::Axisymmetric => 2.0 * std::f64::consts::PI * p[0],
            _ => thickness,
        };
        let mut points = vec![];
        // node-to-segment: the nodal rule (trapezoid / Simpson) gives each node its share of
        // the surface; the continuous method's multipliers are pressures already
        let mut node_weight = vec![if opts.node_to_segment { 0.0 } else { 1.0 }; mult_nodes.len()];
        for (ic, &c) in slave.cells.iter().enumerate() {
            let kind = mesh.kind(c);
            let x0: Vec<[f64; 2]> = mesh.cell_nodes(c).iter().map(|&n| mesh.coords[n]).collect();
            let nodal: Vec<(f64, f64)> = if kind.is_quadratic() {
                vec![(-1.0, 1.0 / 3.0), (1.0, 1.0 / 3.0), (0.0, 4.0 / 3.0)]
            } else {
                vec![(-1.0, 1.0), (1.0, 1.0)]
            };
            if opts.node_to_segment {
                if model == Modelisation::Axisymmetric {
                    // ∫ N_a 2πr ds: the trapezoid / Simpson rule gives a node on the axis
                    // no share at all
                    let (gp, gw) = gauss_legendre(4);
                    let mut nv = [0.0; MAX_NODES];
                    for (q, &xi) in gp.iter().enumerate() {
                        let (p, t) = point_and_tangent(kind, &x0, xi);
                        shape(kind, [xi, 0.0], &mut nv);
                        for (a, &n) in mesh.cell_nodes(c).iter().enumerate() {
                            node_weight[mult_of[&n]] +=
                                gw[q] * nv[a] * t[0].hypot(t[1]) * measure_at(p);
                        }
                    }
                } else {
                    for (a, &(xi, w)) in nodal.iter().enumerate() {
                        let (p, t) = point_and_tangent(kind, &x0, xi);
                        node_weight[mult_of[&mesh.cell_nodes(c)[a]]] +=
                            w * t[0].hypot(t[1]) * measure_at(p);
                    }
                }
                continue;
            }
            let rule: Vec<(f64, f64)> = match opts.integration {
                Integration::Gauss(n) => {
                    let (p, w) = gauss_legendre(n);
                    p.into_iter().zip(w).collect()
                }
                Integration::Nodal => nodal,
            };
            // Nodal integration in axisymmetry: each node's consistent share ∫ N_a 2πr ds
            // (the nodal rule would give a node on the axis none, and its multiplier no row)
            let shares: Option<Vec<f64>> = (model == Modelisation::Axisymmetric
                && opts.integration == Integration::Nodal)
                .then(|| {
                    let (gp, gw) = gauss_legendre(4);
                    let mut nv = [0.0; MAX_NODES];
                    let mut share = vec![0.0; kind.num_nodes()];
                    for (q, &xi) in gp.iter().enumerate() {
                        let (p, t) = point_and_tangent(kind, &x0, xi);
                        shape(kind, [xi, 0.0], &mut nv);
                        for (a, v) in share.iter_mut().enumerate() {
                            *v += gw[q] * nv[a] * t[0].hypot(t[1]) * measure_at(p);
                        }
                    }
                    share
                });
            for (a, (xi, w)) in rule.into_iter().enumerate() {
                let (p, t) = point_and_tangent(kind, &x0, xi);
                let omega = match &shares {
                    Some(share) => share[a],
                    None => w * t[0].hypot(t[1]) * measure_at(p),
                };
                // (the nodal rule's point at an excluded node)
                let at_excluded = opts.integration == Integration::Nodal
                    && opts.contact_excluded.contains(&mesh.cell_nodes(c)[a]);
                points.push(Point {
                    cell: ic,
                    xi,
                    omega,
                    active: false,
                    excluded: false,
                    left_out: at_excluded,
                    master: 0,
                    xi_m: 0.0,
                });
            }
        }
        if opts.node_to_segment {
            // one unit-weight point per slave node, on the first slave cell holding it
            for &n in &mult_nodes {
                let (ic, a) = slave
                    .cells
                    .iter()
                    .enumerate()
                    .find_map(|(ic, &c)| {
                        mesh.cell_nodes(c)
                            .iter()
                            .position(|&m| m == n)
                            .map(|a| (ic, a))
                    })
                    .expect("a slave node lies on a slave cell");
                points.push(Point {
                    cell: ic,
                    xi: [-1.0, 1.0, 0.0][a],
                    omega: 1.0,
                    active: false,
                    excluded: false,
                    left_out: opts.contact_excluded.contains(&n),
                    master: 0,
                    xi_m: 0.0,
                });
            }
        }
        let mut master_cells_of_node: HashMap<usize, Vec<usize>> = HashMap::new();
        for (im, &c) in master.cells.iter().enumerate() {
            for &n in mesh.cell_nodes(c) {
                master_cells_of_node.entry(n).or_default().push(im);
            }
        }
        // multipliers no point weighs, and points of no weight (never active)
        let weightless: Vec<bool> = if opts.node_to_segment {
            // (a Seg3 corner at the pole of a curved face keeps ~1e-7 of a share)
            let wmax = node_weight.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            node_weight.iter().map(|w| w.abs() <= 1e-6 * wmax).collect()
        } else {
            let mut weight = vec![0.0; mult_nodes.len()];
            let mut nv = [0.0; MAX_NODES];
            for p in &points {
                let c = slave.cells[p.cell];
                shape(mesh.kind(c), [p.xi, 0.0], &mut nv);
                for (a, &n) in mesh.cell_nodes(c).iter().enumerate() {
                    weight[mult_of[&n]] += p.omega * nv[a].abs();
                }
            }
            let wmax = weight.iter().fold(0.0f64, |m, v| m.max(*v));
            weight.iter().map(|&w| w <= 1e-12 * wmax).collect()
        };
        let wmax = points.iter().fold(0.0f64, |m, p| m.max(p.omega));
        for p in points.iter_mut() {
            if p.omega <= 1e-12 * wmax {
                p.left_out = true;
            }
        }
        let mult_coords: Vec<[f64; 2]> = mult_nodes.iter().map(|&n| mesh.coords[n]).collect();
        // reported from the neighbours: a node on the axis, or of no weight
        let on_axis =
            super::super::axis::on_axis(&mult_coords, model == Modelisation::Axisymmetric);
        let is_excluded = |k: usize| opts.contact_excluded.contains(&mult_nodes[k]);
        let reported_from_neighbours: Vec<bool> = (0..mult_nodes.len())
            .map(|k| (weightless[k] || on_axis[k]) && !is_excluded(k))
            .collect();
        // exclude (point-to-segment): the node's multiplier is held at zero by its own row,
        // as a weightless one's, and no point writes its rows (see `contribute`); without
        // contact it has no friction either
        let mut weightless = weightless;
        if !opts.node_to_segment {
            for (k, w) in weightless.iter_mut().enumerate() {
                *w |= is_excluded(k);
            }
            let excluded = opts.contact_excluded.clone();
            opts.friction_excluded.extend(excluded);
        }
        let n_mult = mult_nodes.len();
        let n_points = points.len();
        let rho_f = opts.rho_f;
        let candidates =
            pattern_candidates_within(mesh, None, &slave, &master, CANDIDATE_MARGIN, 0.0);
        let master_pieces = super::super::overlap::pieces_of_bodies(mesh, &master);
        let mut pair = PointToSegment {
            master_pieces,
            slave,
            master,
            opts,
            points,
            mult_of,
            mult_nodes,
            master_cells_of_node,
            saved: vec![],
            changed: vec![],
            candidates,
            candidates_generation: 0,
            pattern_sent: std::cell::Cell::new(None),
            u_start: vec![0.0; 2 * mesh.num_nodes()],
            node_weight,
            weightless,
            reported_from_neighbours,
            mult_coords,
            q_start: vec![0.0; n_mult],
            law: vec![None; n_points],
            branch_switches: 0,
            switches: vec![0; n_points],
            trial_scale: vec![1.0; n_points],
            balanced_rho_f: vec![rho_f; n_points],
        };
        // (every point inactive until `initialise`)
        pair.save_start();
        pair
    }

    /// Normal multipliers on the slave nodes, then (with friction) tangential ones.
    /// The mean share of the slave surface per multiplier (node-to-segment: length times
    /// thickness, or 2πr; the continuous method: 1).
    pub fn mean_node_share(&self) -> f64 {
        let n = self.node_weight.len().max(1) as f64;
        self.node_weight.iter().sum::<f64>() / n
    }

    pub fn num_multipliers(&self) -> usize {
        self.mult_nodes.len() * if self.opts.friction.is_some() { 2 } else { 1 }
    }

    pub fn num_active(&self) -> usize {
        self.points.iter().filter(|p| p.active).count()
    }
}
