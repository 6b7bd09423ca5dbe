//! `Nonlinear`: what Newton (newton.rs) needs from a discrete problem, and what it reports
//! of its iterations.

use super::problem::Norms;
use crate::assembly::matrix::SparseMatrix;
use crate::error::Result;
use serde::Serialize;

/// What Newton needs from a discrete problem. Contact plugs in here: its statuses are
/// updated after each correction and a step converges only when none changed.
pub trait Nonlinear {
    fn num_unknowns(&self) -> usize;
    /// A length of the model (its size), to recognise absurd displacement increments.
    fn length_scale(&self) -> f64 {
        f64::INFINITY
    }
    /// Leading unknowns that are displacements (the rest are multipliers).
    fn num_primal(&self) -> usize {
        self.num_unknowns()
    }
    /// The unknowns of the current state (the start of the solve).
    fn unknowns(&self) -> Vec<f64>;
    /// Sets the state to (x, λ), writes the residual, assembles the tangent if asked.
    fn evaluate(
        &mut self,
        x: &[f64],
        lambda: f64,
        r: &mut [f64],
        with_tangent: bool,
    ) -> Result<Norms>;
    /// Like `evaluate` with the tangent, but the tangent's displacement part may stay the
    /// last assembled one while its contact part is current: for iterations that follow
    /// contact status changes, when the linear solver keeps the bodies' factorisations
    /// for such tangents (only the contact interface is refactorised).
    fn evaluate_contact_tangent(&mut self, x: &[f64], lambda: f64, r: &mut [f64]) -> Result<Norms> {
        self.evaluate(x, lambda, r, true)
    }
    fn matrix(&self) -> &SparseMatrix;
    /// Why the current (converged) state is not admissible, if it is not: e.g. cells turned
    /// inside out. Such a state is not accepted as converged (the step is cut).
    fn state_defect(&self) -> Option<String> {
        None
    }
    /// Updates discrete statuses (contact) from the new iterate; returns how many changed.
    fn update_status(&mut self, _x: &[f64], _lambda: f64) -> Result<usize> {
        Ok(0)
    }
    /// Statuses of the problem linearised at the last evaluation, taken at the trial point
    /// x (how many changed), or None where the problem keeps no such linearisation.
    fn update_status_linearised(&mut self, _x: &[f64], _lambda: f64) -> Result<Option<usize>> {
        Ok(None)
    }
    /// Sets the contact statuses to the initial ones (the bodies at rest, about to be
    /// loaded: a rest solution opened them all).
    fn restart_statuses(&mut self) {}
    /// Opens every contact status if nothing penetrates at rest (see
    /// `ContactPair::open_at_rest`); whether it did.
    fn open_at_rest(&mut self) -> bool {
        false
    }
    /// Nodes whose status the last `update_status` changed (for failure messages).
    fn changed_nodes(&self) -> Vec<usize> {
        vec![]
    }
    /// Where the residual r (over the unknowns) is largest, in the user's terms (a node and
    /// a component), for failure messages.
    fn residual_location(&self, _r: &[f64]) -> Option<String> {
        None
    }
    /// A hash of the discrete statuses (to recognise a cycle of active-set re-solves).
    fn status_signature(&self) -> u64 {
        0
    }
    /// Bumped whenever the tangent's pattern grows (contact couplings come within reach).
    fn pattern_generation(&self) -> usize {
        0
    }
    /// Takes into the tangent's pattern the couplings within reach at `predicted`, the
    /// unknowns predicted at time `end` (the loading's end) from x at time lambda.
    fn anticipate(&mut self, _x: &[f64], _lambda: f64, _predicted: &[f64], _end: f64) {}
    /// Whether status changes are worth an active-set re-solve from the same point (the
    /// bodies' factorisations stand; see `solve`).
    fn active_set_resolves(&self) -> bool {
        false
    }
    /// Whether corrections that make the residual worse are shortened by the line search
    /// (see line_search.rs).
    fn line_search(&self) -> bool {
        true
    }
    /// Friction branches the last `update_status` saw change that it did not count among
    /// the status changes it returned.
    fn branch_switches(&self) -> usize {
        0
    }
    /// Whether a correction that raises the residual without any status change should be
    /// cut back (semi-smooth terms such as friction, which can cycle).
    fn backtracking(&self) -> bool {
        false
    }
    /// Whether imposed displacements change between times t0 and t1.
    fn imposed_change(&self, _t0: f64, _t1: f64) -> bool {
        false
    }
    /// Whether nothing loads the problem at time t (no force, no imposed motion).
    fn unloaded(&self, _t: f64) -> bool {
        false
    }
    /// Switches to linear kinematics (small strains, contact on the reference geometry) in
    /// place of the model's large kinematics, or back; whether the problem has large
    /// kinematics to switch (see `continuation.rs`).
    fn set_linear_kinematics(&mut self, _linear: bool) -> bool {
        false
    }
    /// Called when a load step has converged (commit history variables).
    fn commit_step(&mut self) {}
    /// Called when a load step failed and is retried from its start.
    fn restore_step(&mut self) {}
}

#[derive(Clone, Debug, Serialize)]
pub struct Iteration {
    pub iteration: usize,
    /// max-norm of the residual over the displacement rows, divided by the force scale
    pub relative_residual: f64,
    /// Contact statuses changed by the update after this iteration's correction.
    pub status_changes: usize,
    /// Friction branches that update changed without counting them as status changes
    /// (`Nonlinear::branch_switches`).
    #[serde(skip_serializing_if = "is_zero")]
    pub branch_switches: usize,
    /// Evaluated at the previous iteration's point with the statuses its correction
    /// changed (an active-set re-solve: only the contact terms and the interface redone).
    pub active_set_resolve: bool,
    /// This iteration's correction reused the last factorisation (a chord step) instead of
    /// factorising the tangent at this point.
    pub chord: bool,
    /// This iteration's tangent kept the bodies' part (and their factorisations) of an
    /// earlier iterate; its contact terms are those of this point.
    pub frozen_bodies: bool,
    /// The fraction of the last correction kept by the line search, when it shortened it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub step_length: Option<f64>,
    /// Iterated with linear kinematics (the first stage of a step: see `continuation.rs`).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub linear_kinematics: bool,
}

#[derive(Clone, Debug, Serialize)]
pub struct StepReport {
    /// The time reached (the load factor without a load history).
    pub time: f64,
    pub converged: bool,
    pub iterations: Vec<Iteration>,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct NewtonReport {
    pub steps: Vec<StepReport>,
    pub total_iterations: usize,
    pub factorizations: usize,
    pub symbolic_factorizations: usize,
    /// Numeric LDLᵀ factorisations (the others reused an earlier one).
    pub numeric_factorizations: usize,
    /// Linear solves where GMRES stalled and LU solved instead.
    pub gmres_stalls: usize,
    /// Wall time spent evaluating residuals and tangents, factorising, solving (s).
    pub time_evaluate_s: f64,
    pub time_factor_s: f64,
    pub time_solve_s: f64,
    /// (time, unknowns) after each converged step, with `keep_states`.
    #[serde(skip)]
    pub states: Vec<(f64, Vec<f64>)>,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}
