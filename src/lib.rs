//! tribo: a finite-element solver for frictional contact between elastic bodies in 2D
//! (plane strain, plane stress, axisymmetry).
//!
//! Units are whatever the user's are, consistently; the SSNP154 benchmark uses mm, N, MPa.
//!
//! | module | what |
//! |---|---|
//! | `mesh` | nodes, cells, groups; Gmsh reader; built-in generators |
//! | `assembly` | dof map (imposed, linked), sparse pattern, parallel assembly, loads |
//! | `solver` | faer direct solvers, Newton with load steps |
//! | `post` | stresses at nodes, VTU output |
//! | `case` | TOML case files, built-in SSNP154 cases |
//! | `cli` | the `tribo` command |
//! | `progress` | the status line of long work on a terminal, `--quiet` |
//! | `fem` | shape functions, quadrature, materials, element kernels |
//! | `expr` | values given as expressions of x, y and t (compiled once, errors placed) |
//! | `union_find` | disjoint sets (bodies of a mesh, blocks of an interface) |

// Index loops mirror the formulas (sums over nodes, components, Gauss points).
#![allow(clippy::needless_range_loop)]

pub mod alloc_cap;
pub mod assembly;
pub mod case;
pub mod cli;
pub mod contact;
pub mod error;
pub mod expr;
pub mod fem;
pub mod memory;
pub mod mesh;
pub mod post;
pub mod progress;
pub mod solver;
pub mod union_find;

pub use error::{Error, Result};
