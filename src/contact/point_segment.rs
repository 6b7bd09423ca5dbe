//! The `point-to-segment` formulation: the reference code's "continuous" method
//! (contact.md §1.1–1.7), reproduced to match its SSNP154 runs A–D.
//!
//! Multipliers λ_k on the slave nodes, interpolated with the slave shape functions (λ < 0 in
//! compression; pressure p = −λ). Contact points are the integration points of the slave
//! cells (3 Gauss points or the nodes), weighted with the initial slave Jacobian. Each point
//! is projected on the master surface (nearest master node, then the master cells around
//! it), giving the inward master normal n and the penetration d = (x_s − x̄_m)·n.
//! With the augmented multiplier λ̂ = λ − ρ d, a point is active iff λ̂ < 0, and
//!   active:   r_u += −ω λ̂ B,            r_λ += −ω d N_s
//!   inactive:                           r_λ += −ω (λ/ρ) N_s
//! with B = [N_s n ; −N_m n]. The tangent freezes pairing and normal.
//!
//! The same machinery gives the `node-to-segment` formulation (the reference's "discrete"
//! method, contact.md §2): one point per slave node with unit weight, so that λ is the
//! nodal contact force, exact non-penetration of the slave nodes (or a penalty: active rows
//! d + λ/k = 0, i.e. λ = −k d). Pressures for output divide the force by the node's share
//! of the slave surface.

use super::friction;
use super::projection::{point_and_tangent, project};
use super::smoothed_normal::smoothed_frame;
use super::surface::Surface;
use crate::assembly::coupled::Triplets;
use crate::fem::element::{shape, shape_grad, MAX_NODES};
use crate::fem::material::Modelisation;
use crate::fem::quadrature::gauss_legendre;
use crate::mesh::Mesh;
use std::collections::HashMap;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Integration {
    /// n-point Gauss–Legendre per slave cell.
    Gauss(usize),
    /// At the nodes: trapezoid on Seg2, Simpson on Seg3 (axisymmetric: each node's consistent
    /// share ∫ N_a 2πr ds).
    Nodal,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InitialStatus {
    /// Every point starts active (the reference's CONTACT_INIT = OUI).
    All,
    /// Points whose initial gap is closed start active: within `initial_gap` if given, else
    /// within 1e-3 of the shortest slave cell (touching).
    Closed,
}

#[derive(Clone, Debug)]
pub struct Options {
    pub integration: Integration,
    /// One point per slave node with unit weight (node-to-segment); `integration` is unused.
    pub node_to_segment: bool,
    /// Node-to-segment penalty stiffness k (force per length): λ = −k d instead of d = 0.
    pub penalty: Option<f64>,
    /// Slave nodes excluded from contact (node-to-segment: the reference's SANS_GROUP_NO).
    pub contact_excluded: Vec<usize>,
    /// Augmentation coefficient ρ (the reference's COEF_CONT, 100).
    pub rho: f64,
    pub initial: InitialStatus,
    /// With `Closed`: open gaps up to this distance count as closed at the start. Starting
    /// from about the first step's contact zone instead of one touching point (or of every
    /// point) halves the Newton iterations on SSNP154; the converged state is the same.
    pub initial_gap: Option<f64>,
    /// Parametric overshoot beyond which a projection is rejected (TOLE_PROJ_EXT, 0.5).
    pub projection_tolerance: f64,
    /// Coulomb friction coefficient (None: frictionless).
    pub friction: Option<f64>,
    /// Friction augmentation ρ_f (the reference's COEF_FROT, 100, per unit length).
    pub rho_f: f64,
    /// Slave nodes excluded from friction only (the reference's SANS_GROUP_NO_FR).
    pub friction_excluded: Vec<usize>,
    /// Node-to-segment tangential penalty k_t (a stick stiffness, force per length): a
    /// sticking node's tangential force is its force at the step start − k_t × its slip
    /// since, instead of exact stick (no slip) by the multiplier.
    pub tangential_penalty: Option<f64>,
    /// Straight master cells: the gap and force along the normal interpolated between the
    /// vertices' averaged normals (continuous along the surface), or along each cell's own
    /// normal (the reference code's default, which SSNP154 reproduces).
    pub smoothed_normal: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            integration: Integration::Gauss(3),
            node_to_segment: false,
            penalty: None,
            contact_excluded: vec![],
            rho: 100.0,
            initial: InitialStatus::All,
            initial_gap: None,
            projection_tolerance: 0.5,
            friction: None,
            rho_f: 100.0,
            friction_excluded: vec![],
            tangential_penalty: None,
            smoothed_normal: true,
        }
    }
}

/// A point is paired with the master surface only within this many times the larger of
/// its cell's and the nearest master cell's length; the initial candidates reach further
/// (CANDIDATE_MARGIN times the cells' sizes), so that a body closing a gap of about one
/// cell pairs inside the initial pattern (no new analysis of the matrix).
const PAIRING_REACH: f64 = 2.0;

/// How far (in the parametric coordinate, of 2 per cell) a point's projection may leave
/// its master cell before the point is paired again (see `pair`).
const PAIRING_HYSTERESIS: f64 = 0.01;
const CANDIDATE_MARGIN: f64 = 3.0;

#[derive(Clone, Debug)]
struct Point {
    /// Index into slave.cells.
    cell: usize,
    xi: f64,
    /// Weight × initial Jacobian × (thickness or 2πr).
    omega: f64,
    active: bool,
    excluded: bool,
    /// Never active (a node excluded from contact).
    left_out: bool,
    /// Index into master.cells and parametric coordinate of the (clamped) projection.
    master: usize,
    xi_m: f64,
}

/// What a cut step restores of a point (see `Point`).
struct Saved {
    active: bool,
    master: usize,
    xi_m: f64,
    excluded: bool,
}

