//! Post-processing of a converged state.
//!
//! | file | what |
//! |---|---|
//! | `contact_pressure.rs` | tractions from surface stresses, half-width |
//! | `plot.rs` | dependency-free SVG plots |
//! | `stress.rs` | Gauss-point stresses, extrapolation to nodes, nodal averages |
//! | `vtu.rs` | ParaView .vtu writer (raw appended binary, atomic write) |

pub mod contact_pressure;
pub mod plot;
pub mod stress;
pub mod vtu;
