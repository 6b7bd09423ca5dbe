//! `SolidProblem`: the discrete equilibrium of elastic bodies at time t,
//! R(x, t) = Tᵀ(f_int(u) − f_ext(t)) with u = T x + G g(t), plus reactions at the imposed
//! dofs. Without a load history t is the load factor (everything proportional to t).

use crate::assembly::dofs::Role;
use crate::assembly::matrix::SparseMatrix;
use crate::assembly::Assembler;
use crate::error::Result;
use crate::mesh::Mesh;
use crate::solver::history::Loading;
use crate::solver::newton::Nonlinear;

pub struct SolidProblem<'m> {
    pub mesh: &'m Mesh,
    pub asm: Assembler,
    /// The forces and imposed displacements as functions of time.
    pub loading: Loading,
    /// External loads at the current time (full dofs).
    pub fext: Vec<f64>,
    /// Imposed values at the current time (see `DofMap::expand`).
    imposed: Vec<f64>,
    /// Current full displacement and internal forces.
    pub u: Vec<f64>,
    pub fint: Vec<f64>,
    /// f_int + other internal contributions (contact) − f_ext, full dofs, last evaluation.
    pub residual_full: Vec<f64>,
    /// The time of the current state (NaN before the first evaluation).
    pub time: f64,
    /// The free unknowns `fint` was assembled at, and whether the tangent was too (an
    /// evaluation at the same state, e.g. an active-set re-solve, assembles nothing).
    assembled_at: Option<(Vec<f64>, bool)>,
    /// The smallest force scale of the residual: without loads (a zero load, a history
    /// that comes back to zero) the residual is measured against the force of a strain of
    /// 1e-12 over the model, E L t (E L 2πL in axisymmetry), not against round-off.
    force_floor: f64,
}

/// Max-norms used by the convergence test (as the reference code: displacement rows only).
#[derive(Clone, Copy, Debug, Default)]
pub struct Norms {
    pub residual: f64,
    /// max |f_ext| and |reaction| over all dofs: the scale of the residual.
    pub reference: f64,
    /// Residual of the constraint (multiplier) rows, already relative (0 when unmeasured).
    pub constraint: f64,
}

impl Norms {
    /// The larger of the displacement rows' residual over its scale and the constraint rows'.
    pub fn relative(&self) -> f64 {
        let r = if self.reference > 0.0 {
            self.residual / self.reference
        } else {
            self.residual
        };
        r.max(self.constraint)
    }
}

impl<'m> SolidProblem<'m> {
    /// Loads `fext` and the imposed values of the dof map, all proportional to t.
    pub fn new(mesh: &'m Mesh, asm: Assembler, fext: Vec<f64>) -> Self {
        let loading = Loading::proportional(fext, &asm.dofs);
        Self::with_loading(mesh, asm, loading)
    }

    pub fn with_loading(mesh: &'m Mesh, asm: Assembler, loading: Loading) -> Self {
        let n = asm.dofs.num_dofs();
        SolidProblem {
            mesh,
            asm,
            loading,
            fext: vec![0.0; n],
            imposed: vec![],
            u: vec![0.0; n],
            fint: vec![0.0; n],
            residual_full: vec![0.0; n],
            time: f64::NAN,
            assembled_at: None,
            force_floor: 0.0,
        }
        .with_force_floor()
    }

    fn with_force_floor(mut self) -> Self {
        use crate::fem::material::Modelisation;
        let l = self.length_scale();
        self.force_floor = self
            .asm
            .cell_model
            .iter()
            .map(|m| {
                let t = match m.model {
                    Modelisation::Axisymmetric => 2.0 * std::f64::consts::PI * l,
                    _ => m.thickness,
                };
                1e-12 * m.material.young * l * t
            })
            .fold(0.0, f64::max);
        self
    }

    /// Moves the loads to time t.
    fn set_time(&mut self, t: f64) {
        if t != self.time {
            self.loading.forces_at(t, &mut self.fext);
            self.loading
                .imposed_at(t, &self.asm.dofs, &mut self.imposed);
            self.time = t;
        }
    }

    /// Whether any imposed value differs between times t0 and t1.
    pub fn imposed_change(&self, t0: f64, t1: f64) -> bool {
        let (mut a, mut b) = (vec![], vec![]);
        self.loading.imposed_at(t0, &self.asm.dofs, &mut a);
        self.loading.imposed_at(t1, &self.asm.dofs, &mut b);
        a != b
    }

    /// Whether nothing loads the bodies at time t: no force, no imposed value, no relation
    /// right-hand side (the bodies at rest are then in equilibrium).
    pub fn unloaded(&self, t: f64) -> bool {
        let mut f = vec![0.0; self.u.len()];
        self.loading.forces_at(t, &mut f);
        let mut imposed = vec![];
        self.loading.imposed_at(t, &self.asm.dofs, &mut imposed);
        f.iter().chain(&imposed).all(|&v| v == 0.0)
    }