pub struct PointToSegment {
    pub slave: Surface,
    pub master: Surface,
    pub opts: Options,
    points: Vec<Point>,
    /// slave node → multiplier index
    pub mult_of: HashMap<usize, usize>,
    /// multiplier index → slave node
    pub mult_nodes: Vec<usize>,
    master_cells_of_node: HashMap<usize, Vec<usize>>,
    /// Per point, its status and its pairing at the start of the load step (restored when
    /// the step is cut: a failed attempt may have paired points far from where the step
    /// started).
    saved: Vec<Saved>,
    /// Slave nodes (nearest the points) whose status the last `update_status` changed.
    changed: Vec<usize>,
    /// Per slave cell, the master cells it may couple with: those near it initially, plus
    /// any it has been paired with since. The matrix pattern covers all of them, so it only
    /// changes when a point pairs outside this set.
    candidates: Vec<Vec<usize>>,
    /// Bumped whenever `candidates` grows; the generation whose pattern was last sent.
    candidates_generation: usize,
    pattern_sent: std::cell::Cell<Option<usize>>,
    /// Displacement at the start of the load step (slips are measured from it).
    u_start: Vec<f64>,
    /// Per multiplier, what turns it into a pressure: 1 for the continuous method (λ is a
    /// pressure), the node's share of the slave surface for node-to-segment (λ is a force).
    node_weight: Vec<f64>,
    /// Per multiplier, whether no point weighs it (the continuous method with nodal
    /// integration at a node on the axis, where 2πr = 0; a node-to-segment node of zero
    /// share): its row sets it to zero, and its pressure is its neighbours' limit.
    weightless: Vec<bool>,
    /// Per multiplier, whether its pressure is reported as its neighbours' limit (a node on
    /// the axis, or weightless).
    reported_from_neighbours: Vec<bool>,
    /// Initial positions of the slave nodes (multiplier order).
    mult_coords: Vec<[f64; 2]>,
    /// Per multiplier, the tangential force at the start of the load step (the spring
    /// force a tangential penalty starts the step from).
    q_start: Vec<f64>,
}

/// Coefficients of a linear form over dofs: (dof, value).
type Coefs<'a> = &'a [(usize, f64)];
type OwnedCoefs = Vec<(usize, f64)>;

/// What the friction term of one point needs from the normal one.
struct FrictionPoint<'a> {
    mu: f64,
    /// |λ| below which a point carries no friction (1e-8 of the largest |λ|)
    lambda_floor: f64,
    w: f64,
    lp: f64,
    chi: bool,
    e: &'a Eval,
    snodes: &'a [usize],
    mnodes: &'a [usize],
    /// δξ̄ and (n·δt)/|t| over dofs (None when the projection is clamped at a cell end).
    geo: Option<(Coefs<'a>, Coefs<'a>)>,
}

