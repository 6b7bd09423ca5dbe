//! The `mortar` formulation (our default): segment-to-segment mortar with dual multipliers
//! on the slave nodes, nodal weighted gaps and a nodal active set (semi-smooth Newton on
//! the complementarity function), averaged slave normals (contact.md §5.2).
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
//! Linearisation: the derivatives of the weighted gaps and of the mortar force coefficients
//! with respect to the displacements are taken by central finite differences, cell by
//! cell (each perturbed dof only re-evaluates the slave cells that read it). They contain
//! every geometric variation (normals, segment ends, projections, Jacobians) to ~1e-8.
//!
//! Coulomb friction: tangential multipliers t_j (tractions) on the same dual basis, weighted
//! slips s̃_j = ∫ Φ_j (Δu_s − Δu_m)·τ̂ since the step start, and per node no friction
//! (t_j = 0), stick (s̃_j = 0) or slip (t_j = μ λ_j sign(t_j + c s̃_j / D_j)).

use super::pair::ContactPair;
use super::point_segment::{candidates_at, initial_candidates};
use super::projection::point_and_tangent;
use super::surface::Surface;
use crate::assembly::coupled::Triplets;
use crate::fem::element::{shape, shape_grad, MAX_NODES};
use crate::fem::material::Modelisation;
use crate::fem::quadrature::gauss_legendre;
use crate::mesh::Mesh;
use rayon::prelude::*;
use std::collections::HashMap;

/// The matrix pattern holds the couplings of the master cells within this many cell
/// sizes of each slave cell (the pairing itself uses one), so that a contact zone growing
/// under load re-pairs inside it.
const PATTERN_MARGIN: f64 = 3.0;

pub struct Mortar {
    pub slave: Surface,
    pub master: Surface,
    /// Complementarity parameter c (stress / length).
    pub c: f64,
    pub mult_nodes: Vec<usize>,
    mult_of: HashMap<usize, usize>,
    /// slave cells around each slave node (for the averaged normals)
    cells_of_node: HashMap<usize, Vec<usize>>,
    candidates: Vec<Vec<usize>>,
    /// A superset of the candidates over the whole solve (those within PATTERN_MARGIN
    /// cell sizes initially, and every candidate found since): the matrix pattern covers
    /// their couplings, so re-pairing as the bodies deform keeps it (and its analysis).
    pattern_candidates: Vec<Vec<usize>>,
    /// The candidates at the start of the load step (restored when it is cut).
    saved_candidates: Vec<Vec<usize>>,
    /// for each full dof read by some slave cell's evaluation, those cells
    readers: HashMap<usize, Vec<usize>>,
    saved_readers: HashMap<usize, Vec<usize>>,
    active: Vec<bool>,
    saved: Vec<bool>,
    axisymmetric: bool,
    thickness: f64,
    small: bool,
    /// Open gaps (along the averaged normal) up to this count as closed at the start;
    /// None: only touching nodes (1e-6 of the cell size).
    pub initial_gap: Option<f64>,
    /// Coulomb coefficient (None: frictionless), and the multiplier indices of the slave
    /// nodes excluded from friction.
    pub friction: Option<f64>,
    pub friction_excluded: Vec<usize>,
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
    /// D_j of the last `contribute`, to express its constraint rows as pressures.
    last_d: std::sync::Mutex<Vec<f64>>,
    /// Multiplier indices of each slave cell's nodes (corners, then mid-side).
    cell_mults: Vec<Vec<usize>>,
}

/// What one slave cell contributes: per slave node j (multiplier index) its weighted gap,
/// its D_j = ∫ N_j, and force coefficients (dof, value) per unit λ_j.
#[derive(Default, Clone)]
struct CellTerms {
    gap: Vec<(usize, f64)>,
    dj: Vec<(usize, f64)>,
    /// ∫ N_j over the parts of the cell that face the master surface
    cover: Vec<(usize, f64)>,
    force: Vec<(usize, usize, f64)>,
    /// With friction: weighted slips s̃_j = ∫ Φ_j (Δu_s − Δu_m)·τ̂ since the step start,
    /// and tangential force coefficients per unit traction t_j.
    slip: Vec<(usize, f64)>,
    tforce: Vec<(usize, usize, f64)>,
}

/// The Coulomb branch of a slave node: no friction (no contact or no pressure), stick, or
/// slip with the sign of the trial traction.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Branch {
    Free,
    Stick,
    Slip(f64),
}

