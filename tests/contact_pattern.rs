//! The contact pattern (and so the interface the solver condenses on) holds only the part
//! of the slave surface within reach of the master; a point that comes within reach is
//! paired at the next status update and its couplings join the pattern.

mod common;

use tribo::assembly::dofs::Role;
use tribo::case::{build_pairs, build_problem, schema::CaseFile};
use tribo::contact::problem::ContactProblem;
use tribo::mesh::generate::rectangle;
use tribo::mesh::{CellKind, Mesh};
use tribo::solver::newton::Nonlinear;

/// Slave nodes (on y = 0, upper body) whose displacements share an entry with a multiplier.
fn coupled_slave_nodes(p: &ContactProblem, mesh: &Mesh, first_upper: usize) -> Vec<usize> {
    let a = p.matrix();
    let nf = p.num_primal();
    let mut out = vec![];
    for n in first_upper..mesh.num_nodes() {
        if mesh.coords[n][1].abs() > 1e-12 {
            continue;
        }
        let coupled = (0..2).any(|comp| match p.solid.asm.dofs.roles[2 * n + comp] {
            Role::Free(i) => a.row_idx[a.col_ptr[i]..a.col_ptr[i + 1]]
                .iter()
                .any(|&r| r >= nf),
            _ => false,
        });
        if coupled {
            out.push(n);
        }
    }
    out
}

#[test]
fn pattern_holds_the_slave_surface_within_reach_only() {
    // master top x in [0, 2] (cells 2/3 long); slave bottom x in [1.5, 5.5] (cells 2/3 long):
    // the initial candidates reach 3 cell sizes past the master (x ≈ 4), so the slave
    // nodes at x ≈ 4.83 and 5.5 are out of reach
    let lower = rectangle([0.0, -1.0], 2.0, 1.0, 3, 2, CellKind::Quad4, 0.0).unwrap();
    let upper = rectangle([1.5, 0.0], 4.0, 0.8, 6, 2, CellKind::Quad4, 0.0).unwrap();
    let mesh = common::bodies(&[("Lower", &lower), ("Upper", &upper)]);
    let first_upper = lower.num_nodes();
    let text = common::case_head(&[("LowerBody", 1000.0, 0.3), ("UpperBody", 1000.0, 0.3)])
        + common::HELD_BELOW_CONTACT_ABOVE
        + "formulation = \"point-to-segment\"\n";
    let case: CaseFile = toml::from_str(&text).unwrap();
    let solid = build_problem(&case, &mesh).unwrap();
    let pairs = build_pairs(&case, &mesh).unwrap();
    let mut p = ContactProblem::new(solid, pairs);
    let n = p.num_unknowns();
    let mut r = vec![0.0; n];
    let x = p.unknowns();
    p.evaluate(&x, 1.0, &mut r, true).unwrap();
    let near = coupled_slave_nodes(&p, &mesh, first_upper);
    let xs: Vec<f64> = near.iter().map(|&n| mesh.coords[n][0]).collect();
    assert!(
        xs.iter().any(|&x| x < 2.0),
        "slave nodes over the master are coupled: {xs:?}"
    );
    assert!(
        xs.iter().all(|&x| x < 4.5),
        "slave nodes far from the master are not: {xs:?}"
    );

    // slide the upper body 3 to the left: its far end comes over the master
    let mut u = vec![0.0; 2 * mesh.num_nodes()];
    for i in first_upper..mesh.num_nodes() {
        u[2 * i] = -3.0;
    }
    let mut x = p.unknowns();
    let nf = p.num_primal();
    p.solid.asm.dofs.restrict(&u, &mut x[..nf]);
    p.update_status(&x, 1.0).unwrap();
    p.evaluate(&x, 1.0, &mut r, true).unwrap();
    let after: Vec<f64> = coupled_slave_nodes(&p, &mesh, first_upper)
        .iter()
        .map(|&n| mesh.coords[n][0])
        .collect();
    assert!(
        after.iter().any(|&x| x > 4.5),
        "the far end, now over the master, is coupled: {after:?}"
    );
}

/// Mortar re-pairs on the current geometry at every status update; the pattern covers
/// the master cells within a few cell sizes, so as the SSNP154 contact zone grows under
/// load the matrix keeps its pattern and is analysed once.
#[test]
fn mortar_contact_zone_grows_inside_one_pattern() {
    use std::path::Path;
    use tribo::case::{self, ssnp154};
    for quadratic in [false, true] {
        let spec = ssnp154::builtin_mesh(quadratic, 1.5);
        let mesh = case::build_mesh(&spec, Path::new("")).unwrap();
        let c = ssnp154::contact_case("A", spec, Some("mortar"));
        let out = case::run(&c, &mesh, false).unwrap();
        assert_eq!(
            out.report.symbolic_factorizations, 1,
            "quadratic {quadratic}: one analysis"
        );
    }
}
