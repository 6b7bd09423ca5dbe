//! Post-processing of a converged state.
//!
//! | file | what |
//! |---|---|
//! | `contact_picture.rs` | SVG of the deformed contact region coloured by von Mises |
//! | `contact_pressure.rs` | tractions from surface stresses, half-width |
//! | `curve.rs` | nodes of an edge group ordered by arc length |
//! | `contact_fields.rs` | the contact outputs of a contact problem's state, per pair |
//! | `contact_state.rs` | gap and open/stick/slip status at the slave nodes |
//! | `contact_summary.rs` | per pair: nodal contact values, resultants, length, centre, peak, counts |
//! | `probe.rs` | probes: their nodes, fields (Cauchy, PK2, polar, contact) and values |
//! | `plot.rs` | dependency-free SVG plots |
//! | `results/` | results.json's numbers and history.csv of an outcome, in memory |
//! | `result_vtu.rs` | result fields of a state as VTU, a load history as a .pvd series |
//! | `stress.rs` | Gauss-point stresses, extrapolation to nodes, nodal averages |
//! | `vtu.rs` | ParaView .vtu/.pvd writers (raw appended binary, atomic writes) |

pub mod contact_fields;
pub mod contact_picture;
pub mod contact_pressure;
pub mod contact_state;
pub mod contact_summary;
pub mod curve;
pub mod plot;
pub mod probe;
pub mod result_vtu;
pub mod results;
pub mod stress;
pub mod vtu;
