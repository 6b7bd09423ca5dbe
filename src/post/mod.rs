//! Post-processing of a converged state.
//!
//! | file | what |
//! |---|---|
//! | `plot.rs` | dependency-free SVG plots |
//! | `stress.rs` | Gauss-point stresses, extrapolation to nodes, nodal averages |
//! | `vtu.rs` | ParaView .vtu writer (raw appended binary, atomic write) |

pub mod plot;
pub mod stress;
pub mod vtu;
