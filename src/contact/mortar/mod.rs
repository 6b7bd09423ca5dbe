//! The `mortar` formulation: segment-to-segment mortar with dual multipliers on the slave
//! nodes, nodal weighted gaps and a nodal active set (semi-smooth Newton on the
//! complementarity function), averaged slave normals (contact.md §5.2).
//!
//! For each slave cell the master cells it faces are found by projecting along the slave
//! normal field n(ξ) = Σ N_k n_k (nodal normals averaged over the adjacent slave cells);
//! each overlap segment is integrated with Gauss points. With the dual basis Φ_j
//! (∫ Φ_j N_k = δ_jk ∫ N_k on each cell):
//!   weighted gap  g̃_j = ∫ Φ_j (x_m − x_s)·n̂ dγ          (open > 0)
//!   forces        slave  +λ_j ∫ Φ_j N_s n̂ dγ,   master  −λ_j ∫ Φ_j N_m n̂ dγ   (in r = f_int − f_ext + …)
//! λ_j ≥ 0 is the contact pressure at slave node j. Node j is active iff λ_j − c g̃_j/D_j > 0
//! (D_j = ∫ N_j); active rows enforce g̃_j = 0, inactive ones λ_j = 0.
//!
//! n̂ is the slave normal field with large kinematics (the surfaces in contact coincide in
//! the current configuration); with small kinematics, whose geometry is the reference one,
//! the bisector of the slave and master normal fields, so that the answer does not depend
//! on which side is the slave.
//!
//! Coulomb friction: tangential multipliers t_j (tractions) on the same dual basis, weighted
//! slips s̃_j = ∫ Φ_j (Δu_s − Δu_m)·τ̂ since the step start, and per node no friction
//! (t_j = 0), stick (s̃_j = 0) or slip (t_j = μ λ_j sign(t_j + c s̃_j / D_j)).
//!
//! | file | what |
//! |---|---|
//! | `mod.rs` | the pair's state, its construction, the pattern's candidates, the pairing's reach |
//! | `contact_pair.rs` | the `ContactPair` impl: initialisation, residual and tangent assembly, statuses, outputs |
//! | `geometry.rs` | positions, slave and master normal fields, the axisymmetric measure |
//! | `segments.rs` | one slave cell's terms: dual basis, overlap segments, weighted gaps, forces, slips |
//! | `active_set.rs` | initial contact, nodal weighted gaps and D_j, row weights |
//! | `friction.rs` | the Coulomb branch of a slave node |
//! | `linearisation.rs` | the exact tangent: linear terms (small kinematics) or dual numbers |
//! | `sides.rs` | which surface carries the multipliers: the coarser where they face |

mod active_set;
mod contact_pair;
mod friction;
mod geometry;
mod linearisation;
mod segments;
mod sides;

pub use sides::multiplier_side;

use super::point_segment::{initial_candidates, pattern_candidates_within};
use super::surface::Surface;
use crate::fem::material::Modelisation;
use crate::mesh::Mesh;
use friction::Branch;
use segments::CellTerms;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize};

/// The matrix pattern holds the couplings of the master cells within this many sizes of
/// the smaller cell of each slave cell near the master (the pairing itself uses one of
/// the larger), so that a contact zone growing under load re-pairs inside it.
pub(crate) const PATTERN_MARGIN: f64 = 3.0;

