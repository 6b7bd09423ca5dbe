//! Contact between bodies.
//!
//! | file | what |
//! |---|---|
//! | `axis.rs` | the pressure at slave nodes of zero weight (on the axis) from their neighbours |
//! | `surface.rs` | contact surfaces from edge groups: connected chains with outward sides |
//! | `projection.rs` | closest-point projection on Seg2/Seg3 segments; their points and tangents |
//! | `real.rs` | the number type of exactly differentiated code (f64 or dual) |
//! | `friction.rs` | Coulomb's law as a pure return map (semi-multiplier form) |
//! | `pair.rs` | the `ContactPair` interface of the formulations |
//! | `mortar/` | dual mortar, nodal weighted gaps and active set |
//! | `point_segment/` | the reference code's continuous formulation (augmented Lagrangian, per-point status) |
//! | `overlap/` | the physical check: no contact node deep inside the other body |
//! | `problem.rs` | `ContactProblem`: bodies + pairs as one nonlinear problem |

pub mod axis;
pub mod friction;
pub mod mortar;
pub mod overlap;
pub mod pair;
pub mod point_segment;
pub mod problem;
pub mod projection;
pub mod real;
pub(crate) mod smoothed_normal;
pub mod surface;
