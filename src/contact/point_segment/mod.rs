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
//!
//! | file | what |
//! |---|---|
//! | `mod.rs` | options, the pair's state, a contact point and its geometry |
//! | `construction.rs` | `new`: contact points, weights, multipliers; counts |
//! | `pairing.rs` | pairing points with master cells, projection, the point's geometry (`eval`), candidates anticipated at a predicted displacement |
//! | `residual.rs` | `contribute`: normal residual and tangent, the matrix pattern |
//! | `friction.rs` | Coulomb friction at a point: semi-multiplier or tangential penalty |
//! | `status.rs` | initial statuses, the active set update (on the iterate or on the linearisation), step commit and restore, pressures |
//! | `candidates.rs` | master cells within reach of each slave cell (also used by `mortar`) |
//! | `contact_pair.rs` | the `ContactPair` interface |
//! | `tests.rs` | anticipated candidates, pairing, statuses on the linearisation |

mod candidates;
mod construction;
mod contact_pair;
mod friction;
mod pairing;
mod residual;
mod status;

pub use candidates::{
    anticipated_candidates, candidates_within, initial_candidates, overlap_candidates,
    pattern_candidates_within, swept_candidates,
};

use super::surface::Surface;
use crate::fem::element::MAX_NODES;
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
    /// Friction augmentation ρ_f (the reference's COEF_FROT, 100, per unit length), raised
    /// at points of low pressure (`trial_stiffness`).
    pub rho_f: f64,
    /// The bodies' stiffness over the cell size, E/h (stress per length): the scale a
    /// point's friction trial is raised to where its pressure is low
    /// (`friction::balanced_rho_f`; 0: the pair's ρ_f at every point).
    pub trial_stiffness: f64,
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
            trial_stiffness: 0.0,
            friction_excluded: vec![],
            tangential_penalty: None,
            smoothed_normal: true,
        }
    }
}

/// A point is paired with the master surface only within this many times the larger of
/// its cell's and the nearest master cell's length, or inside the master body (`pair`).
/// The pattern holds the candidates within CANDIDATE_MARGIN times the smaller of the
/// cells' sizes (`pattern_candidates_within`), and takes in a paired point's cell once the
/// point is that near or in contact (`pair`), so that a body closing a gap of a few fine
/// cells pairs inside the initial pattern (no new analysis of the matrix).
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
    /// The boundary pieces of the master's body (none: rigid), where a point overlaps.
    master_pieces: Vec<[usize; 2]>,
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
    /// Per point, with friction: its Coulomb branch at the last status update (None: no
    /// friction there), how often its slip reversed its direction in this step, the
    /// factor on ρ_f of its trial (cut where it keeps reversing: `friction::count_reversal`),
    /// and its ρ_f balanced on its pressure at the last status update
    /// (`friction::balanced_rho_f`).
    law: Vec<Option<super::friction::State>>,
    /// Points whose Coulomb branch the last status update changed.
    branch_switches: usize,
    switches: Vec<u32>,
    trial_scale: Vec<f64>,
    balanced_rho_f: Vec<f64>,
}

/// Coefficients of a linear form over dofs: (dof, value).
type Coefs<'a> = &'a [(usize, f64)];
type OwnedCoefs = Vec<(usize, f64)>;

/// What the friction term of one point needs from the normal one.
struct FrictionPoint<'a> {
    mu: f64,
    /// the point's ρ_f (balanced on its pressure, times its trial factor)
    rho_f: f64,
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

#[cfg(test)]
mod tests;
