//! `SolidProblem`: the discrete equilibrium of elastic bodies, R(x, λ) = Tᵀ(f_int(u) − λ f_ext)
//! with u = T x + λ g, plus reactions at the imposed dofs.

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
    pub lambda: f64,
}

/// Max-norms used by the convergence test (as the reference code: displacement rows only).
#[derive(Clone, Copy, Debug, Default)]
pub struct Norms {
    pub residual: f64,
    /// max |λ f_ext| and |reaction| over all dofs: the scale of the residual.
    pub reference: f64,
}

impl Norms {
    pub fn relative(&self) -> f64 {
        if self.reference > 0.0 {
            self.residual / self.reference
        } else {
            self.residual
        }
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
            lambda: 0.0,
        }
    }

    pub fn num_unknowns(&self) -> usize {
        self.asm.dofs.num_free
    }

    /// Sets x and λ, assembles, writes the reduced residual into `r`.
    pub fn evaluate_solid(
        &mut self,
        x: &[f64],
        lambda: f64,
        r: &mut [f64],
        with_tangent: bool,
    ) -> Result<Norms> {
        self.lambda = lambda;
        self.asm.dofs.expand(x, lambda, &mut self.u);
        self.asm
            .assemble(self.mesh, &self.u, &mut self.fint, with_tangent)?;
        let mut full = self.fint.clone();
        for (f, e) in full.iter_mut().zip(&self.fext) {
            *f -= lambda * e;
        }
        self.asm.dofs.reduce(&full, r);
        let residual = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut reference = self
            .fext
            .iter()
            .fold(0.0f64, |m, v| m.max((lambda * v).abs()));
        for (d, role) in self.asm.dofs.roles.iter().enumerate() {
            if !matches!(role, crate::assembly::dofs::Role::Free(_)) {
                reference = reference.max(full[d].abs());
            }
        }
        Ok(Norms {
            residual,
            reference,
        })
    }

    /// Reactions at the imposed and linked dofs (full vector, 0 at free dofs): the force the
    /// supports exert, f_int − λ f_ext at the current state.
    pub fn reactions(&self) -> Vec<f64> {
        let mut r = vec![0.0; self.u.len()];
        for (d, role) in self.asm.dofs.roles.iter().enumerate() {
            if !matches!(role, crate::assembly::dofs::Role::Free(_)) {
                r[d] = self.fint[d] - self.lambda * self.fext[d];
            }
        }
        r
    }
}

impl Nonlinear for SolidProblem<'_> {
    fn num_unknowns(&self) -> usize {
        self.asm.dofs.num_free
    }
    fn unknowns(&self) -> Vec<f64> {
        let mut x = vec![0.0; self.asm.dofs.num_free];
        self.asm.dofs.restrict(&self.u, &mut x);
        x
    }
    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        r: &mut [f64],
        with_tangent: bool,
    ) -> Result<Norms> {
        self.evaluate_solid(x, lambda, r, with_tangent)
    }
    fn matrix(&self) -> &SparseMatrix {
        &self.asm.matrix
    }
}