    /// The node and component of the largest displacement-row residual in r (over the
    /// free unknowns first), as a failure message says it.
    pub fn residual_location(&self, r: &[f64]) -> Option<String> {
        let nf = self.num_free();
        let (k, v) = r[..nf.min(r.len())]
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))?;
        let d = self
            .asm
            .dofs
            .roles
            .iter()
            .position(|role| matches!(role, Role::Free(i) if *i == k))?;
        let c = ["dx", "dy"][d % 2];
        Some(format!("node {} ({c}, {:.1e})", d / 2 + 1, v.abs()))
    }

    /// The full displacement of the free unknowns `x` at time t.
    pub fn displacement(&mut self, x: &[f64], t: f64, u: &mut [f64]) {
        self.set_time(t);
        self.asm.dofs.expand(x, &self.imposed, u);
    }

    /// Forgets the last assembly (the bodies' model changed: the same unknowns assemble
    /// differently).
    pub fn forget_assembly(&mut self) {
        self.assembled_at = None;
    }

    pub fn num_free(&self) -> usize {
        self.asm.dofs.num_free
    }

    /// Sets the free unknowns `x` and the time, assembles internal forces (and the tangent
    /// if asked).
    pub fn set_state(&mut self, x: &[f64], t: f64, with_tangent: bool) -> Result<()> {
        let same_time = t == self.time;
        self.set_time(t);
        if same_time {
            if let Some((at, tangent)) = &self.assembled_at {
                if at.as_slice() == x && (*tangent || !with_tangent) {
                    return Ok(());
                }
            }
        }
        self.assembled_at = None;
        self.asm.dofs.expand(x, &self.imposed, &mut self.u);
        self.asm
            .assemble(self.mesh, &self.u, &mut self.fint, with_tangent)?;
        self.assembled_at = Some((x.to_vec(), with_tangent));
        Ok(())
    }

    /// Residual f_int + extra − f_ext reduced to the free unknowns, with its norms.
    /// `extra` holds further internal forces on the full dofs (e.g. contact).
    pub fn finish_residual(&mut self, extra: Option<&[f64]>, r: &mut [f64]) -> Norms {
        for d in 0..self.u.len() {
            self.residual_full[d] = self.fint[d] - self.fext[d] + extra.map_or(0.0, |e| e[d]);
        }
        self.asm.dofs.reduce(&self.residual_full, r);
        let residual = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut reference = self
            .fext
            .iter()
            .fold(self.force_floor, |m, v| m.max(v.abs()));
        for (d, role) in self.asm.dofs.roles.iter().enumerate() {
            if !matches!(role, Role::Free(_)) {
                reference = reference.max(self.residual_full[d].abs());
            }
        }
        Norms {
            residual,
            reference,
            constraint: 0.0,
        }
    }

    /// Reactions at the imposed and linked dofs (full vector, 0 at free dofs): the forces the
    /// supports exert, at the last evaluated state.
    pub fn reactions(&self) -> Vec<f64> {
        let mut r = vec![0.0; self.u.len()];
        for (d, role) in self.asm.dofs.roles.iter().enumerate() {
            if !matches!(role, Role::Free(_)) {
                r[d] = self.residual_full[d];
            }
        }
        r
    }

    /// Diagonal of the bounding box of the mesh.
    pub fn length_scale(&self) -> f64 {
        let (lo, hi) = crate::mesh::quality::bounding_box(self.mesh);
        (hi[0] - lo[0]).hypot(hi[1] - lo[1])
    }

    /// Free unknowns of the current displacement.
    pub fn free_unknowns(&self) -> Vec<f64> {
        let mut x = vec![0.0; self.asm.dofs.num_free];
        self.asm.dofs.restrict(&self.u, &mut x);
        x
    }
}

impl SolidProblem<'_> {
    /// The cells whose deformed shape (X + u) is turned inside out or flat: det J ≤ 0 at a
    /// corner or the centre. With small kinematics too: such a displacement field is far
    /// outside the theory, whatever its strains say.
    pub fn inverted_cells(&self) -> Vec<usize> {
        use crate::fem::element::{jacobian_det, reference_nodes};
        use rayon::prelude::*;
        let mesh = self.mesh;
        self.asm
            .cells
            .par_iter()
            .copied()
            .filter(|&c| {
                let kind = mesh.kind(c);
                let x: Vec<[f64; 2]> = mesh
                    .cell_nodes(c)
                    .iter()
                    .map(|&n| {
                        [
                            mesh.coords[n][0] + self.u[2 * n],
                            mesh.coords[n][1] + self.u[2 * n + 1],
                        ]
                    })
                    .collect();
                let centre = if kind.num_corners() == 3 {
                    [1.0 / 3.0, 1.0 / 3.0]
                } else {
                    [0.0, 0.0]
                };
                reference_nodes(kind)
                    .iter()
                    .take(kind.num_corners())
                    .copied()
                    .chain(std::iter::once(centre))
                    .any(|xi| jacobian_det(kind, &x, xi) <= 0.0)
            })
            .collect()
    }

    /// `Nonlinear::state_defect` of the bodies: inverted cells.
    pub fn solid_defect(&self) -> Option<String> {
        let bad = self.inverted_cells();
        let first = bad.first()?;
        Some(format!(
            "{} cells are turned inside out (det J <= 0), cell {} first: the load or imposed \
             motion is far beyond what the model can carry",
            bad.len(),
            first + 1
        ))
    }
}

impl Nonlinear for SolidProblem<'_> {
    fn state_defect(&self) -> Option<String> {
        self.solid_defect()
    }
    fn num_unknowns(&self) -> usize {
        self.asm.dofs.num_free
    }
    fn unknowns(&self) -> Vec<f64> {
        self.free_unknowns()
    }
    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        r: &mut [f64],
        with_tangent: bool,
    ) -> Result<Norms> {
        self.set_state(x, lambda, with_tangent)?;
        Ok(self.finish_residual(None, r))
    }
    // (bodies alone: a rotation imposed in large steps made the line search stall,
    // tests/history.rs; their Newton is plain)
    fn line_search(&self) -> bool {
        false
    }

    fn matrix(&self) -> &SparseMatrix {
        &self.asm.matrix
    }
    fn length_scale(&self) -> f64 {
        self.length_scale()
    }
    fn imposed_change(&self, t0: f64, t1: f64) -> bool {
        self.imposed_change(t0, t1)
    }
}