/// Geometry of one contact point at the current state.
struct Eval {
    ns: [f64; MAX_NODES],
    nm: [f64; MAX_NODES],
    /// dN_m/dξ at the projection
    dnm: [f64; MAX_NODES],
    normal: [f64; 2],
    tau: [f64; 2],
    /// dx̄/dξ and d²x̄/dξ² of the master curve at the projection
    t: [f64; 2],
    tt: [f64; 2],
    d: f64,
    /// the projection fell outside the master cell and was clamped to its end
    clamped: bool,
    /// The master cell's own normal and the distance along it (the orthogonal projection's
    /// terms); `normal` and `d` are those of the interpolated normal (see `eval`), and
    /// tn = t·normal their difference's first-order effect on the gap.
    seg_normal: [f64; 2],
    d_seg: f64,
    tn: f64,
    /// (x_s − x̄)·τ: the gap's first-order change as the frame turns
    tq: f64,
    xi_m: f64,
    /// `normal` is the smoothed one (see `smoothed_normal.rs`)
    smoothed: bool,
}

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
        let on_axis = super::axis::on_axis(&mult_coords, model == Modelisation::Axisymmetric);
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
        let candidates = initial_candidates(mesh, &slave, &master, CANDIDATE_MARGIN);
        let mut pair = PointToSegment {
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

    /// Sets the initial statuses from the undeformed geometry.
    pub fn initialise(&mut self, mesh: &Mesh) {
        let u = vec![0.0; 2 * mesh.num_nodes()];
        for i in 0..self.points.len() {
            self.pair(mesh, &u, i, false);
            let p = &self.points[i];
            let active = !p.excluded
                && match self.opts.initial {
                    InitialStatus::All => true,
                    InitialStatus::Closed => {
                        let gap = self
                            .opts
                            .initial_gap
                            .unwrap_or_else(|| self.touch_tolerance(mesh));
                        self.eval(mesh, &u, i).d >= -gap
                    }
                };
            self.points[i].active = active;
        }
        // A touching point of no weight (on the axis) holds nothing: the other points of its
        // cell start active in its place (a body held by contact alone would start free).
        let gap = self
            .opts
            .initial_gap
            .unwrap_or_else(|| self.touch_tolerance(mesh));
        let wmax = self.points.iter().fold(0.0f64, |m, p| m.max(p.omega));
        for i in 0..self.points.len() {
            let p = &self.points[i];
            let weightless = p.omega <= 1e-12 * wmax && !self.opts.node_to_segment;
            if weightless
                && self.opts.initial == InitialStatus::Closed
                && self.eval(mesh, &u, i).d >= -gap
            {
                let cell = p.cell;
                for q in self
                    .points
                    .iter_mut()
                    .filter(|q| q.cell == cell && !q.excluded)
                {
                    q.active = true;
                }
            }
        }
        self.save_start();
    }

    /// The statuses and pairings a cut step restores.
    fn save_start(&mut self) {
        self.saved = self
            .points
            .iter()
            .map(|p| Saved {
                active: p.active,
                master: p.master,
                xi_m: p.xi_m,
                excluded: p.excluded,
            })
            .collect();
    }

    fn current(mesh: &Mesh, u: &[f64], n: usize) -> [f64; 2] {
        [
            mesh.coords[n][0] + u[2 * n],
            mesh.coords[n][1] + u[2 * n + 1],
        ]
    }

    fn slave_point(&self, mesh: &Mesh, u: &[f64], i: usize, ns: &mut [f64; MAX_NODES]) -> [f64; 2] {
        let p = &self.points[i];
        let c = self.slave.cells[p.cell];
        let kind = mesh.kind(c);
        shape(kind, [p.xi, 0.0], ns);
        let mut x = [0.0; 2];
        for (a, &n) in mesh.cell_nodes(c).iter().enumerate() {
            let xn = Self::current(mesh, u, n);
            x[0] += ns[a] * xn[0];
            x[1] += ns[a] * xn[1];
        }
        x
    }

    /// Pairs point i with the master surface at displacement u. With `keep`, a point stays
    /// with its master cell while its projection lies on the cell or within
    /// PAIRING_HYSTERESIS of its ends: a point at a master vertex (a slave node on a master
    /// node, as on conforming meshes) is otherwise paired with one cell and the other in
    /// turn as round-off moves it, each with its own normal, and Newton stalls between the
    /// two (conforming rings: the residual frozen at 1.5e-2).
    fn pair(&mut self, mesh: &Mesh, u: &[f64], i: usize, keep: bool) {
        let mut ns = [0.0; MAX_NODES];
        let xs = self.slave_point(mesh, u, i, &mut ns);
        if keep && !self.points[i].excluded {
            let c = self.master.cells[self.points[i].master];
            let x: Vec<[f64; 2]> = mesh
                .cell_nodes(c)
                .iter()
                .map(|&n| Self::current(mesh, u, n))
                .collect();
            let xi = project(mesh.kind(c), &x, xs).xi;
            let (q, t) = point_and_tangent(mesh.kind(c), &x, xi.clamp(-1.0, 1.0));
            // (a point gone beyond reach is paired again, i.e. left unpaired, below)
            let near = (q[0] - xs[0]).hypot(q[1] - xs[1]) <= PAIRING_REACH * t[0].hypot(t[1]);
            if near && xi.abs() <= 1.0 + PAIRING_HYSTERESIS {
                self.points[i].xi_m = xi.clamp(-1.0, 1.0);
                return;
            }
        }
        let nearest = self
            .master
            .nodes
            .iter()
            .copied()
            .min_by(|&a, &b| {
                let (pa, pb) = (Self::current(mesh, u, a), Self::current(mesh, u, b));
                let da = (pa[0] - xs[0]).powi(2) + (pa[1] - xs[1]).powi(2);
                let db = (pb[0] - xs[0]).powi(2) + (pb[1] - xs[1]).powi(2);
                da.total_cmp(&db)
            })
            .unwrap();
        let mut best: Option<(f64, usize, f64, f64)> = None; // (dist², master, ξ clamped, overshoot)
        for &im in self
            .master_cells_of_node
            .get(&nearest)
            .map(|v| v.as_slice())
            .unwrap_or(&[])
        {
            let c = self.master.cells[im];
            let kind = mesh.kind(c);
            let x: Vec<[f64; 2]> = mesh
                .cell_nodes(c)
                .iter()
                .map(|&n| Self::current(mesh, u, n))
                .collect();
            let pr = project(kind, &x, xs);
            let xi = pr.xi.clamp(-1.0, 1.0);
            let over = (pr.xi.abs() - 1.0).max(0.0);
            let (q, _) = point_and_tangent(kind, &x, xi);
            let d2 = (q[0] - xs[0]).powi(2) + (q[1] - xs[1]).powi(2);
            if best.is_none_or(|b| d2 < b.0) {
                best = Some((d2, im, xi, over));
            }
        }
        // A point farther from the master surface than PAIRING_REACH times the larger of
        // its cell and the nearest master cell stays unpaired (inactive, no couplings):
        // the pattern, and so the contact interface the solver condenses on, then holds
        // only the part of the slave surface within reach. Pairing is redone at every
        // status update, so a point that comes within reach is paired (and may close)
        // there.
        let length = |c: usize| {
            let nodes = mesh.cell_nodes(c);
            let (a, b) = (
                Self::current(mesh, u, nodes[0]),
                Self::current(mesh, u, nodes[1]),
            );
            (a[0] - b[0]).hypot(a[1] - b[1])
        };
        let ic = self.points[i].cell;
        let best = best.filter(|&(d2, im, _, _)| {
            let reach =
                PAIRING_REACH * length(self.slave.cells[ic]).max(length(self.master.cells[im]));
            d2 <= reach * reach
        });
        if let Some((_, im, _, _)) = best {
            if !self.candidates[ic].contains(&im) {
                self.add_candidates(mesh, ic, im);
            }
        }
        let p = &mut self.points[i];
        match best {
            Some((_, im, xi, over)) => {
                p.master = im;
                p.xi_m = xi;
                p.excluded = p.left_out || over > self.opts.projection_tolerance;
            }
            None => p.excluded = true,
        }
    }

    /// Adds master cell `im` and its neighbours up to two cells away along the master
    /// surface to the candidates of slave cell `ic`: a point slides to a neighbouring
    /// master cell far more often than it jumps, and a pattern that already holds the
    /// neighbours keeps the symbolic factorisation (≈ 2 numeric ones) from being redone.
    fn add_candidates(&mut self, mesh: &Mesh, ic: usize, im: usize) {
        let mut ring = vec![im];
        for _ in 0..2 {
            let mut next = ring.clone();
            for &m in &ring {
                for &n in mesh.cell_nodes(self.master.cells[m]) {
                    next.extend(self.master_cells_of_node.get(&n).into_iter().flatten());
                }
            }
            next.sort_unstable();
            next.dedup();
            ring = next;
        }
        let list = &mut self.candidates[ic];
        for m in ring {
            if !list.contains(&m) {
                list.push(m);
            }
        }
        self.candidates_generation += 1;
    }

    /// Geometry of point i at displacement u: projected again on its paired master cell
    /// (the cell only changes in `update_status`), so that the residual is a smooth
    /// function of u between status updates and the tangent below is its exact derivative.
    fn eval(&self, mesh: &Mesh, u: &[f64], i: usize) -> Eval {
        let mut ns = [0.0; MAX_NODES];
        let xs = self.slave_point(mesh, u, i, &mut ns);
        let p = &self.points[i];
        let c = self.master.cells[p.master];
        let kind = mesh.kind(c);
        let nm_nodes = kind.num_nodes();
        let mut x = [[0.0; 2]; 3];
        for (a, &n) in mesh.cell_nodes(c).iter().enumerate() {
            x[a] = Self::current(mesh, u, n);
        }
        let raw = project(kind, &x[..nm_nodes], xs).xi;
        let clamped = raw.abs() > 1.0;
        let xi_m = raw.clamp(-1.0, 1.0);
        let (q, t) = point_and_tangent(kind, &x[..nm_nodes], xi_m);
        let lt = t[0].hypot(t[1]);
        let tau = [t[0] / lt, t[1] / lt];
        // outward normal of the master body, then inward
        let out = if self.master.ccw[p.master] {
            [tau[1], -tau[0]]
        } else {
            [-tau[1], tau[0]]
        };
        let seg_normal = [-out[0], -out[1]];
        let d_seg = (xs[0] - q[0]) * seg_normal[0] + (xs[1] - q[1]) * seg_normal[1];
        // A straight master cell's normal jumps at its vertices by the angle between cells
        // (a polygon standing for a curve): the gap and force take the normal interpolated
        // between the vertices' averaged normals instead, continuous along the surface, so
        // that a slave node at a vertex (conforming meshes) is pushed along the bisector,
        // not along one cell's normal or the other's (conforming rings: a tangential bias
        // of the pressure, -1.4 % to +2.7 % around the ring). Straight in-line cells keep
        // their normal; curved (Seg3) cells meet with continuous normals already.
        let smoothed = nm_nodes == 2 && self.opts.smoothed_normal;
        let (normal, tau) = if smoothed {
            let at = |n: usize| Self::current(mesh, u, n);
            let (n, tau, _) = smoothed_frame(
                mesh,
                &self.master,
                &self.master_cells_of_node,
                &at,
                p.master,
                xi_m,
                None,
            );
            (n, tau)
        } else {
            (seg_normal, tau)
        };
        let d = (xs[0] - q[0]) * normal[0] + (xs[1] - q[1]) * normal[1];
        let mut nm = [0.0; MAX_NODES];
        let mut dnm = [[0.0; 2]; MAX_NODES];
        shape(kind, [xi_m, 0.0], &mut nm);
        shape_grad(kind, [xi_m, 0.0], &mut dnm);
        // second derivative of the master curve (constant on a Seg3, zero on a Seg2)
        let tt = if nm_nodes == 3 {
            [
                x[0][0] + x[1][0] - 2.0 * x[2][0],
                x[0][1] + x[1][1] - 2.0 * x[2][1],
            ]
        } else {
            [0.0, 0.0]
        };
        Eval {
            ns,
            nm,
            dnm: std::array::from_fn(|a| dnm[a][0]),
            normal,
            tau,
            t,
            tt,
            d,
            clamped,
            seg_normal,
            d_seg,
            tn: t[0] * normal[0] + t[1] * normal[1],
            tq: (xs[0] - q[0]) * tau[0] + (xs[1] - q[1]) * tau[1],
            xi_m,
            smoothed,
        }
    }

    fn point_lambda(&self, mesh: &Mesh, i: usize, ns: &[f64; MAX_NODES], lam: &[f64]) -> f64 {
        let c = self.slave.cells[self.points[i].cell];
        mesh.cell_nodes(c)
            .iter()
            .enumerate()
            .map(|(a, n)| ns[a] * lam[self.mult_of[n]])
            .sum()
    }

    /// Open gap below which a point counts as initially touching: 1e-3 of the shortest
    /// slave cell (so that the Gauss point nearest a single initial contact point is closed).
    fn touch_tolerance(&self, mesh: &Mesh) -> f64 {
        1e-3 * self.slave.shortest_cell(mesh)
    }

    /// Re-pairs every point at the displacement u.
    pub fn pair_all(&mut self, mesh: &Mesh, u: &[f64]) {
        for i in 0..self.points.len() {
            self.pair(mesh, u, i, true);
        }
    }

    /// Residual contributions (`ru` on full dofs, `rl` on multipliers, both added to) and
    /// tangent triplets over extended ids (multiplier k is `ndof + mult_base + k`).
    #[allow(clippy::too_many_arguments)] // state in, three accumulators out
    pub fn contribute(
        &self,
        mesh: &Mesh,
        u: &[f64],
        lam: &[f64],
        ru: &mut [f64],
        rl: &mut [f64],
        k: &mut Triplets,
        mult_base: usize,
    ) {
        let ndof = 2 * mesh.num_nodes();
        let rho = self.opts.rho;
        let nmult = self.mult_nodes.len();
        let lambda_floor = 1e-8 * lam[..nmult].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..self.points.len() {
            let p = &self.points[i];
            let e = self.eval(mesh, u, i);
            let lp = self.point_lambda(mesh, i, &e.ns, lam);
            let chi = p.active && !p.excluded;
            let sc = self.slave.cells[p.cell];
            let mc = self.master.cells[p.master];
            let snodes = mesh.cell_nodes(sc);
            let mnodes = mesh.cell_nodes(mc);
            // B over (dof id, value)
            let mut b: Vec<(usize, f64)> = vec![];
            for (a, &n) in snodes.iter().enumerate() {
                b.push((2 * n, e.ns[a] * e.normal[0]));
                b.push((2 * n + 1, e.ns[a] * e.normal[1]));
            }
            for (a, &n) in mnodes.iter().enumerate() {
                b.push((2 * n, -e.nm[a] * e.normal[0]));
                b.push((2 * n + 1, -e.nm[a] * e.normal[1]));
            }
            // (an excluded node's multiplier stays zero by its own row)
            let mults: Vec<(usize, f64)> = snodes
                .iter()
                .enumerate()
                .filter(|(_, n)| {
                    self.opts.node_to_segment || !self.opts.contact_excluded.contains(n)
                })
                .map(|(a, n)| (self.mult_of[n], e.ns[a]))
                .collect();
            let w = p.omega;
            // Penalty (node-to-segment): the force is λ itself and the row d + λ/k = 0;
            // otherwise the augmented λ̂ = λ − ρ d with d = 0.
            let rho_u = if self.opts.penalty.is_some() {
                0.0
            } else {
                rho
            };
            let lhat = lp - rho_u * e.d;
            if chi {
                for &(dof, bv) in &b {
                    ru[dof] += -w * lhat * bv;
                }
                for &(m, nv) in &mults {
                    rl[m] += -w * e.d * nv;
                }
                if let Some(kp) = self.opts.penalty {
                    for &(m, nv) in &mults {
                        rl[m] += -w * lp / kp * nv;
                        for &(m2, n2) in &mults {
                            k.add(
                                ndof + mult_base + m,
                                ndof + mult_base + m2,
                                -w / kp * nv * n2,
                            );
                        }
                    }
                }
            } else {
                for &(m, nv) in &mults {
                    rl[m] += -w * lp / rho * nv;
                }
            }
            // Variations of the projection and of the master frame (normal part and friction):
            //   δξ̄ = [(δx_s − Σ N_m δu_m)·t + d n·Σ N_m' δu_m] / (|t|² − d n·t'')
            //   δn  = −τ (n·δt)/|t|,  δτ = n (n·δt)/|t|,  δt = Σ N_m' δu_m + t'' δξ̄
            // as coefficient lists over dofs: cxi for δξ̄, cn for (n·δt)/|t|.
            let mut geo: Option<(OwnedCoefs, OwnedCoefs)> = None;
            if (chi || self.opts.friction.is_some()) && !e.clamped {
                let tn2 = e.t[0] * e.t[0] + e.t[1] * e.t[1];
                let (sn, ds) = (e.seg_normal, e.d_seg);
                let den = tn2 - ds * (sn[0] * e.tt[0] + sn[1] * e.tt[1]);
                let lt = tn2.sqrt();
                let mut cxi: Vec<(usize, f64)> = vec![];
                for (a, &n) in snodes.iter().enumerate() {
                    cxi.push((2 * n, e.ns[a] * e.t[0] / den));
                    cxi.push((2 * n + 1, e.ns[a] * e.t[1] / den));
                }
                for (a, &n) in mnodes.iter().enumerate() {
                    for comp in 0..2 {
                        cxi.push((
                            2 * n + comp,
                            (-e.nm[a] * e.t[comp] + ds * e.dnm[a] * sn[comp]) / den,
                        ));
                    }
                }
                let ntt = sn[0] * e.tt[0] + sn[1] * e.tt[1];
                let mut cn: Vec<(usize, f64)> =
                    cxi.iter().map(|&(dof, v)| (dof, ntt * v / lt)).collect();
                for (a, &n) in mnodes.iter().enumerate() {
                    for comp in 0..2 {
                        cn.push((2 * n + comp, e.dnm[a] * sn[comp] / lt));
                    }
                }
                if e.smoothed {
                    let at = |n: usize| Self::current(mesh, u, n);
                    cn = smoothed_frame(
                        mesh,
                        &self.master,
                        &self.master_cells_of_node,
                        &at,
                        p.master,
                        e.xi_m,
                        Some(&cxi),
                    )
                    .2;
                }
                geo = Some((cxi, cn));
            }
            if let (true, Some((cxi, cn))) = (chi, &geo) {
                // −ω λ̂ ∂B/∂u: B moves with the master normal n and the projection ξ̄.
                let f = -w * lhat;
                for (a, &n) in snodes.iter().enumerate() {
                    for comp in 0..2 {
                        for &(col, v) in cn.iter() {
                            k.add(2 * n + comp, col, f * e.ns[a] * (-e.tau[comp]) * v);
                        }
                    }
                }
                for (a, &n) in mnodes.iter().enumerate() {
                    for comp in 0..2 {
                        for &(col, v) in cxi.iter() {
                            k.add(2 * n + comp, col, f * (-e.dnm[a] * e.normal[comp]) * v);
                        }
                        for &(col, v) in cn.iter() {
                            k.add(2 * n + comp, col, f * (-e.nm[a]) * (-e.tau[comp]) * v);
                        }
                    }
                }
            }
            if chi {
                for &(r, br) in &b {
                    for &(cc, bc) in &b {
                        k.add(r, cc, rho_u * w * br * bc);
                    }
                    for &(m, nv) in &mults {
                        k.add(r, ndof + mult_base + m, -w * br * nv);
                        k.add(ndof + mult_base + m, r, -w * br * nv);
                    }
                }
                // smoothed normal: δd = B·δu − (t·n) δξ̄ − ((x_s − x̄)·τ) ω (it is not normal
                // to the cell, and turns with the neighbouring cells)
                if let (Some((cxi, cn)), true) = (&geo, e.smoothed) {
                    let extra = cxi
                        .iter()
                        .map(|&(col, v)| (col, e.tn * v))
                        .chain(cn.iter().map(|&(col, v)| (col, e.tq * v)));
                    for (col, v) in extra {
                        for &(m, nv) in &mults {
                            k.add(ndof + mult_base + m, col, w * nv * v);
                        }
                        for &(r, br) in &b {
                            k.add(r, col, -rho_u * w * br * v);
                        }
                    }
                }
            } else {
                for &(m1, n1) in &mults {
                    for &(m2, n2) in &mults {
                        k.add(
                            ndof + mult_base + m1,
                            ndof + mult_base + m2,
                            -w / rho * n1 * n2,
                        );
                    }
                }
            }
            if let Some(mu) = self.opts.friction {
                let fp = FrictionPoint {
                    lambda_floor,
                    mu,
                    w,
                    lp,
                    chi,
                    e: &e,
                    snodes,
                    mnodes,
                    geo: geo.as_ref().map(|(a, b)| (a.as_slice(), b.as_slice())),
                };
                self.friction_point(&fp, u, lam, ru, rl, k, ndof + mult_base);
            }
        }
        // weightless multipliers (no point weighs them): λ = 0 by a row on the scale of the
        // inactive ones (−ω λ / ρ)
        let wmax = self.points.iter().fold(0.0f64, |m, p| m.max(p.omega));
        for (m, _) in self.weightless.iter().enumerate().filter(|w| *w.1) {
            if !self.opts.node_to_segment {
                let s = wmax / rho;
                rl[m] += -s * lam[m];
                k.add(ndof + mult_base + m, ndof + mult_base + m, -s);
            }
        }
        if self.opts.friction.is_some() {
            // excluded nodes: Λ = 0 by a unit row
            let nm = self.mult_nodes.len();
            for &n in &self.opts.friction_excluded {
                if let Some(&m) = self.mult_of.get(&n) {
                    rl[nm + m] += lam[nm + m];
                    k.add(ndof + mult_base + nm + m, ndof + mult_base + nm + m, 1.0);
                }
            }
            for m in 0..nm {
                let excluded = self.opts.friction_excluded.contains(&self.mult_nodes[m]);
                if self.weightless[m] && !self.opts.node_to_segment && !excluded {
                    rl[nm + m] += lam[nm + m];
                    k.add(ndof + mult_base + nm + m, ndof + mult_base + nm + m, 1.0);
                }
            }
        }
        // The pattern: explicit zeros over every coupling a slave cell may have, so that
        // status and pairing changes within the candidates keep the pattern (and the
        // symbolic factorisation) unchanged. The matrix keeps a pattern once built, so the
        // zeros are sent only while the candidates have changed since they were last sent.
        if self.pattern_sent.get() == Some(self.candidates_generation) {
            return;
        }
        self.pattern_sent.set(Some(self.candidates_generation));
        // A point reads its slave cell and one master cell with the cells next to it (the
        // smoothed normal's vertex normals): the pattern couples the slave cell's dofs and
        // multipliers with each candidate's stencil, and each stencil with itself, not every
        // candidate with every other (a long slave cell far from the contact zone has
        // hundreds of small master cells within reach: their clique made the pattern, and
        // its memory, grow as the square of the refinement).
        let nm = self.mult_nodes.len();
        let mut cliques = vec![];
        for (ic, &sc) in self.slave.cells.iter().enumerate() {
            // a slave cell with no master cell within reach has no coupling (yet)
            let mut own: Vec<usize> = vec![];
            if !self.candidates[ic].is_empty() {
                for &n in mesh.cell_nodes(sc) {
                    own.extend([2 * n, 2 * n + 1]);
                }
            }
            let mults: Vec<usize> = mesh
                .cell_nodes(sc)
                .iter()
                .map(|n| ndof + mult_base + self.mult_of[n])
                .collect();
            if self.opts.friction.is_some() {
                let friction: Vec<usize> = mults.iter().map(|m| m + nm).collect();
                own.extend(friction);
            }
            own.extend(mults);
            if self.candidates[ic].is_empty() {
                cliques.push(own.clone());
            }
            for &im in &self.candidates[ic] {
                let mut stencil = own.clone();
                for &n in mesh.cell_nodes(self.master.cells[im]) {
                    for &jm in self.master_cells_of_node.get(&n).into_iter().flatten() {
                        for &m in mesh.cell_nodes(self.master.cells[jm]) {
                            stencil.extend([2 * m, 2 * m + 1]);
                        }
                    }
                }
                stencil.sort_unstable();
                stencil.dedup();
                cliques.push(stencil);
            }
        }
        k.add_clique_union(&cliques);
    }

    /// Re-pairs and updates the statuses from the iterate (u, λ); returns the number of changes.
    pub fn update_status(&mut self, mesh: &Mesh, u: &[f64], lam: &[f64]) -> usize {
        self.pair_all(mesh, u);
        let mut changes = 0;
        self.changed.clear();
        for i in 0..self.points.len() {
            let e = self.eval(mesh, u, i);
            let lp = self.point_lambda(mesh, i, &e.ns, lam);
            let p = &self.points[i];
            let active = !p.excluded && lp - self.opts.rho * e.d < 0.0;
            if active != p.active {
                let cell = p.cell;
                changes += 1;
                self.points[i].active = active;
                // (the slave node nearest the point)
                let (a, _) =
                    e.ns.iter().enumerate().fold(
                        (0, f64::MIN),
                        |b, (a, &v)| {
                            if v > b.1 {
                                (a, v)
                            } else {
                                b
                            }
                        },
                    );
                self.changed
                    .push(mesh.cell_nodes(self.slave.cells[cell])[a]);
            }
        }
        changes
    }

    pub fn commit(&mut self, u: &[f64], lam: &[f64]) {
        self.save_start();
        self.u_start.copy_from_slice(u);
        if self.opts.friction.is_some() && self.opts.tangential_penalty.is_some() {
            // (the tangential multipliers are the forces)
            let nm = self.mult_nodes.len();
            self.q_start.copy_from_slice(&lam[nm..2 * nm]);
        }
    }

    pub fn restore(&mut self) {
        for (p, s) in self.points.iter_mut().zip(&self.saved) {
            p.active = s.active;
            p.master = s.master;
            p.xi_m = s.xi_m;
            p.excluded = s.excluded;
        }
    }

    /// Contact pressure at each slave node from the multipliers: (node, −λ).
    pub fn nodal_pressures(&self, lam: &[f64]) -> Vec<(usize, f64)> {
        let mut p: Vec<f64> = (0..self.mult_nodes.len())
            .map(|k| {
                if self.weightless[k] {
                    0.0
                } else {
                    -lam[k] / self.node_weight[k]
                }
            })
            .collect();
        super::axis::fill_weightless(&self.mult_coords, &mut p, &self.reported_from_neighbours);
        self.mult_nodes.iter().copied().zip(p).collect()
    }

    /// The friction terms' dependence on the geometry: the slip Δw = τ·(Σ N_s Δu_s −
    /// Σ N_m(ξ̄) Δu_m) and the direction T = (N_s τ, −N_m τ) of the tangential force both
    /// turn with τ and slide with ξ̄ (Δu: displacement since the step start).
    #[allow(clippy::too_many_arguments)]
    fn friction_geometry(
        &self,
        fp: &FrictionPoint,
        u: &[f64],
        tv: &[(usize, f64)],
        cxi: &[(usize, f64)],
        cn: &[(usize, f64)],
        q: f64,
        stick: Option<(f64, f64)>,
        k: &mut Triplets,
        fm: &[(usize, f64)],
        mbase: usize,
    ) {
        let e = fp.e;
        let w = fp.w;
        let du = |n: usize, c: usize| u[2 * n + c] - self.u_start[2 * n + c];
        let mut big_du = [0.0; 2];
        for c in 0..2 {
            for (a, &n) in fp.snodes.iter().enumerate() {
                big_du[c] += e.ns[a] * du(n, c);
            }
            for (b, &n) in fp.mnodes.iter().enumerate() {
                big_du[c] -= e.nm[b] * du(n, c);
            }
        }
        let n_du = e.normal[0] * big_du[0] + e.normal[1] * big_du[1];
        let tdu_m: f64 = fp
            .mnodes
            .iter()
            .enumerate()
            .map(|(b, &n)| e.dnm[b] * (e.tau[0] * du(n, 0) + e.tau[1] * du(n, 1)))
            .sum();
        // geometric part of δΔw
        let g_dw: Vec<(usize, f64)> = cn
            .iter()
            .map(|&(col, v)| (col, n_du * v))
            .chain(cxi.iter().map(|&(col, v)| (col, -tdu_m * v)))
            .collect();
        // sticking: the force on the dofs T and the stick rows depend on Δw, with these
        // coefficients
        if let Some((force, row)) = stick {
            for &(d, v) in tv.iter().filter(|_| force != 0.0) {
                for &(col, gv) in &g_dw {
                    k.add(d, col, force * v * gv);
                }
            }
            for &(m, nv) in fm {
                for &(col, gv) in &g_dw {
                    k.add(mbase + m, col, row * nv * gv);
                }
            }
        }
        // −ω q δT: slave rows N_s n_c (n·δt)/|t|; master rows −N_m' τ_c δξ̄ − N_m n_c (n·δt)/|t|
        for (a, &n) in fp.snodes.iter().enumerate() {
            for c in 0..2 {
                for &(col, v) in cn {
                    k.add(2 * n + c, col, -w * q * e.ns[a] * e.normal[c] * v);
                }
            }
        }
        for (b, &n) in fp.mnodes.iter().enumerate() {
            for c in 0..2 {
                for &(col, v) in cxi {
                    k.add(2 * n + c, col, w * q * e.dnm[b] * e.tau[c] * v);
                }
                for &(col, v) in cn {
                    k.add(2 * n + c, col, w * q * e.nm[b] * e.normal[c] * v);
                }
            }
        }
    }

    /// Coulomb friction at one contact point (contact.md §1.8): with the semi-multiplier
    /// Λ (|Λ| ≤ 1) and the slip Δw since the start of the step along the master tangent,
    /// t = Λ + ρ_f Δw; stick if |t| ≤ 1 (then Δw = 0 weakly), slip otherwise (Λ = ±1);
    /// the tangential traction is μ|λ||Λ|. No contact (or λ = 0): Λ = 0.
    #[allow(clippy::too_many_arguments)]
    fn friction_point(
        &self,
        fp: &FrictionPoint,
        u: &[f64],
        lam: &[f64],
        ru: &mut [f64],
        rl: &mut [f64],
        k: &mut Triplets,
        mbase: usize,
    ) {
        let nm = self.mult_nodes.len();
        let e = fp.e;
        let (w, mu, lp) = (fp.w, fp.mu, fp.lp);
        let rho_f = self.opts.rho_f;
        // T over dofs: slave N_s τ, master −N_m τ; Δw = Tᵀ (u − u_start)
        let mut tv: Vec<(usize, f64)> = vec![];
        let mut dw = 0.0;
        for (a, &n) in fp.snodes.iter().enumerate() {
            for c in 0..2 {
                tv.push((2 * n + c, e.ns[a] * e.tau[c]));
                dw += e.ns[a] * e.tau[c] * (u[2 * n + c] - self.u_start[2 * n + c]);
            }
        }
        for (b, &n) in fp.mnodes.iter().enumerate() {
            for c in 0..2 {
                tv.push((2 * n + c, -e.nm[b] * e.tau[c]));
                dw -= e.nm[b] * e.tau[c] * (u[2 * n + c] - self.u_start[2 * n + c]);
            }
        }
        let excluded = |n: usize| self.opts.friction_excluded.contains(&n);
        // friction multipliers (index, N_s) of this cell; excluded nodes keep their unit row
        let fm: Vec<(usize, f64)> = fp
            .snodes
            .iter()
            .enumerate()
            .filter(|(_, n)| !excluded(**n))
            .map(|(a, n)| (nm + self.mult_of[n], e.ns[a]))
            .collect();
        let nmults: Vec<(usize, f64)> = fp
            .snodes
            .iter()
            .enumerate()
            .map(|(a, n)| (self.mult_of[n], e.ns[a]))
            .collect();
        let big_l: f64 = fp
            .snodes
            .iter()
            .enumerate()
            .map(|(a, n)| e.ns[a] * lam[nm + self.mult_of[n]])
            .sum();
        if let (true, Some(k_t)) = (fp.chi, self.opts.tangential_penalty) {
            let pen = Penalty {
                k_t,
                tv: &tv,
                fm: &fm,
                nmults: &nmults,
                q: big_l,
                dw,
            };
            self.penalty_friction(fp, &pen, u, ru, rl, k, mbase);
            return;
        }
        // Friction needs a pressure: a point with (numerically) no normal multiplier gets the
        // "no contact" row, as an exactly zero λ does in the reference, so that the slip row
        // μ λ (Λ − sign t) / ρ_f never degenerates.
        if !fp.chi || lp >= -fp.lambda_floor {
            for &(m, nv) in &fm {
                rl[m] += w * big_l * nv;
                for &(m2, n2) in &fm {
                    k.add(mbase + m, mbase + m2, w * nv * n2);
                }
            }
            return;
        }
        let (t, law) = friction::state(big_l, dw, rho_f);
        if let Some((cxi, cn)) = fp.geo {
            // q = μ λ t (stick: μ λ (Λ + ρ_f Δw)) or μ λ sign(t) (slip)
            let q = friction::traction(mu, lp, t, law);
            let stick =
                (law == friction::State::Stick).then_some((-w * mu * lp * rho_f, -w * mu * lp));
            self.friction_geometry(fp, u, &tv, cxi, cn, q, stick, k, &fm, mbase);
        }
        if law == friction::State::Stick {
            let q = friction::traction(mu, lp, t, law); // μ λ t
            for &(d, v) in &tv {
                ru[d] += -w * q * v;
                for &(d2, v2) in &tv {
                    k.add(d, d2, -w * mu * lp * rho_f * v * v2);
                }
                for &(m, nv) in &fm {
                    k.add(d, mbase + m, -w * mu * lp * v * nv);
                    k.add(mbase + m, d, -w * mu * lp * nv * v);
                }
                for &(m, nv) in &nmults {
                    k.add(d, mbase + m, -w * mu * t * v * nv);
                }
            }
            for &(m, nv) in &fm {
                rl[m] += -w * mu * lp * dw * nv;
                for &(m2, n2) in &nmults {
                    k.add(mbase + m, mbase + m2, -w * mu * dw * nv * n2);
                }
            }
        } else {
            let sg = t.signum();
            let q = friction::traction(mu, lp, t, law); // μ λ sign(t)
            for &(d, v) in &tv {
                ru[d] += -w * q * v;
                for &(m, nv) in &nmults {
                    k.add(d, mbase + m, -w * mu * sg * v * nv);
                }
            }
            for &(m, nv) in &fm {
                rl[m] += w * mu * lp * (big_l - sg) / rho_f * nv;
                for &(m2, n2) in &fm {
                    k.add(mbase + m, mbase + m2, w * mu * lp / rho_f * nv * n2);
                }
                for &(m2, n2) in &nmults {
                    k.add(
                        mbase + m,
                        mbase + m2,
                        w * mu * (big_l - sg) / rho_f * nv * n2,
                    );
                }
            }
        }
    }
}

