//! Load histories: time functions on loads and imposed displacements, output times,
//! imposed rigid motions, and large sliding under displacement control.

mod common;

use common::{block_contact, block_on_foundation, bodies, case_head, group_sum};
use tribo::case::run;
use tribo::case::schema::CaseFile;
use tribo::mesh::generate::{rectangle, ring};
use tribo::mesh::CellKind;
use tribo::post::contact_state::gaps;

fn case(text: &str) -> CaseFile {
    toml::from_str(text).unwrap()
}

/// Linear elasticity follows its load: a force loaded to 1 at t = 1 and unloaded to 0.5 at
/// t = 2 gives at t = 2 half the displacement of t = 1 (exact), and a displacement imposed
/// through a table is imposed at its table's value at each output time.
#[test]
fn loads_follow_their_time_functions_at_the_output_times() {
    let mesh = rectangle([0.0, 0.0], 4.0, 1.0, 8, 2, CellKind::Quad8, 0.0).unwrap();
    let head = case_head(&[("Body", 1000.0, 0.3)]);
    let text = format!(
        r#"{head}
[[function]]
name = "load-unload"
table = [[0, 0], [1, 1], [2, 0.5]]
[[function]]
name = "there-and-back"
table = [[0, 0], [0.5, 1], [2, -2]]
[[displacement]]
group = "Left"
dy = 0.0
[[displacement]]
group = "TopLeft"
dx = 0.0
[[displacement]]
group = "Bottom"
dx = 0.01
function = "there-and-back"
[[force]]
group = "Right"
fy = -1.0
function = "load-unload"
[solver]
steps = 3
[output]
times = [0.5, 1.0, 2.0]
[[output.probe]]
name = "tip"
at = [4.0, 1.0]
field = "dy"
[[output.probe]]
name = "bottom"
at = [2.0, 0.0]
field = "dx"
"#
    );
    let out = run(&case(&text), &mesh, false).unwrap();
    let times: Vec<f64> = out.steps.iter().map(|s| s.time).collect();
    assert_eq!(times, vec![0.5, 1.0, 2.0]);
    // step ends: the grid 2/3, 4/3, 2, the output times and the tables' kinks 0.5, 1
    let ends: Vec<f64> = out.report.steps.iter().map(|s| s.time).collect();
    let want = [0.5, 2.0 / 3.0, 1.0, 4.0 / 3.0, 2.0];
    assert_eq!(ends.len(), want.len(), "{ends:?}");
    for (a, b) in ends.iter().zip(want) {
        assert!((a - b).abs() < 1e-15, "{ends:?}");
    }
    // The imposed dx on Bottom and the force combine linearly: separate their parts with
    // the three output states (f_load = 0.5, 1, 0.5; f_disp = 1, 0, -2).
    let tip: Vec<f64> = out.steps.iter().map(|s| s.probes[0].1).collect();
    let bottom: Vec<f64> = out.steps.iter().map(|s| s.probes[1].1).collect();
    for (b, f) in bottom.iter().zip([1.0, 0.0, -2.0]) {
        assert!((b - 0.01 * f).abs() < 1e-14, "bottom dx {bottom:?}");
    }
    // tip(t) = f_load · a + f_disp · b: from t = 0.5 and t = 1, predict t = 2
    let a = tip[1];
    let b = tip[0] - 0.5 * a;
    let predicted = 0.5 * a - 2.0 * b;
    println!("tip dy {tip:?}, predicted at t = 2: {predicted:e}");
    assert!(a < 0.0, "the force pushes the tip down");
    assert!(
        (tip[2] - predicted).abs() < 1e-9 * a.abs(),
        "t = 2: {} vs {predicted}",
        tip[2]
    );
}