pub struct Mortar {
    pub slave: Surface,
    pub master: Surface,
    /// Complementarity parameter c (stress / length).
    pub c: f64,
    pub mult_nodes: Vec<usize>,
    mult_of: HashMap<usize, usize>,
    /// slave cells around each slave node (for the averaged normals)
    cells_of_node: HashMap<usize, Vec<usize>>,
    /// master cells around each master corner node (small kinematics: the master's averaged
    /// normals enter the interface normal)
    master_cells_of_node: HashMap<usize, Vec<usize>>,
    /// The master chain's end nodes (none on a closed chain).
    master_ends: Vec<usize>,
    candidates: Vec<Vec<usize>>,
    /// Per slave cell, a superset of its candidates over the whole solve once it is
    /// `reserved` (those within PATTERN_MARGIN initially, those anticipated, and every
    /// candidate found since): the matrix pattern covers their couplings, so re-pairing
    /// as the bodies deform keeps it (and its analysis).
    pattern_candidates: Vec<Vec<usize>>,
    /// The slave cells whose couplings the pattern holds: those near the master at the
    /// start (within PATTERN_MARGIN of the smaller cell), near it at the geometry predicted
    /// for the loading's end (`anticipate`), or with a node that has carried a multiplier.
    /// Another cell's nodes are open with zero multipliers: their rows hold their diagonal
    /// alone and their columns are left out of the tangent (exact: their corrections are
    /// zero), so they couple nothing. On a graded mesh the coarse slave cells far from the
    /// contact overlap many fine master cells; their couplings brought those cells' nodes
    /// into the contact interface the solver condenses on (SSNP154 D with mortar at 93k
    /// unknowns: 1782 displacement unknowns there, of which contact coupled 854).
    reserved: Vec<bool>,
    /// Changes whenever `pattern_candidates` grows; the generation whose pattern zeros
    /// `contribute` last sent (usize::MAX: none yet).
    pattern_generation: usize,
    pattern_sent: AtomicUsize,
    /// Whether `contribute` writes the tangent (see `ContactPair::set_tangent_wanted`).
    tangent_wanted: AtomicBool,
    /// Whether the tangent keeps the augmentation's curvature (see `exact_tangent`).
    exact_augmentation: bool,
    /// The candidates at the start of the load step (restored when it is cut).
    saved_candidates: Vec<Vec<usize>>,
    active: Vec<bool>,
    saved: Vec<bool>,
    axisymmetric: bool,
    thickness: f64,
    small: bool,
    /// Open gaps (along the averaged normal) up to this count as closed at the start;
    /// None: only touching nodes (1e-6 of the cell size).
    pub initial_gap: Option<f64>,
    /// initial = "all": every node facing the master starts active.
    pub initial_all: bool,
    /// Initial gaps and overlaps up to this distance are removed, strain-free: the weighted
    /// gap of such a node is measured from its initial value (`offset`, set by `initialise`).
    /// For interfaces discretised differently on the two sides (linear chords against
    /// quadratic arcs) whose bodies fit in the geometry the mesh approximates.
    pub adjust: Option<f64>,
    offset: Vec<f64>,
    /// Coulomb coefficient (None: frictionless), and the multiplier indices of the slave
    /// nodes excluded from friction.
    pub friction: Option<f64>,
    pub friction_excluded: Vec<usize>,
    /// The multiplier indices of `exclude` (never in contact), and their nodes.
    pub contact_excluded: Vec<usize>,
    pub excluded_nodes: Vec<usize>,
    /// Multiplier nodes whose status the last `update_status` changed.
    changed: Vec<usize>,
    /// The smallest pressure scale of the constraint residual (when every multiplier is
    /// about zero, e.g. a contact that has opened, the rows are measured against this).
    pub pressure_floor: f64,
    /// Displacement at the start of the load step (slips are measured from it).
    u_start: Vec<f64>,
    /// Friction branch per node at the last status update, and at the start of the step: a
    /// change is a status change, so Newton does not stop on balanced displacement rows
    /// while the friction rows follow another branch.
    law: Vec<Branch>,
    saved_law: Vec<Branch>,
    /// Per slave node, the factor on c in the friction trial and how often its branch
    /// changed in the current step: a node that keeps switching gets a smaller factor
    /// (semi-smooth Newton cycles when c is large for the local tangential stiffness; the
    /// solution does not depend on c).
    trial_scale: Vec<f64>,
    switches: Vec<u32>,
    /// `trial_scale` and `switches` when small kinematics was switched on (restored when it
    /// is switched off: see `set_small_kinematics`).
    before_switch: (Vec<f64>, Vec<u32>),
    /// D_j of the last `contribute`, to express its constraint rows as pressures.
    last_d: std::sync::Mutex<Vec<f64>>,
    /// Multiplier indices of each slave cell's nodes (corners, then mid-side).
    cell_mults: Vec<Vec<usize>>,
    /// Initial positions of the slave nodes (multiplier order).
    mult_coords: Vec<[f64; 2]>,
    /// Compliance (1 − ν²)/E (plane stress: 1/E) of the body under each slave cell and
    /// each master cell: the weights of the small-kinematics interface normal (equal by
    /// default: the bisector).
    pub compliance: (Vec<f64>, Vec<f64>),
    /// Large kinematics: the constraints linearised at the last evaluation (for the
    /// active-set iterations at a fixed linearisation, `linearised_status`).
    linearisation: std::sync::Mutex<Option<active_set::Linearisation>>,
    /// The cells' terms `update_status` computed at its iterate (u, terms): Newton
    /// evaluates the residual at that same iterate next, which takes them instead of
    /// computing them again.
    terms_cache: std::sync::Mutex<Option<(Vec<f64>, Vec<CellTerms>)>>,
}

