//! Finite elements: shape functions, quadrature, materials, element kernels.
//!
//! | file | what |
//! |---|---|
//! | `element.rs` | shape functions and reference gradients per `CellKind` |
//! | `quadrature.rs` | Gauss rules: the reference code's stiffness rules, general rules |
//! | `material.rs` | isotropic elasticity, modelisations, von Mises |
//! | `solid.rs` | cell residual, tangent and Gauss-point stresses (small or large strain) |
//! | `extrapolate.rs` | Gauss point → node extrapolation matrices |

pub mod element;
pub mod extrapolate;
pub mod material;
pub mod quadrature;
pub mod solid;
