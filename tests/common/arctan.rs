//! A one-unknown nonlinear problem for Newton's own tests: R(x, t) = atan(x) − t·atan(1),
//! whose root at t = 1 is x = 1. Full Newton converges from 0 but overshoots without end
//! from x = 4 (each correction lands farther on the other side).

use tribo::assembly::matrix::SparseMatrix;
use tribo::error::Result;
use tribo::solver::newton::Nonlinear;
use tribo::solver::problem::Norms;

pub struct Arctan {
    pub x: f64,
    /// A "linear kinematics" form R(x, t) = x − t·root that `set_linear_kinematics`
    /// switches to (None: the problem has none, as one with small kinematics).
    pub linear_root: Option<f64>,
    /// Whether the linear form is on.
    pub linear: bool,
    /// What `Nonlinear::line_search` answers.
    pub line_search: bool,
    k: SparseMatrix,
}

impl Arctan {
    /// At x, without a linear form, with the line search.
    pub fn new(x: f64) -> Self {
        Arctan {
            x,
            linear_root: None,
            linear: false,
            line_search: true,
            k: SparseMatrix::from_entries(1, &[(0, 0, 1.0)]),
        }
    }
}

impl Nonlinear for Arctan {
    fn num_unknowns(&self) -> usize {
        1
    }
    fn unknowns(&self) -> Vec<f64> {
        vec![self.x]
    }
    fn evaluate(&mut self, x: &[f64], t: f64, r: &mut [f64], _tangent: bool) -> Result<Norms> {
        self.x = x[0];
        (r[0], self.k.values[0]) = match (self.linear, self.linear_root) {
            (true, Some(root)) => (x[0] - t * root, 1.0),
            _ => (x[0].atan() - t * 1f64.atan(), 1.0 / (1.0 + x[0] * x[0])),
        };
        Ok(Norms {
            residual: r[0].abs(),
            reference: 1.0,
            constraint: 0.0,
        })
    }
    fn matrix(&self) -> &SparseMatrix {
        &self.k
    }
    fn line_search(&self) -> bool {
        self.line_search
    }
    fn set_linear_kinematics(&mut self, linear: bool) -> bool {
        if self.linear_root.is_none() {
            return false;
        }
        self.linear = linear;
        true
    }
}