/// Adds the master cells `found` to a slave cell's pattern candidates. Whether any was new.
fn add_new(pattern: &mut Vec<usize>, found: &[usize]) -> bool {
    let mut grew = false;
    for &im in found {
        if !pattern.contains(&im) {
            pattern.push(im);
            grew = true;
        }
    }
    grew
}

impl Mortar {
    pub fn new(
        mesh: &Mesh,
        slave: Surface,
        master: Surface,
        c: f64,
        model: Modelisation,
        thickness: f64,
        small: bool,
    ) -> Self {
        let mult_nodes = slave.nodes.clone();
        let mult_of: HashMap<usize, usize> = mult_nodes
            .iter()
            .enumerate()
            .map(|(k, &n)| (n, k))
            .collect();
        let corner_cells = |s: &Surface| {
            let mut of: HashMap<usize, Vec<usize>> = HashMap::new();
            for (ic, &c) in s.cells.iter().enumerate() {
                for &n in &mesh.cell_nodes(c)[..2] {
                    of.entry(n).or_default().push(ic);
                }
            }
            of
        };
        let cells_of_node = corner_cells(&slave);
        let master_cells_of_node = corner_cells(&master);
        let mut master_ends: Vec<usize> = master_cells_of_node
            .iter()
            .filter(|(_, cells)| cells.len() == 1)
            .map(|(&n, _)| n)
            .collect();
        master_ends.sort_unstable();
        let cell_mults = slave
            .cells
            .iter()
            .map(|&c| mesh.cell_nodes(c).iter().map(|n| mult_of[n]).collect())
            .collect();
        let candidates = initial_candidates(mesh, &slave, &master, 1.0);
        let mut pattern_candidates =
            pattern_candidates_within(mesh, None, &slave, &master, PATTERN_MARGIN, 0.0);
        // (a cell near the master reserves its integration candidates too)
        for (pattern, near) in pattern_candidates.iter_mut().zip(&candidates) {
            if !pattern.is_empty() {
                add_new(pattern, near);
            }
        }
        let reserved = pattern_candidates.iter().map(|p| !p.is_empty()).collect();
        let mut m = Mortar {
            slave,
            master,
            c,
            mult_nodes,
            mult_of,
            cells_of_node,
            master_ends,
            master_cells_of_node,
            saved_candidates: candidates.clone(),
            pattern_candidates,
            reserved,
            pattern_generation: 0,
            pattern_sent: AtomicUsize::new(usize::MAX),
            tangent_wanted: AtomicBool::new(true),
            exact_augmentation: false,
            candidates,
            active: vec![],
            saved: vec![],
            axisymmetric: model == Modelisation::Axisymmetric,
            thickness,
            small,
            initial_gap: None,
            initial_all: false,
            adjust: None,
            offset: vec![],
            friction: None,
            friction_excluded: vec![],
            contact_excluded: vec![],
            excluded_nodes: vec![],
            changed: vec![],
            pressure_floor: 0.0,
            u_start: vec![0.0; 2 * mesh.num_nodes()],
            law: vec![],
            saved_law: vec![],
            trial_scale: vec![],
            switches: vec![],
            before_switch: Default::default(),
            last_d: Default::default(),
            cell_mults,
            mult_coords: vec![],
            compliance: (vec![], vec![]),
            linearisation: Default::default(),
            terms_cache: Default::default(),
        };
        m.compliance = (
            vec![1.0; m.slave.cells.len()],
            vec![1.0; m.master.cells.len()],
        );
        m.mult_coords = m.mult_nodes.iter().map(|&n| mesh.coords[n]).collect();
        m.active = vec![false; m.mult_nodes.len()];
        m.saved = m.active.clone();
        m
    }

