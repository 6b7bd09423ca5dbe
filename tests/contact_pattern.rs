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
/// the master cells within a few cell sizes of the cells near the master at the start,
/// and after the first correction those near it at the geometry extrapolated to the
/// loading's end (as point-to-segment's, which is analysed twice here too): as the SSNP154
/// contact zone grows under load the matrix is analysed at most twice.
#[test]
fn mortar_contact_zone_grows_inside_one_anticipated_pattern() {
    use std::path::Path;
    use tribo::case::{self, ssnp154};
    for quadratic in [false, true] {
        let spec = ssnp154::builtin_mesh(quadratic, 1.5);
        let mesh = case::build_mesh(&spec, Path::new("")).unwrap();
        let c = ssnp154::contact_case("A", spec, Some("mortar"));
        let out = case::run(&c, &mesh, false).unwrap();
        assert!(
            out.report.symbolic_factorizations <= 2,
            "quadratic {quadratic}: {} analyses",
            out.report.symbolic_factorizations
        );
    }
}

/// Mortar on a graded interface: a coarse slave cell over fine master cells is paired
/// with every master cell within its own size, but the pattern reserves its couplings
/// only within a few sizes of the smaller cell (or once a node of it closes): an open
/// coarse cell some fine cells away couples nothing, and its nodes stay out of the contact
/// interface the solver condenses on, until they close.
#[test]
fn mortar_pattern_holds_an_open_coarse_cell_out_until_it_closes() {
    // master: the lower body's top, x in [-1, 9], cells 0.25 long; slave: the upper body's
    // bottom, cells 2 long, tilted to y = 0.25 x (gap 0 at x = 0, 2 at x = 8): the cells
    // over [4, 8] are 1 to 2 from the master, within their own size, beyond three of the
    // master's. (The node at x = 6 couples through the averaged normal at x = 4, which
    // its position moves.)
    let lower = rectangle([-1.0, -1.0], 10.0, 1.0, 40, 2, CellKind::Quad4, 0.0).unwrap();
    let mut upper = rectangle([0.0, 0.0], 8.0, 1.0, 4, 1, CellKind::Quad4, 0.0).unwrap();
    for x in &mut upper.coords {
        x[1] += 0.25 * x[0];
    }
    let mesh = common::bodies(&[("Lower", &lower), ("Upper", &upper)]);
    let first_upper = lower.num_nodes();
    // (large kinematics: the body laid flat below turns by 14°)
    let text = common::case_head(&[("LowerBody", 1000.0, 0.3), ("UpperBody", 1000.0, 0.3)])
        + "[model]\nkinematics = \"large\"\n"
        + common::HELD_BELOW_CONTACT_ABOVE
        + "formulation = \"mortar\"\n";
    let case: CaseFile = toml::from_str(&text).unwrap();
    let solid = build_problem(&case, &mesh).unwrap();
    let pairs = build_pairs(&case, &mesh).unwrap();
    assert_eq!(
        pairs[0].surfaces().0.nodes.len(),
        5,
        "the coarse bottom carries the multipliers"
    );
    let mut p = ContactProblem::new(solid, pairs);
    let n = p.num_unknowns();
    let mut r = vec![0.0; n];
    let x = p.unknowns();
    p.evaluate(&x, 1.0, &mut r, true).unwrap();
    // the upper body's bottom nodes (x = 0, 2, …, 8) whose displacements share an entry
    // with a multiplier
    let bottom = |p: &ContactProblem| -> Vec<f64> {
        let a = p.matrix();
        let nf = p.num_primal();
        (first_upper..mesh.num_nodes())
            .filter(|&n| (mesh.coords[n][1] - 0.25 * mesh.coords[n][0]).abs() < 1e-12)
            .filter(|&n| {
                (0..2).any(|comp| match p.solid.asm.dofs.roles[2 * n + comp] {
                    Role::Free(i) => a.row_idx[a.col_ptr[i]..a.col_ptr[i + 1]]
                        .iter()
                        .any(|&r| r >= nf),
                    _ => false,
                })
            })
            .map(|n| mesh.coords[n][0])
            .collect()
    };
    let coupled = bottom(&p);
    assert!(
        coupled.contains(&0.0) && coupled.contains(&4.0),
        "the cells near the master are coupled: {coupled:?}"
    );
    assert!(
        !coupled.contains(&8.0),
        "the open coarse cell's far node is not: {coupled:?}"
    );

    // the upper body laid flat 0.01 into the master: every slave node closes
    let mut u = vec![0.0; 2 * mesh.num_nodes()];
    for i in first_upper..mesh.num_nodes() {
        u[2 * i + 1] = -0.25 * mesh.coords[i][0] - 0.01;
    }
    let mut x = p.unknowns();
    let nf = p.num_primal();
    p.solid.asm.dofs.restrict(&u, &mut x[..nf]);
    p.update_status(&x, 1.0).unwrap();
    p.evaluate(&x, 1.0, &mut r, true).unwrap();
    let after = bottom(&p);
    assert!(
        after.contains(&8.0),
        "the far node, closed, is coupled: {after:?}"
    );
}
