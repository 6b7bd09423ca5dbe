//! Built-in meshes: the SSNP154 geometry at any refinement, a pair of discs touching at one
//! point (Hertz contact of two cylinders or two spheres), rectangles and rings.
//!
//! | file | what |
//! |---|---|
//! | `cells.rs` | shared cell builders: quadtree cells, plain cells, boundary edge groups, points |
//! | `ssnp154.rs` | the SSNP154 block and half-cylinder (graded quadtrees) |
//! | `disc_pair.rs` | two half-discs touching at the origin, meshed independently |
//! | `grid.rs` | structured grids: rectangles and rings |

mod cells;
mod disc_pair;
mod grid;
mod ssnp154;

pub use disc_pair::{disc_pair, DiscPairOptions};
pub use grid::{rectangle, ring};
pub use ssnp154::{ssnp154, Ssnp154Options};

#[cfg(test)]
pub(crate) fn area(m: &super::Mesh) -> f64 {
    let mut total = 0.0;
    for c in m.cells_of_dim(2) {
        let kind = m.kind(c);
        let (x, nn) = m.cell_coords(c);
        let rule = crate::fem::quadrature::exact_to_degree(kind, 8);
        for (q, &xi) in rule.points.iter().enumerate() {
            total += rule.weights[q] * crate::fem::element::jacobian_det(kind, &x[..nn], xi);
        }
    }
    total
}
