//! Memory checks of a case before work starts (see `crate::memory`): a generated mesh from
//! its counts before it is made, the model from its mesh before it is assembled.

use super::schema::{CaseFile, MeshSpec};
use crate::error::Result;
use crate::memory::{self, Contact, Model};
use crate::mesh::{CellKind, Mesh};

/// Nodes and cells of a structured grid of `a` × `b` cells of `kind`.
fn grid(a: u64, b: u64, kind: CellKind) -> (u64, u64) {
    let corners = (a + 1).saturating_mul(b + 1);
    let fine = (2 * a + 1).saturating_mul(2 * b + 1);
    let ab = a.saturating_mul(b);
    match kind {
        CellKind::Tri3 => (corners, 2 * ab),
        CellKind::Tri6 => (fine, 2 * ab),
        CellKind::Quad8 => (fine - ab, ab),
        _ => (corners, ab),
    }
}

/// The rectangle and ring generators: the mesh, and at least an elastic solve of it,
/// must fit in memory; checked from nx × ny (n_r × n_theta) before anything is made.
pub fn check_generated(spec: &MeshSpec) -> Result<()> {
    let (keys, a, b) = match spec.generator.as_deref() {
        Some("rectangle") => ("nx × ny", spec.nx, spec.ny),
        Some("ring") => ("n_r × n_theta", spec.n_r, spec.n_theta),
        _ => return Ok(()),
    };
    let (Some(a), Some(b)) = (a, b) else {
        return Ok(()); // reported by the generator
    };
    let kind = spec
        .cell
        .as_deref()
        .and_then(CellKind::from_name)
        .unwrap_or(CellKind::Quad4);
    let (nodes, cells) = grid(a as u64, b as u64, kind);
    let what = format!("[mesh] {keys} = {a} × {b} ({nodes} nodes, {cells} {kind} cells)");
    memory::check(&what, memory::mesh_bytes(nodes, cells, kind.num_nodes()))?;
    let solve = memory::solve_bytes(&Model {
        nodes: nodes as usize,
        quadratic: kind.is_quadratic(),
        contact: Contact::None,
        kept_states: 1,
    });
    memory::check(&format!("solving the mesh of {what}"), solve)
}

/// The model of a case on its mesh, before assembly.
pub fn check_model(case: &CaseFile, mesh: &Mesh) -> Result<()> {
    let quadratic = mesh.cells_of_dim(2).any(|c| mesh.kind(c).is_quadratic());
    let contact = if case.contact.is_empty() {
        Contact::None
    } else if case.contact.iter().all(|c| c.formulation == "mortar") {
        Contact::Mortar
    } else {
        Contact::Pointwise
    };
    let kept_states = if case.output.history {
        case.solver.steps.max(1)
    } else {
        1
    };
    let bytes = memory::solve_bytes(&Model {
        nodes: mesh.num_nodes(),
        quadratic,
        contact,
        kept_states,
    });
    let what = format!(
        "the model ({} nodes, {} unknowns{}{})",
        mesh.num_nodes(),
        2 * mesh.num_nodes(),
        match contact {
            Contact::None => "",
            Contact::Mortar => ", mortar contact",
            Contact::Pointwise => ", contact",
        },
        if kept_states > 1 {
            format!(", {kept_states} load steps kept for the history")
        } else {
            String::new()
        }
    );
    memory::check(&what, bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_counts_match_the_generator() {
        for kind in [
            CellKind::Tri3,
            CellKind::Tri6,
            CellKind::Quad4,
            CellKind::Quad8,
        ] {
            let m =
                crate::mesh::generate::rectangle([0.0, 0.0], 2.0, 1.0, 5, 3, kind, 0.0).unwrap();
            let (nodes, cells) = grid(5, 3, kind);
            assert_eq!(nodes as usize, m.num_nodes(), "{kind}");
            assert_eq!(cells as usize, m.cells_of_dim(2).count(), "{kind}");
        }
    }
}
