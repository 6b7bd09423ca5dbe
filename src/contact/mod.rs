//! Contact between bodies.
//!
//! | file | what |
//! |---|---|
//! | `surface.rs` | contact surfaces from edge groups: connected chains with outward sides |
//! | `projection.rs` | closest-point projection on Seg2/Seg3 segments |

pub mod projection;
pub mod surface;