/// What a tangential-penalty point needs besides the normal terms.
struct Penalty<'a> {
    k_t: f64,
    /// T over dofs (slave N_s τ, master −N_m τ), the friction multipliers and the normal
    /// ones of the cell with their N_s
    tv: &'a [(usize, f64)],
    fm: &'a [(usize, f64)],
    nmults: &'a [(usize, f64)],
    /// the tangential force at the point (its multiplier) and the slip since the step start
    q: f64,
    dw: f64,
}

impl PointToSegment {
    /// Coulomb friction with a tangential penalty k_t at an active point: the tangential
    /// multiplier Q is the force on the slave along τ (not a semi-multiplier: at λ = 0 a
    /// multiplier scaled by μλ would be undetermined, and a body held by friction alone
    /// would start singular). With the trial force q_tr = q_start − k_t Δw and the cone
    /// μ max(−λ, 0): stick if |q_tr| ≤ the cone (row Q = q_tr), otherwise slip (row
    /// Q = cone · sign q_tr). The force −Q T goes to the dofs.
    #[allow(clippy::too_many_arguments)]
    fn penalty_friction(
        &self,
        fp: &FrictionPoint,
        pen: &Penalty,
        u: &[f64],
        ru: &mut [f64],
        rl: &mut [f64],
        k: &mut Triplets,
        mbase: usize,
    ) {
        let (e, w, mu, lp) = (fp.e, fp.w, fp.mu, fp.lp);
        let q_start: f64 = fp
            .snodes
            .iter()
            .enumerate()
            .map(|(a, n)| e.ns[a] * self.q_start[self.mult_of[n]])
            .sum();
        let trial = q_start - pen.k_t * pen.dw;
        let cone = mu * (-lp).max(0.0);
        let stick = trial.abs() <= cone;
        if let Some((cxi, cn)) = fp.geo {
            let rows = stick.then_some((0.0, w * pen.k_t));
            self.friction_geometry(fp, u, pen.tv, cxi, cn, pen.q, rows, k, pen.fm, mbase);
        }
        for &(d, v) in pen.tv {
            ru[d] += -w * pen.q * v;
            for &(m, nv) in pen.fm {
                k.add(d, mbase + m, -w * v * nv);
            }
        }
        let sg = trial.signum();
        let target = if stick { trial } else { cone * sg };
        for &(m, nv) in pen.fm {
            rl[m] += w * (pen.q - target) * nv;
            for &(m2, n2) in pen.fm {
                k.add(mbase + m, mbase + m2, w * nv * n2);
            }
            if stick {
                for &(d, v) in pen.tv {
                    k.add(mbase + m, d, w * pen.k_t * nv * v);
                }
            } else if lp < 0.0 {
                for &(m2, n2) in pen.nmults {
                    k.add(mbase + m, mbase + m2, w * mu * sg * nv * n2);
                }
            }
        }
    }
}

