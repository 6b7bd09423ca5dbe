//! Manufactured-solution convergence: u = ∇ψ with ψ = eˣ sin y is harmonic, so div u = 0 and
//! Δu = 0, and u solves the Navier equations without body force for any λ, μ. Dirichlet
//! data on the whole boundary of [0,1]²; errors in L2 and in the energy norm against the
//! exact field, integrated with a high-order rule; rates fitted over 4 levels. The field is
//! scaled to strains of 0.1 % (the problem is linear: the rates do not depend on it), so that
//! no cell turns inside out, which a solve does not accept as a state.

mod common;
use common::*;
use tribo::fem::element::{shape, MAX_NODES};
use tribo::fem::material::{apply, Modelisation};
use tribo::fem::quadrature::exact_to_degree;
use tribo::fem::solid::{point_geometry, strain_at, SolidModel};
use tribo::mesh::generate::rectangle;
use tribo::mesh::CellKind;

const SCALE: f64 = 1e-3;

fn exact(x: [f64; 2]) -> [f64; 2] {
    [
        SCALE * x[0].exp() * x[1].sin(),
        SCALE * x[0].exp() * x[1].cos(),
    ]
}

/// Exact small strain [xx, yy, zz, γxy].
fn exact_strain(x: [f64; 2]) -> [f64; 4] {
    let (e, s, c) = (x[0].exp(), x[1].sin(), x[1].cos());
    [SCALE * e * s, -SCALE * e * s, 0.0, 2.0 * SCALE * e * c]
}

fn errors(kind: CellKind, n: usize, sm: &SolidModel) -> (f64, f64, f64) {
    let mesh = rectangle([0.0, 0.0], 1.0, 1.0, n, n, kind, 0.0).unwrap();
    let fixed = impose(&mesh, &["Bottom", "Right", "Top", "Left"], exact);
    let p = solve_elastic(&mesh, *sm, &fixed, vec![0.0; 2 * mesh.num_nodes()]);
    let d = sm.material.matrix(sm.model);
    let (mut l2, mut en) = (0.0, 0.0);
    for c in mesh.cells_of_dim(2) {
        let (x, nn) = mesh.cell_coords(c);
        let mut ue = [[0.0; 2]; MAX_NODES];
        for (a, &node) in mesh.cell_nodes(c).iter().enumerate() {
            ue[a] = [p.u[2 * node], p.u[2 * node + 1]];
        }
        let rule = exact_to_degree(kind, 10);
        for (q, &xi) in rule.points.iter().enumerate() {
            let g = point_geometry(kind, &x[..nn], xi, rule.weights[q], sm).unwrap();
            let mut nv = [0.0; MAX_NODES];
            shape(kind, xi, &mut nv);
            let mut xp = [0.0; 2];
            let mut uh = [0.0; 2];
            for a in 0..nn {
                for k in 0..2 {
                    xp[k] += nv[a] * x[a][k];
                    uh[k] += nv[a] * ue[a][k];
                }
            }
            let ex = exact(xp);
            l2 += ((uh[0] - ex[0]).powi(2) + (uh[1] - ex[1]).powi(2)) * g.dv;
            let (_, _, eh) = strain_at(&g, nn, &ue[..nn], sm);
            let ee = exact_strain(xp);
            let de: Vec<f64> = (0..4).map(|k| ee[k] - eh[k]).collect();
            let sd = apply(&d, &[de[0], de[1], de[2], de[3]]);
            en += (0..4).map(|k| sd[k] * de[k]).sum::<f64>() * g.dv;
        }
    }
    (1.0 / n as f64, l2.sqrt(), en.sqrt())
}

fn rates(kind: CellKind) -> (f64, f64) {
    let sm = model(Modelisation::PlaneStrain, 1.0, 0.3);
    let levels = [4, 8, 16, 32];
    let r: Vec<(f64, f64, f64)> = levels.iter().map(|&n| errors(kind, n, &sm)).collect();
    let h: Vec<f64> = r.iter().map(|t| t.0).collect();
    let l2: Vec<f64> = r.iter().map(|t| t.1).collect();
    let en: Vec<f64> = r.iter().map(|t| t.2).collect();
    let rates = (fitted_rate(&h, &l2), fitted_rate(&h, &en));
    println!(
        "{kind}: L2 {l2:?} rate {:.3}; energy {en:?} rate {:.3}",
        rates.0, rates.1
    );
    rates
}

#[test]
fn linear_cells_converge_at_rates_2_and_1() {
    for kind in [CellKind::Tri3, CellKind::Quad4] {
        let (l2, en) = rates(kind);
        assert!(l2 >= 1.9, "{kind}: L2 rate {l2}");
        assert!(en >= 0.95, "{kind}: energy rate {en}");
    }
}

#[test]
fn quadratic_cells_converge_at_rates_3_and_2() {
    for kind in [CellKind::Tri6, CellKind::Quad8] {
        let (l2, en) = rates(kind);
        assert!(l2 >= 2.9, "{kind}: L2 rate {l2}");
        assert!(en >= 1.9, "{kind}: energy rate {en}");
    }
}