/// Central-difference derivatives of one cell group's terms with respect to one dof:
/// weighted gaps, weights, forces (ordered: the triplets and the sums of duplicates come out
/// the same every time), slips and tangential forces.
struct DofDerivatives {
    dg: Vec<f64>,
    dd: Vec<f64>,
    df: std::collections::BTreeMap<(usize, usize), f64>,
    ds: Vec<f64>,
    dtf: std::collections::BTreeMap<(usize, usize), f64>,
}

/// Adds each slave cell's `found` master cells to its pattern candidates.
fn add_to_pattern(pattern: &mut [Vec<usize>], found: &[Vec<usize>]) {
    for (p, f) in pattern.iter_mut().zip(found) {
        for &im in f {
            if !p.contains(&im) {
                p.push(im);
            }
        }
    }
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
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
        let mut cells_of_node: HashMap<usize, Vec<usize>> = HashMap::new();
        for (ic, &c) in slave.cells.iter().enumerate() {
            for &n in &mesh.cell_nodes(c)[..2] {
                cells_of_node.entry(n).or_default().push(ic);
            }
        }
        let cell_mults = slave
            .cells
            .iter()
            .map(|&c| mesh.cell_nodes(c).iter().map(|n| mult_of[n]).collect())
            .collect();
        let candidates = initial_candidates(mesh, &slave, &master, 1.0);
        let mut pattern_candidates = initial_candidates(mesh, &slave, &master, PATTERN_MARGIN);
        add_to_pattern(&mut pattern_candidates, &candidates);
        let mut m = Mortar {
            slave,
            master,
            c,
            mult_nodes,
            mult_of,
            cells_of_node,
            saved_candidates: candidates.clone(),
            pattern_candidates,
            candidates,
            readers: HashMap::new(),
            saved_readers: HashMap::new(),
            active: vec![],
            saved: vec![],
            axisymmetric: model == Modelisation::Axisymmetric,
            thickness,
            small,
            initial_gap: None,
            friction: None,
            friction_excluded: vec![],
            pressure_floor: 0.0,
            u_start: vec![0.0; 2 * mesh.num_nodes()],
            law: vec![],
            saved_law: vec![],
            trial_scale: vec![],
            switches: vec![],
            last_d: Default::default(),
            cell_mults,
        };
        m.active = vec![false; m.mult_nodes.len()];
        m.saved = m.active.clone();
        m.build_readers(mesh);
        m.saved_readers = m.readers.clone();
        m
    }

    fn build_readers(&mut self, mesh: &Mesh) {
        self.readers.clear();
        for ic in 0..self.slave.cells.len() {
            for n in self.nodes_read(mesh, ic) {
                for d in [2 * n, 2 * n + 1] {
                    self.readers.entry(d).or_default().push(ic);
                }
            }
        }
    }

    /// Nodes whose positions the evaluation of slave cell ic depends on.
    fn nodes_read(&self, mesh: &Mesh, ic: usize) -> Vec<usize> {
        self.nodes_with(mesh, ic, &self.candidates[ic])
    }

    /// The same with the pattern's candidates (a superset).
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

    fn pos(mesh: &Mesh, u: &[f64], n: usize) -> [f64; 2] {
        [
            mesh.coords[n][0] + u[2 * n],
            mesh.coords[n][1] + u[2 * n + 1],
        ]
    }

    /// Where the geometry (normals, projections, Jacobians) is evaluated: the current
    /// position for large kinematics, the reference one for small kinematics (whose
    /// multipliers are then pressures on the reference surface, like the loads).
    fn geo(&self, mesh: &Mesh, u: &[f64], n: usize) -> [f64; 2] {
        if self.small {
            mesh.coords[n]
        } else {
            Self::pos(mesh, u, n)
        }
    }

    /// Outward unit normal of slave cell ic at ξ.
    fn cell_normal(&self, mesh: &Mesh, u: &[f64], ic: usize, xi: f64) -> [f64; 2] {
        let c = self.slave.cells[ic];
        let x: Vec<[f64; 2]> = mesh
            .cell_nodes(c)
            .iter()
            .map(|&n| self.geo(mesh, u, n))
            .collect();
        let (_, t) = point_and_tangent(mesh.kind(c), &x, xi);
        let l = t[0].hypot(t[1]);
        if self.slave.ccw[ic] {
            [t[1] / l, -t[0] / l]
        } else {
            [-t[1] / l, t[0] / l]
        }
    }

    /// Averaged outward unit normal at a slave corner node.
    fn node_normal(&self, mesh: &Mesh, u: &[f64], n: usize) -> [f64; 2] {
        let mut acc = [0.0; 2];
        for &ic in &self.cells_of_node[&n] {
            let nodes = mesh.cell_nodes(self.slave.cells[ic]);
            let xi = if nodes[0] == n { -1.0 } else { 1.0 };
            let v = self.cell_normal(mesh, u, ic, xi);
            acc[0] += v[0];
            acc[1] += v[1];
        }
        let l = acc[0].hypot(acc[1]);
        [acc[0] / l, acc[1] / l]
    }

    /// The terms of slave cell ic at displacement u.
    fn cell_terms(&self, mesh: &Mesh, u: &[f64], ic: usize) -> CellTerms {
        let c = self.slave.cells[ic];
        let kind = mesh.kind(c);
        let nn = kind.num_nodes();
        let snodes = mesh.cell_nodes(c);
        let xs: Vec<[f64; 2]> = snodes.iter().map(|&n| self.geo(mesh, u, n)).collect();
        let us: Vec<[f64; 2]> = snodes.iter().map(|&n| [u[2 * n], u[2 * n + 1]]).collect();
        // nodal normals: averaged at corners, the cell's own at a mid-side node
        let normals: Vec<[f64; 2]> = (0..nn)
            .map(|a| {
                if a < 2 {
                    self.node_normal(mesh, u, snodes[a])
                } else {
                    self.cell_normal(mesh, u, ic, 0.0)
                }
            })
            .collect();
        let (gp, gw) = gauss_legendre(6);
        // dual basis: Φ = A N with A = D M⁻¹ on this cell (current geometry)
        let mut m = [[0.0; 3]; 3];
        let mut d = [0.0; 3];
        for (q, &xi) in gp.iter().enumerate() {
            let (p, t) = point_and_tangent(kind, &xs, xi);
            let j = t[0].hypot(t[1]) * gw[q] * self.measure(p);
            let mut nv = [0.0; MAX_NODES];
            shape(kind, [xi, 0.0], &mut nv);
            for a in 0..nn {
                d[a] += nv[a] * j;
                for b in 0..nn {
                    m[a][b] += nv[a] * nv[b] * j;
                }
            }
        }
        // ∫ N_a r = 0 for a Seg3 corner on the axis when the cell is straight; on a curved
        // one (a sphere's pole) it is ~1e-7 of the cell's weight: a pressure so weakly
        // weighted is undetermined (and slows Newton), so such a node gets the zero weight
        // of the straight case (its force, λ D, is below 1e-6 of the cell's anyway).
        let dsum: f64 = d.iter().map(|v| v.abs()).sum();
        for v in d.iter_mut() {
            if v.abs() <= 1e-6 * dsum {
                *v = 0.0;
            }
        }
        let minv = invert(&m, nn);
        let mut amat = [[0.0; 3]; 3];
        for a in 0..nn {
            for b in 0..nn {
                amat[a][b] = d[a] * minv[a][b];
            }
        }
        let field = |xi: f64| -> ([f64; MAX_NODES], [f64; 2], [f64; 2], [f64; 2]) {
            let mut nv = [0.0; MAX_NODES];
            shape(kind, [xi, 0.0], &mut nv);
            let (p, t) = point_and_tangent(kind, &xs, xi);
            let mut nf = [0.0; 2];
            for a in 0..nn {
                nf[0] += nv[a] * normals[a][0];
                nf[1] += nv[a] * normals[a][1];
            }
            (nv, p, t, nf)
        };
        let mut out = CellTerms::default();
        for a in 0..nn {
            out.dj.push((self.mult_of[&snodes[a]], d[a]));
        }
        for &im in &self.candidates[ic] {
            let mc = self.master.cells[im];
            let mkind = mesh.kind(mc);
            let mnodes = mesh.cell_nodes(mc);
            let xm: Vec<[f64; 2]> = mnodes.iter().map(|&n| self.geo(mesh, u, n)).collect();
            let um: Vec<[f64; 2]> = mnodes.iter().map(|&n| [u[2 * n], u[2 * n + 1]]).collect();
            // master end nodes projected on the slave cell along the normal field
            let proj_slave = |target: [f64; 2]| -> Option<f64> {
                let mut xi = 0.0;
                for _ in 0..30 {
                    let (_, p, t, nf) = field(xi);
                    let r = cross([target[0] - p[0], target[1] - p[1]], nf);
                    // derivative: −t × n + (target − p) × n'  (n' from the nodal normals)
                    let mut dn = [[0.0; 2]; MAX_NODES];
                    shape_grad(kind, [xi, 0.0], &mut dn);
                    let mut nd = [0.0; 2];
                    for a in 0..nn {
                        nd[0] += dn[a][0] * normals[a][0];
                        nd[1] += dn[a][0] * normals[a][1];
                    }
                    let dr = -cross(t, nf) + cross([target[0] - p[0], target[1] - p[1]], nd);
                    if dr.abs() < 1e-300 {
                        return None;
                    }
                    let step = r / dr;
                    xi -= step;
                    if step.abs() < 1e-13 {
                        return Some(xi);
                    }
                    if xi.abs() > 10.0 {
                        return None;
                    }
                }
                None
            };
            let (Some(xa), Some(xb)) = (proj_slave(xm[0]), proj_slave(xm[1])) else {
                continue;
            };
            let lo = xa.min(xb).max(-1.0);
            let hi = xa.max(xb).min(1.0);
            if hi - lo < 1e-12 {
                continue;
            }
            for (q, &g) in gp.iter().enumerate() {
                let xi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * g;
                let (nv, p, t, nf) = field(xi);
                // project along the normal field on the master cell
                let mut xim = 0.0;
                let mut ok = false;
                for _ in 0..30 {
                    let (pm, tm) = point_and_tangent(mkind, &xm, xim);
                    let r = cross([pm[0] - p[0], pm[1] - p[1]], nf);
                    let dr = cross(tm, nf);
                    let step = r / dr;
                    xim -= step;
                    if step.abs() < 1e-13 {
                        ok = true;
                        break;
                    }
                }
                if !ok || xim.abs() > 1.0 + 1e-9 {
                    continue;
                }
                let (mut pm, _) = point_and_tangent(mkind, &xm, xim);
                let mut ps = p;
                if self.small {
                    // geometry on the reference configuration, gap with the displacements
                    let (dm, _) = point_and_tangent(mkind, &um, xim);
                    let (ds, _) = point_and_tangent(kind, &us, xi);
                    pm = [pm[0] + dm[0], pm[1] + dm[1]];
                    ps = [p[0] + ds[0], p[1] + ds[1]];
                }
                let ln = nf[0].hypot(nf[1]);
                let nhat = [nf[0] / ln, nf[1] / ln];
                let gap = (pm[0] - ps[0]) * nhat[0] + (pm[1] - ps[1]) * nhat[1];
                let w = gw[q] * 0.5 * (hi - lo) * t[0].hypot(t[1]) * self.measure(p);
                let mut nm = [0.0; MAX_NODES];
                shape(mkind, [xim, 0.0], &mut nm);
                // slip since the step start along τ̂ (slave relative to master)
                let tau = [-nhat[1], nhat[0]];
                let slip = if self.friction.is_some() {
                    let mut rel = [0.0; 2];
                    for c in 0..2 {
                        for (a, &n) in snodes.iter().enumerate() {
                            rel[c] += nv[a] * (u[2 * n + c] - self.u_start[2 * n + c]);
                        }
                        for (b, &n) in mnodes.iter().enumerate() {
                            rel[c] -= nm[b] * (u[2 * n + c] - self.u_start[2 * n + c]);
                        }
                    }
                    rel[0] * tau[0] + rel[1] * tau[1]
                } else {
                    0.0
                };
                for j in 0..nn {
                    let phi: f64 = (0..nn).map(|b| amat[j][b] * nv[b]).sum();
                    let k = self.mult_of[&snodes[j]];
                    out.gap.push((k, w * phi * gap));
                    out.cover.push((k, w * nv[j]));
                    for a in 0..nn {
                        for comp in 0..2 {
                            out.force
                                .push((k, 2 * snodes[a] + comp, w * phi * nv[a] * nhat[comp]));
                        }
                    }
                    for (b, &mn) in mnodes.iter().enumerate() {
                        for comp in 0..2 {
                            out.force
                                .push((k, 2 * mn + comp, -w * phi * nm[b] * nhat[comp]));
                        }
                    }
                    if self.friction.is_some() {
                        out.slip.push((k, w * phi * slip));
                        for a in 0..nn {
                            for comp in 0..2 {
                                out.tforce.push((
                                    k,
                                    2 * snodes[a] + comp,
                                    w * phi * nv[a] * tau[comp],
                                ));
                            }
                        }
                        for (b, &mn) in mnodes.iter().enumerate() {
                            for comp in 0..2 {
                                out.tforce
                                    .push((k, 2 * mn + comp, -w * phi * nm[b] * tau[comp]));
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// Whether slave corner node n touches the master: its own gap, measured along its
    /// averaged normal, is below 1e-6 of the adjacent slave cell size. (The weighted gap of
    /// a single touching point is positive, so it cannot start the active set.)
    fn touching(&self, mesh: &Mesh, u: &[f64], n: usize) -> bool {
        let mid_cells: Vec<usize>;
        let cells = match self.cells_of_node.get(&n) {
            Some(c) => c,
            // a mid-side node: only with an initial gap (a touching point is a corner)
            None if self.initial_gap.is_some() => {
                mid_cells = (0..self.slave.cells.len())
                    .filter(|&ic| mesh.cell_nodes(self.slave.cells[ic]).contains(&n))
                    .collect();
                &mid_cells
            }
            None => return false,
        };
        let x = Self::pos(mesh, u, n);
        let nv = if self.cells_of_node.contains_key(&n) {
            self.node_normal(mesh, u, n)
        } else {
            self.cell_normal(mesh, u, cells[0], 0.0) // mid-side: its cell's normal there
        };
        for &ic in cells {
            let sn = mesh.cell_nodes(self.slave.cells[ic]);
            let (a, b) = (mesh.coords[sn[0]], mesh.coords[sn[1]]);
            let size = (a[0] - b[0]).hypot(a[1] - b[1]);
            for &im in &self.candidates[ic] {
                let mc = self.master.cells[im];
                let xm: Vec<[f64; 2]> = mesh
                    .cell_nodes(mc)
                    .iter()
                    .map(|&m| Self::pos(mesh, u, m))
                    .collect();
                let mut xi = 0.0;
                for _ in 0..30 {
                    let (pm, tm) = point_and_tangent(mesh.kind(mc), &xm, xi);
                    let step = cross([pm[0] - x[0], pm[1] - x[1]], nv) / cross(tm, nv);
                    xi -= step;
                    if step.abs() < 1e-13 {
                        break;
                    }
                }
                if xi.abs() <= 1.0 + 1e-9 {
                    let (pm, _) = point_and_tangent(mesh.kind(mc), &xm, xi);
                    let gap = (pm[0] - x[0]) * nv[0] + (pm[1] - x[1]) * nv[1];
                    if gap <= self.initial_gap.unwrap_or(1e-6 * size) {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// The branch of node j at (λ, t) = (lam[j], lam[nm + j]) with weighted slip `slip` and
    /// D_j = `d`; `lmax` is the largest |λ|. `contribute` and `update_status` both use it.
    fn branch(&self, j: usize, lam: &[f64], slip: f64, d: f64, lmax: f64, mu: f64) -> Branch {
        let nm = self.mult_nodes.len();
        let pressure = lam[j];
        if !self.active[j]
            || d == 0.0
            || self.friction_excluded.contains(&j)
            || pressure <= 1e-8 * lmax
        {
            return Branch::Free;
        }
        let cf = self.trial_scale.get(j).copied().unwrap_or(1.0);
        let trial = lam[nm + j] + cf * self.c * slip / d;
        if trial.abs() <= mu * pressure {
            Branch::Stick
        } else {
            Branch::Slip(trial.signum())
        }
    }

    fn measure(&self, p: [f64; 2]) -> f64 {
        if self.axisymmetric {
            2.0 * std::f64::consts::PI * p[0]
        } else {
            self.thickness
        }
    }

    /// Weighted gaps, D_j, whether each slave node faces the master surface (at least
    /// half of ∫ N_j is covered by master segments) and the weighted slips (zero without
    /// friction) at u.
    #[allow(clippy::type_complexity)]
    fn gaps(&self, mesh: &Mesh, u: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<bool>, Vec<f64>) {
        let nm = self.mult_nodes.len();
        let (mut g, mut d, mut cov) = (vec![0.0; nm], vec![0.0; nm], vec![0.0; nm]);
        let mut sl = vec![0.0; nm];
        for ic in 0..self.slave.cells.len() {
            let t = self.cell_terms(mesh, u, ic);
            for (k, v) in t.gap {
                g[k] += v;
            }
            for (k, v) in t.dj {
                d[k] += v;
            }
            for (k, v) in t.cover {
                cov[k] += v;
            }
            for (k, v) in t.slip {
                sl[k] += v;
            }
        }
        let facing = (0..nm).map(|k| cov[k] > 0.5 * d[k]).collect();
        (g, d, facing, sl)
    }
}

fn invert(m: &[[f64; 3]; 3], n: usize) -> [[f64; 3]; 3] {
    let mut a = *m;
    let mut inv = [[0.0; 3]; 3];
    for i in 0..n {
        inv[i][i] = 1.0;
    }
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap();
        a.swap(col, piv);
        inv.swap(col, piv);
        let dv = a[col][col];
        for j in 0..n {
            a[col][j] /= dv;
            inv[col][j] /= dv;
        }
        for r in 0..n {
            if r != col {
                let f = a[r][col];
                for j in 0..n {
                    a[r][j] -= f * a[col][j];
                    inv[r][j] -= f * inv[col][j];
                }
            }
        }
    }
    inv
}

/// The weight D_j scaling each node's multiplier rows; a weightless node (on the axis) gets
/// the largest weight, so that its row sets its multiplier to zero on the usual scale.
fn row_weights(d: &[f64]) -> Vec<f64> {
    let dref = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    d.iter().map(|&v| if v != 0.0 { v } else { dref }).collect()
}

impl ContactPair for Mortar {
    fn num_multipliers(&self) -> usize {
        self.mult_nodes.len() * if self.friction.is_some() { 2 } else { 1 }
    }

    fn initialise(&mut self, mesh: &Mesh) {
        // Nodes already touching (normalised gap within 1e-6 of the cell size) start active.
        let u = vec![0.0; 2 * mesh.num_nodes()];
        let (_, _, facing, _) = self.gaps(mesh, &u);
        for k in 0..self.active.len() {
            self.active[k] = facing[k] && self.touching(mesh, &u, self.mult_nodes[k]);
        }
        self.saved = self.active.clone();
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
        let ndof = 2 * mesh.num_nodes();
        let nm = self.mult_nodes.len();
        let terms: Vec<CellTerms> = (0..self.slave.cells.len())
            .into_par_iter()
            .map(|ic| self.cell_terms(mesh, u, ic))
            .collect();
        let (mut g, mut d) = (vec![0.0; nm], vec![0.0; nm]);
        for t in &terms {
            for &(j, v) in &t.gap {
                g[j] += v;
            }
            for &(j, v) in &t.dj {
                d[j] += v;
            }
            for &(j, dof, v) in &t.force {
                ru[dof] += lam[j] * v;
                // K_uλ
                k.add(dof, ndof + mult_base + j, v);
            }
        }
        self.last_d.lock().unwrap().clone_from(&d);
        // a node without weight (on the axis) carries no contact constraint
        let active: Vec<bool> = (0..nm).map(|j| self.active[j] && d[j] != 0.0).collect();
        // Augmentation on active nodes: the force of the energy (c/2) g̃_j²/D_j, zero at
        // convergence (g̃_j = 0) but giving the displacement block the stiffness that holds
        // bodies only held by contact, so that the saddle-point LDLT needs no pivoting.
        let mut fj: Vec<Vec<(usize, f64)>> = vec![vec![]; nm];
        for t in &terms {
            for &(j, dof, v) in &t.force {
                if active[j] {
                    fj[j].push((dof, v));
                }
            }
        }
        for j in 0..nm {
            if active[j] {
                for &(dof, v) in &fj[j] {
                    ru[dof] += -self.c * g[j] / d[j] * v;
                }
            }
        }
        let row_d = row_weights(&d);
        for j in 0..nm {
            if active[j] {
                rl[j] += -g[j];
            } else {
                rl[j] += -lam[j] * row_d[j] / self.c;
                k.add(
                    ndof + mult_base + j,
                    ndof + mult_base + j,
                    -row_d[j] / self.c,
                );
            }
        }
        // Coulomb friction per slave node (semi-smooth, decided from the iterate): with the
        // traction t_j and the trial t_j + c s̃_j / D_j, no contact (or no pressure): t_j = 0;
        // stick (|trial| ≤ μ λ_j): s̃_j = 0; slip: t_j = μ λ_j sign(trial). Rows scaled by
        // D_j / c like the normal ones.
        let mut sl = vec![0.0; nm];
        let mut law = vec![Branch::Free; nm];
        if let Some(mu) = self.friction {
            let mut tf: Vec<Vec<(usize, f64)>> = vec![vec![]; nm];
            for t in &terms {
                for &(j, v) in &t.slip {
                    sl[j] += v;
                }
                for &(j, dof, v) in &t.tforce {
                    tf[j].push((dof, v));
                }
            }
            let lmax = lam[..nm].iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for j in 0..nm {
                let tj = lam[nm + j];
                let row = ndof + mult_base + nm + j;
                for &(dof, v) in &tf[j] {
                    ru[dof] += tj * v;
                    k.add(dof, row, v);
                }
                law[j] = self.branch(j, lam, sl[j], d[j], lmax, mu);
                match law[j] {
                    Branch::Free => {
                        rl[nm + j] += -tj * row_d[j] / self.c;
                        k.add(row, row, -row_d[j] / self.c);
                    }
                    Branch::Stick => rl[nm + j] += -sl[j],
                    Branch::Slip(sg) => {
                        let scale = d[j] / self.c;
                        rl[nm + j] += -(tj - mu * lam[j] * sg) * scale;
                        k.add(row, row, -scale);
                        k.add(row, ndof + mult_base + j, mu * sg * scale);
                    }
                }
            }
        }
        // u-derivatives by central differences, cell by cell: each dof's in parallel (on
        // a copy of u per thread), their triplets then emitted in dof order, so the
        // matrix is the same whatever the threads.
        let mut dofs: Vec<usize> = self.readers.keys().copied().collect();
        dofs.sort_unstable();
        let derivatives: Vec<DofDerivatives> = dofs
            .par_iter()
            .map_init(
                || u.to_vec(),
                |up, &dof| {
                    let h = 1e-7 * (1.0 + mesh.coords[dof / 2][dof % 2].abs().max(1.0));
                    let mut dv = DofDerivatives {
                        dg: vec![0.0; nm],
                        dd: vec![0.0; nm],
                        df: Default::default(),
                        ds: vec![0.0; nm],
                        dtf: Default::default(),
                    };
                    for (sign, s) in [(1.0, h), (-1.0, -h)] {
                        up[dof] = u[dof] + s;
                        for &ic in &self.readers[&dof] {
                            let t = self.cell_terms(mesh, up, ic);
                            for (j, v) in t.gap {
                                dv.dg[j] += sign * v / (2.0 * h);
                            }
                            for (j, v) in t.dj {
                                dv.dd[j] += sign * v / (2.0 * h);
                            }
                            for (j, row, v) in t.force {
                                *dv.df.entry((j, row)).or_insert(0.0) += sign * v / (2.0 * h);
                            }
                            for (j, v) in t.slip {
                                dv.ds[j] += sign * v / (2.0 * h);
                            }
                            for (j, row, v) in t.tforce {
                                *dv.dtf.entry((j, row)).or_insert(0.0) += sign * v / (2.0 * h);
                            }
                        }
                    }
                    up[dof] = u[dof];
                    dv
                },
            )
            .collect();
        for (&dof, dv) in dofs.iter().zip(derivatives) {
            let DofDerivatives {
                dg,
                dd,
                df,
                ds,
                dtf,
            } = dv;
            if let Some(mu) = self.friction {
                for ((j, row), v) in dtf {
                    k.add(row, dof, lam[nm + j] * v);
                }
                for j in 0..nm {
                    let row = ndof + mult_base + nm + j;
                    let v = match law[j] {
                        Branch::Stick => -ds[j],
                        Branch::Slip(sg) => -(lam[nm + j] - mu * lam[j] * sg) / self.c * dd[j],
                        Branch::Free => -lam[nm + j] / self.c * dd[j],
                    };
                    if v != 0.0 {
                        k.add(row, dof, v);
                    }
                }
            }
            for ((j, row), v) in df {
                let aug = if active[j] {
                    -self.c * g[j] / d[j]
                } else {
                    0.0
                };
                k.add(row, dof, (lam[j] + aug) * v);
            }
            for j in 0..nm {
                if active[j] && (dg[j] != 0.0 || dd[j] != 0.0) {
                    let (gj, dj) = (g[j], d[j]);
                    for &(row, v) in &fj[j] {
                        k.add(
                            row,
                            dof,
                            -self.c * (v / dj * dg[j] - gj * v / (dj * dj) * dd[j]),
                        );
                    }
                }
            }
            for j in 0..nm {
                let v = if active[j] {
                    -dg[j]
                } else {
                    -lam[j] * dd[j] / self.c
                };
                if v != 0.0 {
                    k.add(ndof + mult_base + j, dof, v);
                }
            }
        }
        // pattern: every dof a cell may read couples with every dof and multiplier of its
        // cells
        for (ic, &sc) in self.slave.cells.iter().enumerate() {
            let nodes = self.nodes_in_pattern(mesh, ic);
            let mut mults: Vec<usize> = mesh
                .cell_nodes(sc)
                .iter()
                .map(|n| ndof + mult_base + self.mult_of[n])
                .collect();
            if self.friction.is_some() {
                let tangential: Vec<usize> = mults.iter().map(|m| m + nm).collect();
                mults.extend(tangential);
            }
            let mut all: Vec<usize> = nodes.iter().flat_map(|&n| [2 * n, 2 * n + 1]).collect();
            all.extend_from_slice(&mults);
            for &r in &all {
                for &cc in &all {
                    k.add(r, cc, 0.0);
                }
            }
        }
    }

    fn update_status(&mut self, mesh: &Mesh, u: &[f64], lam: &[f64]) -> usize {
        // Re-pair on the current geometry (large sliding): the master cells near each slave
        // cell now; a new set changes the residual, so it counts as a status change.
        let near = candidates_at(mesh, Some(u), &self.slave, &self.master, 1.0);
        let mut changes = 0;
        if near != self.candidates {
            changes += 1;
            add_to_pattern(&mut self.pattern_candidates, &near);
            self.candidates = near;
            self.build_readers(mesh);
        }
        let (g, d, facing, sl) = self.gaps(mesh, u);
        for j in 0..self.active.len() {
            let active = facing[j] && d[j] != 0.0 && lam[j] - self.c * g[j] / d[j] > 0.0;
            if active != self.active[j] {
                changes += 1;
                self.active[j] = active;
            }
        }
        if let Some(mu) = self.friction {
            // the branch `contribute` takes at this iterate
            let nm = self.mult_nodes.len();
            self.law.resize(nm, Branch::Free);
            self.trial_scale.resize(nm, 1.0);
            self.switches.resize(nm, 0);
            let lmax = lam[..nm].iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for j in 0..nm {
                let law = self.branch(j, lam, sl[j], d[j], lmax, mu);
                if law != self.law[j] {
                    self.switches[j] += 1;
                    if self.switches[j] >= 3 {
                        self.trial_scale[j] = (0.1 * self.trial_scale[j]).max(1e-4);
                        self.switches[j] = 0;
                    }
                    changes += 1;
                    self.law[j] = law;
                }
            }
        }
        changes
    }

    fn commit(&mut self, u: &[f64]) {
        self.switches.fill(0);
        if self.saved_candidates != self.candidates {
            self.saved_candidates = self.candidates.clone();
            self.saved_readers = self.readers.clone();
        }
        self.saved = self.active.clone();
        self.saved_law = self.law.clone();
        self.u_start.copy_from_slice(u);
    }

    fn restore(&mut self) {
        if self.candidates != self.saved_candidates {
            self.candidates = self.saved_candidates.clone();
            self.readers = self.saved_readers.clone();
        }
        self.active = self.saved.clone();
        self.law = self.saved_law.clone();
    }

    fn constraint_residual(&self, rl: &[f64], lam: &[f64]) -> f64 {
        // every row (weighted gap or slip, or multiplier × D_j / c) times c / D_j is a
        // pressure; relative to the largest normal multiplier
        let d = self.last_d.lock().unwrap();
        let nm = self.mult_nodes.len();
        if d.len() != nm {
            return 0.0;
        }
        let scale = lam[..nm]
            .iter()
            .fold(self.pressure_floor, |m, v| m.max(v.abs()));
        let w = row_weights(&d);
        let worst = rl
            .iter()
            .enumerate()
            .map(|(k, r)| (r * self.c / w[k % nm]).abs())
            .fold(0.0f64, f64::max);
        if scale > 0.0 {
            worst / scale
        } else {
            worst
        }
    }

    fn multiplier_nodes(&self) -> &[usize] {
        &self.mult_nodes
    }
    fn surfaces(&self) -> (&Surface, &Surface) {
        (&self.slave, &self.master)
    }

    fn nodal_pressures(&self, lam: &[f64]) -> Vec<(usize, f64)> {
        let mut p: Vec<f64> = lam[..self.mult_nodes.len()].to_vec();
        // A node of zero weight (∫ N_j dA = 0: the Seg3 corner on the axis in axisymmetry)
        // carries no multiplier; its pressure is extrapolated from its cell's other nodes
        // (mid-side at ξ = 0, far corner at ξ = 1: p = 2 p_mid − p_far).
        let d = self.last_d.lock().unwrap();
        let dmax = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let weightless = |k: usize| d.get(k).is_some_and(|v| v.abs() <= 1e-12 * dmax);
        for nodes in &self.cell_mults {
            if let [a, b, mid] = nodes[..] {
                for (end, far) in [(a, b), (b, a)] {
                    if weightless(end) && !weightless(far) && !weightless(mid) {
                        p[end] = 2.0 * lam[mid] - lam[far];
                    }
                }
            }
        }
        self.mult_nodes.iter().copied().zip(p).collect()
    }

    fn nodal_shear(&self, lam: &[f64]) -> Vec<(usize, f64)> {
        let nm = self.mult_nodes.len();
        match self.friction {
            Some(_) => (0..nm).map(|k| (self.mult_nodes[k], lam[nm + k])).collect(),
            None => vec![],
        }
    }

    /// No: a mortar re-solve redoes the contact terms and their finite-difference tangent,
    /// nearly a whole iteration, and on fine meshes the nodal active set cycles at a fixed
    /// linearisation (SSNP154 quadratic, 0.375 mm: 41 Newton iterations with re-solves,
    /// 10 without; reference meshes A–D: 10/12/13/14 → 7/8/9/9).
    fn active_set_resolves(&self) -> bool {
        false
    }
    fn friction(&self) -> f64 {
        self.friction.unwrap_or(0.0)
    }
}