/// Master cells within reach of each slave cell on the initial geometry: those whose
/// bounding box, grown by `margin` times the larger of the two cells' sizes, meets the
/// slave cell's.
pub fn initial_candidates(
    mesh: &Mesh,
    slave: &Surface,
    master: &Surface,
    margin: f64,
) -> Vec<Vec<usize>> {
    candidates_at(mesh, None, slave, master, margin)
}

/// The same on the geometry displaced by `u` (full dofs), when given.
pub fn candidates_at(
    mesh: &Mesh,
    u: Option<&[f64]>,
    slave: &Surface,
    master: &Surface,
    margin: f64,
) -> Vec<Vec<usize>> {
    candidates_within(mesh, u, slave, master, margin, 0.0)
}

/// The same, the boxes grown by at least `reach` (a distance).
pub fn candidates_within(
    mesh: &Mesh,
    u: Option<&[f64]>,
    slave: &Surface,
    master: &Surface,
    margin: f64,
    reach: f64,
) -> Vec<Vec<usize>> {
    let bbox = |c: usize| {
        let mut lo = [f64::MAX; 2];
        let mut hi = [f64::MIN; 2];
        for &n in mesh.cell_nodes(c) {
            for d in 0..2 {
                let x = mesh.coords[n][d] + u.map_or(0.0, |u| u[2 * n + d]);
                lo[d] = lo[d].min(x);
                hi[d] = hi[d].max(x);
            }
        }
        (lo, hi)
    };
    let mboxes: Vec<_> = master.cells.iter().map(|&c| bbox(c)).collect();
    slave
        .cells
        .iter()
        .map(|&sc| {
            let (slo, shi) = bbox(sc);
            let ssize = (shi[0] - slo[0]).hypot(shi[1] - slo[1]);
            mboxes
                .iter()
                .enumerate()
                .filter(|(_, (lo, hi))| {
                    let r = (margin * ssize.max((hi[0] - lo[0]).hypot(hi[1] - lo[1]))).max(reach);
                    (0..2).all(|d| lo[d] - r <= shi[d] && slo[d] <= hi[d] + r)
                })
                .map(|(i, _)| i)
                .collect()
        })
        .collect()
}

