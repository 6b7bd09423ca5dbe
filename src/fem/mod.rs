//! Finite elements: shape functions, quadrature, materials, element kernels.
//!
//! | file | what |
//! |---|---|
//! | `element.rs` | shape functions and reference gradients per `CellKind` |

pub mod element;
