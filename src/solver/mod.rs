//! Solvers: sparse direct linear solves and Newton with load steps.
//!
//! | file | what |
//! |---|---|
//! | `continuation.rs` | large kinematics' first load step started from its linear-kinematics solution |
//! | `gmres.rs` | right-preconditioned GMRES (non-symmetric tangents on the LDLᵀ of their symmetric part) |
//! | `interface/` | exact contact tangent solves condensed on the contact interface (bodies factorised in parallel) |
//! | `history.rs` | time functions, rigid motions, loads and imposed values at a time t |
//! | `ldlt/` | LDLᵀ in a fixed order; saddle-point LDLᵀ with the constrained ordering |
//! | `line_search.rs` | backtracking on the residual with each trial point's contact statuses |
//! | `linear.rs` | faer Cholesky / LU with symbolic reuse |
//! | `problem.rs` | `SolidProblem`: residual, tangent, reactions of the discrete bodies |
//! | `nonlinear.rs` | `Nonlinear`: what Newton needs from a problem; the iteration report |
//! | `newton/` | load stepping, Newton iterations, step cutting, iteration report |

pub mod continuation;
pub mod gmres;
pub mod history;
pub mod interface;
pub mod ldlt;
pub mod line_search;
pub mod linear;
pub mod newton;
pub mod nonlinear;
pub mod problem;
