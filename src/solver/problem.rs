//! `SolidProblem`: the discrete equilibrium of elastic bodies, R(x, λ) = Tᵀ(f_int(u) − λ f_ext)
//! with u = T x + λ g, plus reactions at the imposed dofs.

use crate::assembly::dofs::Role;
use crate::assembly::matrix::SparseMatrix;
use crate::assembly::Assembler;
use crate::error::Result;
use crate::mesh::Mesh;
use crate::solver::newton::Nonlinear;

pub struct SolidProblem<'m> {
    pub mesh: &'m Mesh,
    pub asm: Assembler,
    /// External loads at load factor 1 (full dofs).
    pub fext: Vec<f64>,
    /// Current full displacement and internal forces.
    pub u: Vec<f64>,
    pub fint: Vec<f64>,
    /// f_int + other internal contributions (contact) − λ f_ext, full dofs, last evaluation.
    pub residual_full: Vec<f64>,
    pub lambda: f64,
}

/// Max-norms used by the convergence test (as the reference code: displacement rows only).
#[derive(Clone, Copy, Debug, Default)]
pub struct Norms {
    pub residual: f64,
    /// max |λ f_ext| and |reaction| over all dofs: the scale of the residual.
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
    pub fn new(mesh: &'m Mesh, asm: Assembler, fext: Vec<f64>) -> Self {
        let n = fext.len();
        SolidProblem {
            mesh,
            asm,
            fext,
            u: vec![0.0; n],
            fint: vec![0.0; n],
            residual_full: vec![0.0; n],
            lambda: 0.0,
        }
    }

    pub fn num_free(&self) -> usize {
        self.asm.dofs.num_free
    }

    /// Sets the free unknowns `x` and the load factor, assembles internal forces (and the
    /// tangent if asked).
    pub fn set_state(&mut self, x: &[f64], lambda: f64, with_tangent: bool) -> Result<()> {
        self.lambda = lambda;
        self.asm.dofs.expand(x, lambda, &mut self.u);
        self.asm
            .assemble(self.mesh, &self.u, &mut self.fint, with_tangent)
    }

    /// Residual f_int + extra − λ f_ext reduced to the free unknowns, with its norms.
    /// `extra` holds further internal forces on the full dofs (e.g. contact).
    pub fn finish_residual(&mut self, extra: Option<&[f64]>, r: &mut [f64]) -> Norms {
        let lambda = self.lambda;
        for d in 0..self.u.len() {
            self.residual_full[d] =
                self.fint[d] - lambda * self.fext[d] + extra.map_or(0.0, |e| e[d]);
        }
        self.asm.dofs.reduce(&self.residual_full, r);
        let residual = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut reference = self
            .fext
            .iter()
            .fold(0.0f64, |m, v| m.max((lambda * v).abs()));
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

impl Nonlinear for SolidProblem<'_> {
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
    fn matrix(&self) -> &SparseMatrix {
        &self.asm.matrix
    }
    fn length_scale(&self) -> f64 {
        self.length_scale()
    }
}