    /// How far from a slave cell, on the deformed geometry, master cells are sought along
    /// its normal (large kinematics: inward only): the largest motion since the step
    /// start, rounded up to the smallest slave cell size times a power of two (so that the
    /// set changes only when the motion doubles: a changed set is a status change); 0 below
    /// one cell (the margin covers it).
    /// An iterate can carry a body many cells through another on a fine mesh; within one
    /// cell of the deformed slave the overlap was not seen, its nodes' weighted gaps were
    /// zero and could not close (SSNP154 A with small kinematics at 0.033 mm: the cylinder
    /// 0.34 mm inside the block at a "converged" state, 9 step cuts and a failure; every
    /// size and stepping from 0.3 to 0.033 mm: 300 Newton iterations, 27 cuts and 3 failed
    /// runs → 232, none and none).
    fn overlap_reach(&self, mesh: &Mesh, u: &[f64]) -> f64 {
        let motion = u
            .iter()
            .zip(&self.u_start)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        let h = self.slave.shortest_cell(mesh);
        if motion > h {
            h * (motion / h).log2().ceil().exp2()
        } else {
            0.0
        }
    }

    /// Reserves the pattern of the slave cells with a node in contact, or (`lam`) carrying
    /// a multiplier, and takes the current candidates of every reserved cell into the
    /// pattern. Whether the pattern grew (its generation then moves on).
    fn grow_pattern(&mut self, lam: Option<&[f64]>) -> bool {
        let nm = self.mult_nodes.len();
        let carries =
            |k: usize| lam.is_some_and(|l| l[k] != 0.0 || (l.len() >= 2 * nm && l[nm + k] != 0.0));
        let mut grew = false;
        for ic in 0..self.slave.cells.len() {
            if !self.reserved[ic] {
                if !self.cell_mults[ic]
                    .iter()
                    .any(|&k| self.active[k] || carries(k))
                {
                    continue;
                }
                self.reserved[ic] = true;
                grew = true;
            }
            grew |= add_new(&mut self.pattern_candidates[ic], &self.candidates[ic]);
        }
        if grew {
            self.pattern_generation += 1;
        }
        grew
    }

    /// Nodes whose positions the evaluation of slave cell ic may depend on over the
    /// solve (with the pattern's candidates).
    fn nodes_in_pattern(&self, mesh: &Mesh, ic: usize) -> Vec<usize> {
        self.nodes_with(mesh, ic, &self.pattern_candidates[ic])
    }

    fn nodes_with(&self, mesh: &Mesh, ic: usize, masters: &[usize]) -> Vec<usize> {
        let c = self.slave.cells[ic];
        let mut nodes: Vec<usize> = mesh.cell_nodes(c).to_vec();
        for &n in &mesh.cell_nodes(c)[..2] {
            for &jc in &self.cells_of_node[&n] {
                nodes.extend_from_slice(mesh.cell_nodes(self.slave.cells[jc]));
            }
        }
        for &im in masters {
            nodes.extend_from_slice(mesh.cell_nodes(self.master.cells[im]));
        }
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }
}

#[cfg(test)]
mod tests;
