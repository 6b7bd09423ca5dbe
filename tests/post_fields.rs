//! Probe and curve fields against exact answers (issue 21, item 6): polar stresses of a
//! ring under internal pressure (Lamé), second Piola–Kirchhoff stress beside Cauchy with
//! large kinematics (St Venant–Kirchhoff stretch; S = J F⁻¹ σ F⁻ᵀ), contact values at slave
//! nodes, and the errors that name a bad probe.

use std::path::Path;
use std::process::Command;
use tribo::case::{self, schema::CaseFile, ssnp154};
use tribo::fem::solid::StressMeasure;
use tribo::post::stress::{cell_node_stresses_as, nodal_stresses};

const A: f64 = 10.0;
const B: f64 = 20.0;
const P: f64 = 100.0;

/// Lamé's σ_rr and σ_θθ at radius r (internal pressure P on r = A, free at r = B).
fn lame(r: f64) -> (f64, f64) {
    let k = P * A * A / (B * B - A * A);
    (k * (1.0 - B * B / (r * r)), k * (1.0 + B * B / (r * r)))
}

/// The quarter ring of tests/lame.rs, twice finer radially (plane strain, Quad8: the
/// extrapolated stresses of its mid-side nodes within 0.5 %), with polar probes at mid-wall
/// on the 45° line and a curve along θ = 0 with its polar columns.
const RING: &str = r#"
[mesh]
generator = "ring"
r_in = 10.0
r_out = 20.0
n_r = 16
n_theta = 16
angle = 90.0
cell = "Quad8"
[[material]]
group = "Body"
E = 200000.0
nu = 0.3
[[displacement]]
group = "Start"
dy = 0.0
[[displacement]]
group = "End"
dx = 0.0
[[pressure]]
group = "Inner"
p = 100.0
[[output.probe]]
name = "srr"
at = [10.6066017178, 10.6066017178]
field = "sirr"
center = [0.0, 0.0]
[[output.probe]]
name = "stt"
at = [10.6066017178, 10.6066017178]
field = "sitt"
center = [0.0, 0.0]
[[output.probe]]
name = "srt"
at = [10.6066017178, 10.6066017178]
field = "sirt"
center = [0.0, 0.0]
[[output.curve]]
name = "start"
group = "Start"
center = [0.0, 0.0]
"#;