/// Large kinematics: a body turned by a quarter turn through the displacements of one edge
/// follows as a rigid body, without strain (St Venant–Kirchhoff is exact under rotation).
#[test]
fn imposed_rotation_turns_a_body_rigidly() {
    let mesh = rectangle([1.0, 0.0], 2.0, 1.0, 6, 3, CellKind::Quad4, 0.0).unwrap();
    let mut head = case_head(&[("Body", 1000.0, 0.3)]);
    head.push_str("[model]\nkinematics = \"large\"\n");
    let text = format!(
        r#"{head}
[[rotation]]
group = "Left"
center = [0.0, 0.0]
angle = 90.0
[solver]
steps = 6
"#
    );
    let out = run(&case(&text), &mesh, false).unwrap();
    let mut worst = 0.0f64;
    for (n, x) in mesh.coords.iter().enumerate() {
        // a quarter turn about the origin: (x, y) -> (-y, x)
        let want = [-x[1] - x[0], x[0] - x[1]];
        for (c, w) in want.iter().enumerate() {
            worst = worst.max((out.u[2 * n + c] - w).abs());
        }
    }
    let smax = out
        .stress
        .iter()
        .flat_map(|s| s.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    println!("rigid quarter turn: max |u - u_rigid| = {worst:.2e}, max |stress| = {smax:.2e}");
    assert!(worst < 1e-9, "{worst:e}");
    assert!(smax < 1e-6, "{smax:e}");
    assert_eq!(out.report.steps.len(), 6);
}

/// A block dragged 2.5 units along a foundation of 0.25-unit cells (ten segments) with
/// Coulomb friction: the slave nodes are re-paired with new master segments all along, and
/// in every output step once sliding the tangential reaction is μ times the normal one
/// (1e-6) and the normal reaction is unchanged (1e-6: the foundation is uniform).
#[test]
fn large_sliding_along_a_flat_foundation_keeps_coulomb_and_the_normal_force() {
    for formulation in ["mortar", "point-to-segment"] {
        let (mesh, head) = block_on_foundation(6.0, 24);
        let contact = block_contact(formulation);
        let text = format!(
            r#"{head}
[model]
kinematics = "large"
[[function]]
name = "press"
table = [[0, 0], [1, 1]]
[[function]]
name = "drag"
table = [[0, 0], [1, 0], [11, 1]]
[[displacement]]
group = "LowerBody"
dx = 0.0
dy = 0.0
[[displacement]]
group = "UpperTop"
dx = 2.5
function = "drag"
[[displacement]]
group = "UpperTop"
dy = -0.005
function = "press"
{contact}
[solver]
steps = 22
"#
        );
        let out = run(&case(&text), &mesh, false).unwrap();
        let top = mesh.node_group("UpperTop").unwrap();
        let force = |r: &[f64]| group_sum(&mesh, "UpperTop", r);
        let sliding: Vec<&tribo::case::StepOutcome> =
            out.steps.iter().filter(|s| s.time >= 2.0).collect();
        assert_eq!(sliding.len(), 19, "{formulation}");
        let ry0 = force(&sliding[0].reactions).1;
        let (mut worst_ratio, mut worst_normal) = (0.0f64, 0.0f64);
        for s in &sliding {
            let (rx, ry) = force(&s.reactions);
            worst_ratio = worst_ratio.max(((rx / ry).abs() / 0.3 - 1.0).abs());
            worst_normal = worst_normal.max((ry / ry0 - 1.0).abs());
        }
        // the slave has moved on by ten master segments and touches without penetration
        let (slave, master) = &out.contact_surfaces[0];
        let g = gaps(&mesh, &out.u, slave, master);
        let worst_gap = g.iter().fold(0.0f64, |m, p| m.max(p.1.abs()));
        println!(
            "{formulation}: 19 sliding steps, max ||RX/RY|/mu - 1| = {worst_ratio:.2e}, \
             max |RY/RY0 - 1| = {worst_normal:.2e}, final max |gap| = {worst_gap:.2e}"
        );
        assert!(ry0 < 0.0, "{formulation}: pressed down");
        assert!(worst_ratio < 1e-6, "{formulation}: {worst_ratio:e}");
        assert!(worst_normal < 1e-6, "{formulation}: {worst_normal:e}");
        assert!(worst_gap < 1e-9, "{formulation}: gap {worst_gap:e}");
        let moved = out.u[2 * top[0]];
        assert!((moved - 2.5).abs() < 1e-12);
    }
}

/// Large sliding along a curved master: a ring segment (12°) pressed into a clamped ring
/// (an initial interference of 0.002, resolved in the first step) and then turned by 50°
/// about the common centre through its outer nodes ([[rotation]]) with Coulomb friction
/// (μ = 0.2), over 17 master segments of 3°, 1° per step. At the end the interface is
/// closed (nodal gaps below 1 % of the interference: mortar closes weighted gaps) and the friction is at the cone (|t| = μ p at
/// every loaded node); while it slides the supports drive it round (M > 0; M / (μ R |F|) is
/// printed: |F| is the resultant, a little below ∫p) and the contact force keeps its size
/// (1 %: the ring is uniform away from its ends).
#[test]
fn large_sliding_along_a_curved_master_under_imposed_rotation() {
    let outer = ring(1.0, 1.2, 2, 30, 90.0, CellKind::Quad8).unwrap();
    let block = ring(1.198, 1.3, 2, 4, 12.0, CellKind::Quad8).unwrap();
    let mesh = bodies(&[("Base", &outer), ("Shoe", &block)]);
    let head = case_head(&[("BaseBody", 200000.0, 0.3), ("ShoeBody", 200000.0, 0.3)]);
    let text = format!(
        r#"{head}
[model]
kinematics = "large"
[[function]]
name = "turn"
table = [[0, 0], [1, 0], [6, 1]]
[[displacement]]
group = "BaseInner"
dx = 0.0
dy = 0.0
[[rotation]]
group = "ShoeOuter"
center = [0.0, 0.0]
angle = 50.0
function = "turn"
[[contact]]
slave = "ShoeInner"
master = "BaseOuter"
formulation = "mortar"
initial = "all"
friction = 0.2
[solver]
steps = 60
"#
    );
    let out = run(&case(&text), &mesh, false).unwrap();
    assert_eq!(out.steps.len(), 60);
    println!("{} Newton iterations", out.report.total_iterations);
    let top = mesh.node_group("ShoeOuter").unwrap();
    let mut normal = vec![];
    for s in &out.steps {
        // the resultant of the reactions on the shoe, and its moment about the centre
        let (mut f, mut m) = ([0.0, 0.0], 0.0);
        for &n in &top {
            let x = [
                mesh.coords[n][0] + s.u[2 * n],
                mesh.coords[n][1] + s.u[2 * n + 1],
            ];
            let r = [s.reactions[2 * n], s.reactions[2 * n + 1]];
            f[0] += r[0];
            f[1] += r[1];
            m += x[0] * r[1] - x[1] * r[0];
        }
        normal.push((s.time, f[0].hypot(f[1]), m));
    }
    for &(t, f, m) in &normal {
        println!("t = {t:.2}: |F| = {f:.4e}, M = {m:.4e}");
    }
    // turning: the supports drive the shoe round against friction (M = μ R |F|), and the
    // resultant keeps its size
    let sliding: Vec<&(f64, f64, f64)> = normal.iter().filter(|v| v.0 >= 2.0).collect();
    let f0 = sliding[0].1;
    let spread = sliding
        .iter()
        .map(|v| (v.1 / f0 - 1.0).abs())
        .fold(0.0, f64::max);
    let moment = sliding
        .iter()
        .map(|v| (v.2 / (0.2 * 1.2 * v.1) - 1.0).abs())
        .fold(0.0, f64::max);
    println!(
        "sliding: max | |F| / |F0| - 1 | = {spread:.2e}, max |M / (mu R |F|) - 1| = {moment:.2e}"
    );
    assert!(
        sliding.iter().all(|v| v.2 > 0.0),
        "the moment drives the turn"
    );
    assert!(spread < 0.01, "{spread:e}");
    let (slave, master) = &out.contact_surfaces[0];
    let g = gaps(&mesh, &out.u, slave, master);
    let worst_gap = g.iter().fold(0.0f64, |m, p| m.max(p.1.abs()));
    // mortar closes the weighted gaps; the nodal ones on the curved non-matching surfaces
    // are its discretisation error: small against the interference resolved
    println!("final max |gap| = {worst_gap:.2e} (interference 2e-3)");
    assert!(worst_gap < 0.01 * 2e-3, "{worst_gap:e}");
    let (mu, shear) = &out.contact_shear[0];
    let p: std::collections::HashMap<usize, f64> =
        out.contact_pressure[0].iter().copied().collect();
    let pmax = p.values().fold(0.0f64, |m, v| m.max(*v));
    for &(n, t) in shear {
        if p[&n] > 1e-3 * pmax {
            assert!(
                (t.abs() / (mu * p[&n]) - 1.0).abs() < 1e-6,
                "node {}: |t| = {t}, mu p = {}",
                n + 1,
                mu * p[&n]
            );
        }
    }
}
