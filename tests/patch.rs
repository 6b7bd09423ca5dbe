//! Constant-strain patch tests: a linear displacement field imposed on the boundary of a
//! distorted mesh must be reproduced exactly inside, for every cell kind and modelisation.

mod common;
use common::*;
use tribo::fem::material::Modelisation;
use tribo::mesh::generate::rectangle;
use tribo::mesh::CellKind;
use tribo::post::stress::{cell_node_stresses, nodal_stresses};

const BOUNDARY: [&str; 4] = ["Bottom", "Right", "Top", "Left"];

fn check_patch(kind: CellKind, m: Modelisation) {
    // Origin at x = 1 so that the axisymmetric radius stays positive.
    let mesh = rectangle([1.0, 0.0], 2.0, 1.5, 4, 3, kind, 0.25).unwrap();
    // Axisymmetry: u_r = a r, u_z = b z + c has constant strain; plane: any linear field.
    let exact = |x: [f64; 2]| -> [f64; 2] {
        match m {
            Modelisation::Axisymmetric => [1e-3 * x[0], -2e-3 * x[1] + 0.01],
            _ => [
                1e-3 * x[0] + 4e-4 * x[1] + 0.02,
                -2e-3 * x[1] + 3e-4 * x[0] - 0.01,
            ],
        }
    };
    let fixed = impose(&mesh, &BOUNDARY, exact);
    let p = solve_elastic(
        &mesh,
        model(m, 1000.0, 0.3),
        &fixed,
        vec![0.0; 2 * mesh.num_nodes()],
    );
    let scale = 1e-2;
    for n in 0..mesh.num_nodes() {
        let e = exact(mesh.coords[n]);
        for (c, ec) in e.iter().enumerate() {
            let err = (p.u[2 * n + c] - ec).abs();
            assert!(
                err < 1e-10 * scale,
                "{kind} {m:?}: node {n} comp {c} error {err}"
            );
        }
    }
    // The recovered stresses are constant too.
    let elno = cell_node_stresses(&mesh, &p.asm, &p.u).unwrap();
    let s = nodal_stresses(&mesh, &p.asm, &elno, None).unwrap();
    let s0 = s[0];
    let smax = s0.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for si in &s {
        for k in 0..4 {
            assert!(
                (si[k] - s0[k]).abs() < 1e-9 * smax,
                "{kind} {m:?}: stress not constant"
            );
        }
    }
}

#[test]
fn patch_plane_strain() {
    for kind in [
        CellKind::Tri3,
        CellKind::Tri6,
        CellKind::Quad4,
        CellKind::Quad8,
    ] {
        check_patch(kind, Modelisation::PlaneStrain);
    }
}

#[test]
fn patch_plane_stress() {
    for kind in [
        CellKind::Tri3,
        CellKind::Tri6,
        CellKind::Quad4,
        CellKind::Quad8,
    ] {
        check_patch(kind, Modelisation::PlaneStress);
    }
}

#[test]
fn patch_axisymmetric() {
    for kind in [
        CellKind::Tri3,
        CellKind::Tri6,
        CellKind::Quad4,
        CellKind::Quad8,
    ] {
        check_patch(kind, Modelisation::Axisymmetric);
    }
}
