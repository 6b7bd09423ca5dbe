//! Axisymmetric Hertz contact: an elastic sphere on an elastic body. The SSNP154 geometry
//! turned about its axis x = 0 is a steel sphere (R = 50) on an aluminium cylinder (radius
//! 100, height 200), pressed by a force on the axis at the sphere's top. Against Hertz
//! (a = (3FR / 4E*)^(1/3), p0 = 3F / 2πa²; a/R = 0.07, and a body 30 a wide and 60 a deep
//! is a half-space to well below 1 % in 3D), with mortar on a refined quadratic mesh; the
//! pair's outputs carry the force and give the contact area of that radius.

use std::path::Path;
use tribo::case;
use tribo::case::schema::CaseFile;
use tribo::post::contact_pressure::half_width;

#[test]
fn sphere_on_a_body_matches_hertz_peak_pressure_and_contact_radius() {
    let force: f64 = 60000.0;
    let text = format!(
        r#"
[mesh]
generator = "ssnp154"
quadratic = true
size = 0.5
[model]
modelisation = "axisymmetric"
kinematics = "small"
[[material]]
group = "Block"
E = 70000.0
nu = 0.3
[[material]]
group = "Cylinder"
E = 210000.0
nu = 0.3
[[displacement]]
group = "Encast"
dx = 0.0
dy = 0.0
[[displacement]]
group = "Axe"
dx = 0.0
[[force]]
group = "Force"
fy = {}
[[contact]]
slave = "Bottom_C"
master = "Top_B"
formulation = "mortar"
initial = "closed"
initial_gap = 0.1
[output]
vtu = false
"#,
        -force
    );
    let c: CaseFile = toml::from_str(&text).unwrap();
    let mesh = case::build_mesh(&c.mesh, Path::new("")).unwrap();
    let out = case::run(&c, &mesh, false).unwrap();
    let e_star = 1.0 / ((1.0 - 0.09) / 210000.0 + (1.0 - 0.09) / 70000.0);
    let a = (3.0 * force * 50.0 / (4.0 * e_star)).cbrt();
    let p0 = 3.0 * force / (2.0 * std::f64::consts::PI * a * a);
    let samples: Vec<(f64, f64)> = out.contact_pressure[0]
        .iter()
        .map(|&(n, p)| (mesh.coords[n][0], p))
        .collect();
    let peak = samples.iter().fold(0.0f64, |m, s| m.max(s.1));
    let radius = half_width(&samples).unwrap();
    println!(
        "Hertz a = {a:.4}, p0 = {p0:.2}; computed a = {radius:.4} ({:+.3} %), peak = {peak:.2} ({:+.3} %), {} Newton iterations",
        100.0 * (radius / a - 1.0),
        100.0 * (peak / p0 - 1.0),
        out.report.total_iterations
    );
    assert!((peak / p0 - 1.0).abs() < 0.01, "peak {peak} vs {p0}");
    assert!((radius / a - 1.0).abs() < 0.01, "radius {radius} vs {a}");
    // the total contact force carries the load: Σ reactions on the block's base = F
    let base = mesh.node_group("Encast").unwrap();
    let ry: f64 = base.iter().map(|&n| out.reactions[2 * n + 1]).sum();
    assert!((ry / force - 1.0).abs() < 1e-6, "base reaction {ry}");
    // the pair's outputs, totals over 2πr: its normal resultant is the force (1e-8), its
    // contact area that of a disc within one slave cell of the Hertz radius
    let s = &out.contact[0].summary;
    let h = mesh
        .cell_group("Bottom_C")
        .unwrap()
        .iter()
        .find_map(|&c| {
            let n = mesh.cell_nodes(c);
            let (p, q) = (mesh.coords[n[0]], mesh.coords[n[1]]);
            (p[0].min(q[0]) <= a && a <= p[0].max(q[0])).then(|| (q[0] - p[0]).hypot(q[1] - p[1]))
        })
        .unwrap();
    let pi = std::f64::consts::PI;
    println!(
        "normal force {:?}, contact area {} (π a² = {}, cell {h} at r = a)",
        s.normal_force,
        s.contact_length,
        pi * a * a
    );
    // (on whichever body carries the multipliers: up on the sphere, down on the block)
    assert!((s.normal_force[1].abs() / force - 1.0).abs() < 1e-8);
    assert!(s.contact_length > pi * (a - h).powi(2) && s.contact_length < pi * (a + h).powi(2));
}
