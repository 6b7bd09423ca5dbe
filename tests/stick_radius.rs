//! The stick zone of a frictional point contact under refinement: the SSNP154 sphere
//! (steel, R = 50) pressed on the aluminium block by 60 kN in axisymmetry, mortar with
//! μ = 0.2, small kinematics, linear cells. The dissimilar materials slip at the rim of
//! the contact (Hertz a = 3.39) and stick inside. Measured here: the stick radius lies
//! between the outermost stick node and the next node, [2.625, 3.0] at 0.375,
//! [2.8125, 3.0] at 0.1875 ([2.719, 2.8125] at 0.09375, 9 s): brackets nested, their width
//! the node spacing, so the stick radius converges (to about 0.82 a) at the rate of h.

mod common;

use common::slave_rows;
use std::path::Path;
use tribo::case;
use tribo::case::schema::CaseFile;

/// (outermost stick node, next node outward, outermost loaded node) along the surface.
fn stick_bracket(size: f64) -> (f64, f64, f64) {
    let text = format!(
        r#"
[mesh]
generator = "ssnp154"
quadratic = false
size = {size}
[model]
modelisation = "axisymmetric"
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
fy = -60000.0
[[contact]]
slave = "Bottom_C"
master = "Top_B"
formulation = "mortar"
friction = 0.2
[output]
vtu = false
"#
    );
    let c: CaseFile = toml::from_str(&text).unwrap();
    let mesh = case::build_mesh(&c.mesh, Path::new("")).unwrap();
    let out = case::run(&c, &mesh, false).unwrap();
    let (mu, rows) = slave_rows(&mesh, &out, 0);
    let pmax = rows.iter().fold(0.0f64, |m, r| m.max(r.1));
    let loaded = |r: &(f64, f64, f64)| r.1 > 1e-6 * pmax;
    let (mut stick, mut next) = (0.0, 0.0);
    for (i, r) in rows.iter().enumerate() {
        assert!(r.2.abs() <= mu * r.1.max(0.0) + 1e-9 * pmax, "|t| above μp");
        if loaded(r) && r.2.abs() < mu * r.1 * (1.0 - 1e-9) {
            stick = r.0;
            next = rows.get(i + 1).map_or(r.0, |q| q.0);
        }
    }
    let edge = rows
        .iter()
        .filter(|r| loaded(r))
        .map(|r| r.0)
        .fold(0.0, f64::max);
    println!("size {size}: stick radius in [{stick}, {next}], contact to {edge}");
    (stick, next, edge)
}

#[test]
fn stick_radius_converges_under_refinement() {
    let levels: Vec<(f64, f64, f64)> = [0.75, 0.375, 0.1875]
        .iter()
        .map(|&h| stick_bracket(h))
        .collect();
    for (k, &(lo, hi, edge)) in levels.iter().enumerate().skip(1) {
        // a slip annulus at the rim, and the bracket inside the coarser one
        assert!(hi <= edge && lo < edge, "level {k}: no slip zone");
        let (plo, phi, _) = levels[k - 1];
        assert!(
            lo <= phi + 1e-12 && hi >= plo - 1e-12,
            "level {k}: brackets apart"
        );
        assert!(
            hi - lo < phi - plo + 1e-12,
            "level {k}: bracket not narrower"
        );
    }
}