/// σ_rr, σ_θθ within 0.5 % of Lamé (σ_rθ below 0.5 % of P) at the probes' node and along
/// the whole θ = 0 line, inner and outer surface included, in curve_start.csv.
#[test]
fn polar_stresses_of_a_ring_under_internal_pressure_are_lame() {
    let case: CaseFile = toml::from_str(RING).unwrap();
    let mesh = case::build_mesh(&case.mesh, Path::new("")).unwrap();
    let out = case::run(&case, &mesh, false).unwrap();
    let at = case.output.probe[0].at.unwrap();
    let node = (0..mesh.num_nodes())
        .min_by(|&a, &b| {
            let d = |n: usize| (mesh.coords[n][0] - at[0]).hypot(mesh.coords[n][1] - at[1]);
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    let r = mesh.coords[node][0].hypot(mesh.coords[node][1]);
    let get = |n: &str| out.probes.iter().find(|p| p.0 == n).unwrap().1;
    let (srr, stt) = lame(r);
    println!(
        "r = {r}: sirr {} (Lamé {srr}), sitt {} (Lamé {stt}), sirt {}",
        get("srr"),
        get("stt"),
        get("srt")
    );
    assert!((get("srr") / srr - 1.0).abs() < 5e-3);
    assert!((get("stt") / stt - 1.0).abs() < 5e-3);
    assert!(get("srt").abs() < 5e-3 * P);
    // the curve through the CLI: its polar columns along θ = 0
    let dir = std::env::temp_dir().join(format!("tribo-post-fields-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ring.toml"), RING).unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .arg("run")
        .arg(dir.join("ring.toml"))
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("ring/curve_start.csv")).unwrap();
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    let (cx, crr, ctt, crt) = (col("x"), col("sirr"), col("sitt"), col("sirt"));
    let mut worst = 0.0f64;
    for line in csv.lines().skip(1) {
        let f: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        let (srr, stt) = lame(f[cx]);
        // σ_rr vanishes at r = B: its error is measured against P there
        worst = worst
            .max((f[crr] - srr).abs() / srr.abs().max(P))
            .max((f[ctt] / stt - 1.0).abs())
            .max(f[crt].abs() / P);
    }
    println!("curve along θ = 0: largest relative deviation from Lamé {worst:.2e}");
    assert!(worst < 5e-3, "{worst}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A plane-strain plate stretched by 20 % (large kinematics, free to contract): the exact
/// St Venant–Kirchhoff state S_xx = E/(1 − ν²) E_xx, S_yy = 0, σ_xx = F_xx S_xx / F_yy, in
/// the probes pk2xx, pk2yy and sixx (1e-9: the Newton tolerance, 1e-12).
#[test]
fn pk2_probe_of_a_stretched_plate_is_st_venant_kirchhoff() {
    let (e, nu, stretch): (f64, f64, f64) = (1000.0, 0.3, 1.2);
    let text = format!(
        r#"
[mesh]
generator = "rectangle"
width = 2.0
height = 1.0
nx = 4
ny = 2
cell = "Quad8"
[model]
kinematics = "large"
[[material]]
group = "Body"
E = {e:?}
nu = {nu:?}
[[displacement]]
group = "Left"
dx = 0.0
[[displacement]]
group = "Bottom"
dy = 0.0
[[displacement]]
group = "Right"
dx = {}
[solver]
steps = 2
tolerance = 1e-12
[[output.probe]]
name = "Sxx"
group = "TopRight"
field = "pk2xx"
[[output.probe]]
name = "Syy"
group = "TopRight"
field = "pk2yy"
[[output.probe]]
name = "sxx"
group = "TopRight"
field = "sixx"
"#,
        2.0 * (stretch - 1.0)
    );
    let case: CaseFile = toml::from_str(&text).unwrap();
    let mesh = case::build_mesh(&case.mesh, Path::new("")).unwrap();
    let out = case::run(&case, &mesh, false).unwrap();
    let get = |n: &str| out.probes.iter().find(|p| p.0 == n).unwrap().1;
    let exx = 0.5 * (stretch * stretch - 1.0);
    let sxx = e / (1.0 - nu * nu) * exx;
    let eyy = -nu / (1.0 - nu) * exx;
    let fyy = (1.0 + 2.0 * eyy).sqrt();
    let cauchy = stretch * sxx / fyy;
    println!(
        "S_xx {} (exact {sxx}), S_yy {}, σ_xx {} (exact {cauchy})",
        get("Sxx"),
        get("Syy"),
        get("sxx")
    );
    assert!((get("Sxx") / sxx - 1.0).abs() < 1e-9);
    assert!(get("Syy").abs() < 1e-9 * sxx);
    assert!((get("sxx") / cauchy - 1.0).abs() < 1e-9);
    assert!(
        out.pk2.is_some(),
        "large kinematics writes PK2 beside Cauchy"
    );
}

/// Under a homogeneous deformation with shear (u = H X, F = I + H), every nodal PK2 stress
/// is J F⁻¹ σ F⁻ᵀ of the nodal Cauchy stress (1e-12), plane strain and axisymmetric
/// (S_zz = J σ_zz / F_zz², F_zz = 1 + u_r/r: uniform when u_r depends on r alone).
#[test]
fn pk2_and_cauchy_are_related_by_the_deformation_gradient() {
    for modelisation in ["plane_strain", "axisymmetric"] {
        let text = format!(
            "[mesh]\ngenerator = \"rectangle\"\norigin = [1.0, 0.0]\nwidth = 2.0\nheight = 1.0\n\
             nx = 3\nny = 2\ncell = \"Quad8\"\n[model]\nkinematics = \"large\"\n\
             modelisation = \"{modelisation}\"\n[[material]]\ngroup = \"Body\"\nE = 1000.0\n\
             nu = 0.3\n[[displacement]]\ngroup = \"Left\"\ndx = 0.0\ndy = 0.0\n"
        );
        let case: CaseFile = toml::from_str(&text).unwrap();
        let mesh = case::build_mesh(&case.mesh, Path::new("")).unwrap();
        let mut problem = case::build_problem(&case, &mesh).unwrap();
        let axi = modelisation == "axisymmetric";
        let h = [[0.15, if axi { 0.0 } else { 0.25 }], [-0.1, 0.05]];
        for (n, x) in mesh.coords.iter().enumerate() {
            for (i, row) in h.iter().enumerate() {
                problem.u[2 * n + i] = row[0] * x[0] + row[1] * x[1];
            }
        }
        let f = [[1.0 + h[0][0], h[0][1]], [h[1][0], 1.0 + h[1][1]]];
        let fzz = if axi { 1.0 + h[0][0] } else { 1.0 };
        let stresses = |m| {
            let e = cell_node_stresses_as(&mesh, &problem.asm, &problem.u, m).unwrap();
            nodal_stresses(&mesh, &problem.asm, &e, None).unwrap()
        };
        let (sigma, pk2) = (
            stresses(StressMeasure::Cauchy),
            stresses(StressMeasure::Pk2),
        );
        let det = f[0][0] * f[1][1] - f[0][1] * f[1][0];
        let inv = [
            [f[1][1] / det, -f[0][1] / det],
            [-f[1][0] / det, f[0][0] / det],
        ];
        let scale = pk2.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut worst = 0.0f64;
        for (s, pk) in sigma.iter().zip(&pk2) {
            let j = det * fzz;
            let m = [[s[0], s[3]], [s[3], s[1]]];
            let mut want = [[0.0; 2]; 2];
            for (a, row) in want.iter_mut().enumerate() {
                for (b, w) in row.iter_mut().enumerate() {
                    for p in 0..2 {
                        for q in 0..2 {
                            *w += j * inv[a][p] * m[p][q] * inv[b][q];
                        }
                    }
                }
            }
            let want = [want[0][0], want[1][1], j * s[2] / (fzz * fzz), want[0][1]];
            for k in 0..4 {
                worst = worst.max((pk[k] - want[k]).abs() / scale);
            }
        }
        println!("{modelisation}: largest |S − J F⁻¹ σ F⁻ᵀ| / max|S| = {worst:.1e}");
        assert!(worst < 1e-12, "{modelisation}: {worst:e}");
    }
}

/// Contact probes read the slave node's values (those of the per-pair outputs); a contact
/// field on a node off every slave surface, a polar field without its centre and a centre
/// on a non-polar field are refused before the solve, naming the probe.
#[test]
fn contact_probes_read_slave_nodes_and_bad_probes_are_named() {
    let spec = ssnp154::builtin_mesh(false, 1.5);
    let mesh = case::build_mesh(&spec, Path::new("")).unwrap();
    let mut c = ssnp154::contact_case("A", spec, None);
    let probe = |name: &str, field: &str, group: Option<&str>, at: Option<[f64; 2]>| {
        case::schema::ProbeSpec {
            name: name.into(),
            group: group.map(Into::into),
            at,
            field: field.into(),
            stress_group: at.map(|_| "Cylinder".to_string()),
            center: None,
        }
    };
    // the cylinder's lowest node (its bottom point), and the node C on its axis
    c.output
        .probe
        .push(probe("p0", "contact_pressure", None, Some([0.0, 0.0])));
    c.output
        .probe
        .push(probe("g0", "contact_gap", None, Some([0.0, 0.0])));
    c.output
        .probe
        .push(probe("s0", "contact_status", None, Some([0.0, 0.0])));
    let out = case::run(&c, &mesh, false).unwrap();
    let get = |n: &str| out.probes.iter().find(|p| p.0 == n).unwrap().1;
    let bottom = out.contact[0]
        .nodes
        .iter()
        .find(|n| mesh.coords[n.node][0].abs() < 1e-9 && mesh.coords[n.node][1].abs() < 1e-9)
        .unwrap();
    println!(
        "bottom node {}: pressure {}, gap {}, status {}",
        bottom.node + 1,
        get("p0"),
        get("g0"),
        get("s0")
    );
    assert_eq!(get("p0"), bottom.pressure);
    assert_eq!(get("g0"), bottom.gap);
    assert_eq!(get("s0"), 1.0, "stick (closed, frictionless)");
    assert!(get("p0") > 0.0);
    // bad probes
    let refused = |p: case::schema::ProbeSpec| {
        let mut bad = ssnp154::contact_case("A", ssnp154::builtin_mesh(false, 1.5), None);
        bad.output.probe = vec![p];
        case::run(&bad, &mesh, false).err().unwrap().to_string()
    };
    let e = refused(probe("far", "contact_pressure", Some("Encast"), None));
    assert!(
        e.starts_with("probe 'far': node ") && e.contains("is on no slave surface"),
        "{e}"
    );
    let e = refused(probe("polar", "sitt", Some("B"), None));
    assert_eq!(
        e,
        "probe 'polar': field 'sitt' (a polar component) needs center = [x, y], the pole of \
         the polar frame"
    );
    let mut centred = probe("dy", "dy", Some("B"), None);
    centred.center = Some([0.0, 0.0]);
    let e = refused(centred);
    assert_eq!(
        e,
        "probe 'dy': center is for the polar fields sirr, sitt, sirt only, not 'dy'"
    );
}
