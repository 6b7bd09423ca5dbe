//! Node-to-segment friction with a tangential penalty k_t (a stick stiffness per node):
//! exact answers on a block on a clamped (rigid) base.
//! - Stick: a one-cell-wide column (its two bottom nodes carry equal shares), ν = 0, under
//!   pressure p and shear τ < μp on its top with the side shears that make the stress
//!   uniform: each bottom node slips s = (τW/2)/k_t, and the top moves s + τH/G. The
//!   shear is applied in three steps, so the force each step starts from counts.
//! - Slip: a block pressed and dragged far beyond the stick limit: the base's tangential
//!   over normal reaction is μ to 1e-6.

mod common;

use common::{bodies, case_head, group_sum};
use tribo::case::{run, schema::CaseFile, Outcome};
use tribo::mesh::generate::rectangle;
use tribo::mesh::{CellKind, Mesh};

const MU: f64 = 0.3;
const E: f64 = 1000.0;

fn solve(text: &str, mesh: &Mesh) -> Outcome {
    let case: CaseFile = toml::from_str(text).unwrap();
    run(&case, mesh, false).unwrap_or_else(|e| panic!("{e}"))
}

/// A base 3 × 1 from x = −1 (every node clamped: rigid) under a block at [0, w] × [0, h].
fn mesh(w: f64, h: f64, nx: usize, ny: usize) -> Mesh {
    let lower = rectangle([-1.0, -1.0], 3.0, 1.0, 3, 1, CellKind::Quad4, 0.0).unwrap();
    let upper = rectangle([0.0, 0.0], w, h, nx, ny, CellKind::Quad4, 0.0).unwrap();
    bodies(&[("Lower", &lower), ("Upper", &upper)])
}

fn head(nu: f64, contact: &str) -> String {
    format!(
        "{}[solver]\nsteps = 3\n[[displacement]]\ngroup = \"LowerBody\"\ndx = 0.0\ndy = 0.0\n\
         [[contact]]\nslave = \"UpperBottom\"\nmaster = \"LowerTop\"\n\
         formulation = \"node-to-segment\"\nfriction = {MU}\n{contact}\n\
         [[function]]\nname = \"ramp\"\ntable = [[0.0, 0.0], [1.0, 1.0]]\n",
        case_head(&[("LowerBody", E, nu), ("UpperBody", E, nu)])
    )
}

/// Top dx and the bottom nodes' dx of the column (pressure p, shear tau), and its top dy.
fn column(tau: f64, p: f64, contact: &str) -> ([f64; 2], Vec<f64>) {
    let (w, h) = (0.5, 1.0);
    let m = mesh(w, h, 1, 4);
    let text = format!(
        "{}[[pressure]]\ngroup = \"UpperTop\"\np = {p:?}\n\
         [[traction]]\ngroup = \"UpperTop\"\ntx = {tau:?}\nfunction = \"ramp\"\n\
         [[traction]]\ngroup = \"UpperLeft\"\nty = {:?}\nfunction = \"ramp\"\n\
         [[traction]]\ngroup = \"UpperRight\"\nty = {tau:?}\nfunction = \"ramp\"\n",
        head(0.0, contact),
        -tau
    );
    let out = solve(&text, &m);
    let top = m.node_group("UpperTop").unwrap();
    let bottom = m.node_group("UpperBottom").unwrap();
    let mean = |nodes: &[usize], c: usize| {
        nodes.iter().map(|&n| out.u[2 * n + c]).sum::<f64>() / nodes.len() as f64
    };
    for &n in &top {
        assert!(
            (out.u[2 * n] - mean(&top, 0)).abs() < 1e-12,
            "top moves as one"
        );
    }
    let slips = bottom.iter().map(|&n| out.u[2 * n]).collect();
    ([mean(&top, 0), mean(&top, 1)], slips)
}

#[test]
fn sticking_column_slips_the_spring_share_plus_the_elastic_shear() {
    let (w, h, p) = (0.5, 1.0, 10.0);
    let tau = 0.5 * MU * p; // each node: τW/2 against μ pW/2, half the cone
    let k_t = 200.0;
    let g = E / 2.0; // ν = 0
    let s = tau * w / 2.0 / k_t;
    let ([top_x, top_y], slips) = column(tau, p, &format!("tangential_penalty = {k_t:?}"));
    println!(
        "slips {slips:?} (exact {s}), top dx {top_x} (exact {})",
        s + tau * h / g
    );
    for sl in &slips {
        assert!((sl - s).abs() < 1e-9 * s, "bottom slip {sl}, exact {s}");
    }
    assert!((top_x - (s + tau * h / g)).abs() < 1e-9 * top_x);
    assert!((top_y + p * h / E).abs() < 1e-9 * p * h / E);
    // twice the stick stiffness: half the spring's share, the same elastic part
    let ([top_x2, _], _) = column(tau, p, &format!("tangential_penalty = {:?}", 2.0 * k_t));
    assert!((top_x2 - (s / 2.0 + tau * h / g)).abs() < 1e-9 * top_x2);
}

#[test]
fn sliding_block_resultants_are_in_the_coulomb_ratio() {
    let m = mesh(1.0, 0.5, 5, 3);
    for contact in [
        "tangential_penalty = 1000.0",
        "tangential_penalty = 1000.0\npenalty = 1e5",
    ] {
        let text = format!(
            "{}[[pressure]]\ngroup = \"UpperTop\"\np = 10.0\n\
             [[displacement]]\ngroup = \"UpperTop\"\ndx = 0.02\nfunction = \"ramp\"\n",
            head(0.3, contact)
        );
        let out = solve(&text, &m);
        let (rx, ry) = group_sum(&m, "LowerBody", &out.reactions);
        let ratio = rx.abs() / ry.abs();
        println!("{contact}: base reaction ({rx}, {ry}), ratio {ratio}");
        assert!(
            (ry.abs() - 10.0).abs() < 1e-8 * 10.0,
            "normal resultant {ry}"
        );
        assert!((ratio - MU).abs() < 1e-6, "tangential / normal = {ratio}");
    }
}
