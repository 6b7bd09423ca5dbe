//! Post-processing of a converged state.
//!
//! | file | what |
//! |---|---|
//! | `stress.rs` | Gauss-point stresses, extrapolation to nodes, nodal averages |
//! | `vtu.rs` | ParaView .vtu writer (raw appended binary, atomic write) |

pub mod stress;
pub mod vtu;
