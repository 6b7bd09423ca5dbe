//! Thick-walled cylinder under internal pressure (Lamé): radial displacement against the
//! closed form, plane strain (quarter ring) and axisymmetric (r-z section with the axial
//! displacement blocked at both ends, i.e. the plane-strain state), on quadratic meshes.

use tribo::case::{build_mesh, run, schema::CaseFile};

const A: f64 = 10.0;
const B: f64 = 20.0;
const P: f64 = 100.0;
const E: f64 = 200000.0;
const NU: f64 = 0.3;

/// Plane-strain Lamé radial displacement.
fn u_r(r: f64) -> f64 {
    (1.0 + NU) / E * P * A * A / (B * B - A * A) * ((1.0 - 2.0 * NU) * r + B * B / r)
}

fn max_relative_error(
    toml_text: &str,
    radius_of: impl Fn([f64; 2], [f64; 2]) -> (f64, f64),
) -> f64 {
    let case: CaseFile = toml::from_str(toml_text).unwrap();
    let mesh = build_mesh(&case.mesh, std::path::Path::new("")).unwrap();
    let out = run(&case, &mesh, false).unwrap();
    let mut worst: f64 = 0.0;
    for (n, x) in mesh.coords.iter().enumerate() {
        let (r, ur_h) = radius_of(*x, [out.u[2 * n], out.u[2 * n + 1]]);
        worst = worst.max(((ur_h - u_r(r)) / u_r(r)).abs());
    }
    worst
}

#[test]
fn lame_plane_strain_quarter_ring() {
    let text = format!(
        r#"
[mesh]
generator = "ring"
r_in = {A}
r_out = {B}
n_r = 8
n_theta = 16
angle = 90.0
cell = "Quad8"
[model]
modelisation = "plane_strain"
[[material]]
group = "Body"
E = {E}
nu = {NU}
[[displacement]]
group = "Start"
dy = 0.0
[[displacement]]
group = "End"
dx = 0.0
[[pressure]]
group = "Inner"
p = {P}
"#
    );
    let err = max_relative_error(&text, |x, u| {
        let r = x[0].hypot(x[1]);
        (r, (u[0] * x[0] + u[1] * x[1]) / r)
    });
    println!("plane strain Lamé: max relative error of u_r {err:.2e}");
    assert!(err < 1e-3, "{err}");
}

#[test]
fn lame_axisymmetric_section() {
    let text = format!(
        r#"
[mesh]
generator = "rectangle"
origin = [{A}, 0.0]
width = {w}
height = 5.0
nx = 8
ny = 4
cell = "Quad8"
[model]
modelisation = "axisymmetric"
[[material]]
group = "Body"
E = {E}
nu = {NU}
[[displacement]]
group = "Bottom"
dy = 0.0
[[displacement]]
group = "Top"
dy = 0.0
[[pressure]]
group = "Left"
p = {P}
"#,
        w = B - A
    );
    let err = max_relative_error(&text, |x, u| (x[0], u[0]));
    println!("axisymmetric Lamé: max relative error of u_r {err:.2e}");
    assert!(err < 1e-3, "{err}");
}
