//! tribo: a finite-element solver for frictional contact between elastic bodies in 2D
//! (plane strain, plane stress, axisymmetry).
//!
//! Units are whatever the user's are, consistently; the SSNP154 benchmark uses mm, N, MPa.
//!
//! | module | what |
//! |---|---|
//! | `mesh` | nodes, cells, groups; Gmsh reader; built-in generators |
//! | `fem` | shape functions, quadrature, materials, element kernels |

pub mod error;
pub mod fem;
pub mod mesh;

pub use error::{Error, Result};