impl super::pair::ContactPair for PointToSegment {
    fn num_multipliers(&self) -> usize {
        self.num_multipliers()
    }
    fn initialise(&mut self, mesh: &Mesh) {
        self.initialise(mesh)
    }
    fn contribute(
        &self,
        mesh: &Mesh,
        u: &[f64],
        lam: &[f64],
        ru: &mut [f64],
        rl: &mut [f64],
        k: &mut Triplets,
        mult_base: usize,
    ) {
        self.contribute(mesh, u, lam, ru, rl, k, mult_base)
    }
    fn update_status(&mut self, mesh: &Mesh, u: &[f64], lam: &[f64]) -> usize {
        self.update_status(mesh, u, lam)
    }
    fn commit(&mut self, u: &[f64], lam: &[f64]) {
        self.commit(u, lam)
    }
    fn restore(&mut self) {
        self.restore()
    }
    fn multiplier_nodes(&self) -> &[usize] {
        &self.mult_nodes
    }
    fn excluded_nodes(&self) -> &[usize] {
        &self.opts.contact_excluded
    }
    fn changed_nodes(&self) -> Vec<usize> {
        self.changed.clone()
    }
    fn open_at_rest(&mut self, mesh: &Mesh) -> bool {
        let u = vec![0.0; 2 * mesh.num_nodes()];
        // (round-off of a touching point's gap: a millionth of the touch tolerance)
        let tol = 1e-6 * self.touch_tolerance(mesh);
        let penetrating = (0..self.points.len()).any(|i| {
            let p = &self.points[i];
            !p.excluded && !p.left_out && self.eval(mesh, &u, i).d > tol
        });
        if penetrating {
            return false;
        }
        for p in &mut self.points {
            p.active = false;
        }
        true
    }
    fn surfaces(&self) -> (&Surface, &Surface) {
        (&self.slave, &self.master)
    }
    fn nodal_pressures(&self, lam: &[f64]) -> Vec<(usize, f64)> {
        self.nodal_pressures(lam)
    }
    fn nodal_shear(&self, lam: &[f64]) -> Vec<(usize, f64)> {
        // traction μ λ Λ (λ < 0 in compression): its magnitude is μ p |Λ| ≤ μ p
        let Some(mu) = self.opts.friction else {
            return vec![];
        };
        let nm = self.mult_nodes.len();
        // (with a tangential penalty the multiplier is the force itself)
        let scale = |k: usize| match self.opts.tangential_penalty {
            Some(_) => 1.0,
            None => mu * lam[k],
        };
        self.mult_nodes
            .iter()
            .enumerate()
            .map(|(k, &n)| (n, scale(k) * lam[nm + k] / self.node_weight[k]))
            .collect()
    }
    fn friction(&self) -> f64 {
        self.opts.friction.unwrap_or(0.0)
    }
}
