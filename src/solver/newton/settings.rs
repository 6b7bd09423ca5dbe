//! `NewtonSettings`: the load steps, tolerance, iteration and cut limits, and which
//! shortcuts Newton may take (factorisation reuse, chord steps, frozen bodies, kinematic
//! continuation, anticipated contact patterns).

#[derive(Clone, Debug)]
pub struct NewtonSettings {
    /// Number of equal steps to t = 1 when `times` is empty.
    pub steps: usize,
    /// The ends of the load steps (increasing, positive); the last one is the end time.
    pub times: Vec<f64>,
    pub tolerance: f64,
    pub max_iterations: usize,
    pub max_cuts: usize,
    pub verbose: bool,
    /// Keep the unknowns of every converged step in `NewtonReport::states`.
    pub keep_states: bool,
    /// Saddle-point solves may precondition with an earlier tangent's factorisation.
    pub reuse_factor: bool,
    /// Near convergence, a correction may reuse the last factorisation (a chord step)
    /// when it is predicted to reach the tolerance (see `iterations.rs`).
    pub chord_steps: bool,
    /// Corrections may keep the bodies' tangent and factorisations with current contact
    /// terms: the first of a step, and with friction those far from the tolerance (see
    /// `iterations.rs`).
    pub frozen_bodies: bool,
    /// A model with large kinematics solves its first load step with linear kinematics
    /// first, and from that solution with its own (see `continuation.rs`).
    pub kinematic_continuation: bool,
    /// A contact zone that grows out of the tangent's pattern makes it take in at once
    /// the couplings within reach at the loading's end (see `iterations.rs`).
    pub anticipate_pattern: bool,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings {
            steps: 1,
            times: vec![],
            tolerance: 1e-6,
            max_iterations: 25,
            max_cuts: 8,
            verbose: false,
            keep_states: false,
            reuse_factor: true,
            chord_steps: true,
            frozen_bodies: true,
            kinematic_continuation: true,
            anticipate_pattern: true,
        }
    }
}

impl NewtonSettings {
    /// The step ends: `times`, or `steps` equal steps to 1.
    pub fn step_ends(&self) -> Vec<f64> {
        if self.times.is_empty() {
            super::super::history::step_ends(1.0, self.steps, &[])
        } else {
            self.times.clone()
        }
    }
}
