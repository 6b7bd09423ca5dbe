//! Hertz contact of two equal elastic bodies with curved faces, frictionless mortar, small
//! kinematics: two cylinders (plane strain) and two spheres (axisymmetric), each a half disc
//! of radius R = 50 of the `disc_pair` generator, the lower disc's arc cells 1.15 times the
//! upper's at the contact (non-matching, but close enough that the multipliers stay on the
//! side named slave: both sides are tried). Force F on the top of the upper disc, the bottom
//! of the lower one held. Against Hertz (equal bodies: R* = R/2, E* = E / 2(1 − ν²)):
//! cylinders a = √(4 P R* / π E*), p0 = 2P / πa (P = 2F per unit length of the full
//! cylinder); spheres a = (3 F R* / 4 E*)^(1/3), p0 = 3F / 2πa². The problem is symmetric
//! about y = 0, so the answer must be too, whichever arc carries the multipliers: the pole
//! stresses of the two bodies equal, the interface on the axis half-way between the disc
//! centres, no tangential force on either body.

mod common;

use std::path::Path;
use tribo::assembly::coupled::Triplets;
use tribo::case;
use tribo::case::schema::CaseFile;
use tribo::post::contact_pressure::half_width;

const E: f64 = 210000.0;
const NU: f64 = 0.3;
const R: f64 = 50.0;

struct Answer {
    peak: f64,
    half_width: f64,
    pole_upper: f64,
    pole_lower: f64,
    /// (interface on the axis − mean of the centres) / approach of the centres
    midplane_offset: f64,
    /// Σ|f_x| / Σ|f_y| of the contact forces on the master's nodes
    master_tangential: f64,
    iterations: usize,
    /// (x, pressure) of every slave node
    samples: Vec<(f64, f64)>,
}

fn case_text(
    axisymmetric: bool,
    quadratic: bool,
    size: f64,
    slave_upper: bool,
    stretch: f64,
) -> String {
    let (slave, master) = if slave_upper {
        ("Upper_arc", "Lower_arc")
    } else {
        ("Lower_arc", "Upper_arc")
    };
    let (modelisation, force) = if axisymmetric {
        ("axisymmetric", 60000.0)
    } else {
        ("plane_strain", 17500.0)
    };
    format!(
        r#"
[mesh]
generator = "disc_pair"
radius = {R}
quadratic = {quadratic}
size = {size}
stretch = {stretch}
[model]
modelisation = "{modelisation}"
kinematics = "small"
[[material]]
group = "Upper"
E = {E}
nu = {NU}
[[material]]
group = "Lower"
E = {E}
nu = {NU}
[[displacement]]
group = "Bottom"
dy = 0.0
[[displacement]]
group = "Axe"
dx = 0.0
[[force]]
group = "Top"
fy = -{force}
[[contact]]
slave = "{slave}"
master = "{master}"
formulation = "mortar"
[output]
vtu = false
[[output.probe]]
name = "pole_upper"
group = "Upper_tip"
field = "siyy"
stress_group = "Upper"
[[output.probe]]
name = "pole_lower"
group = "Lower_tip"
field = "siyy"
stress_group = "Lower"
[[output.probe]]
name = "tip"
group = "Upper_tip"
field = "dy"
[[output.probe]]
name = "centre_upper"
at = [0.0, {R}]
field = "dy"
[[output.probe]]
name = "centre_lower"
at = [0.0, -{R}]
field = "dy"
"#
    )
}

fn solve(axisymmetric: bool, quadratic: bool, size: f64, slave_upper: bool) -> Answer {
    let text = case_text(axisymmetric, quadratic, size, slave_upper, 1.15);
    let c: CaseFile = toml::from_str(&text).unwrap();

    let mesh = case::build_mesh(&c.mesh, Path::new("")).unwrap();
    let out = case::run(&c, &mesh, false).unwrap();
    let probe = |name: &str| out.probes.iter().find(|p| p.0 == name).unwrap().1;
    let samples: Vec<(f64, f64)> = out.contact_pressure[0]
        .iter()
        .map(|&(n, p)| (mesh.coords[n][0], p))
        .collect();
    let (cu, cl) = (probe("centre_upper"), probe("centre_lower"));
    // contact forces on the master's nodes at the solution
    let mut pairs = case::build_pairs(&c, &mesh).unwrap();
    let pair = &mut pairs[0];
    let named = if slave_upper {
        "Upper_arc"
    } else {
        "Lower_arc"
    };
    assert_eq!(
        pair.surfaces().0.group,
        named,
        "the multipliers stay on the slave named"
    );
    pair.initialise(&mesh);
    let of: std::collections::HashMap<usize, f64> = out.contact_multipliers[0]
        .iter()
        .map(|&(n, l)| (n, l[0]))
        .collect();
    let lam: Vec<f64> = pair.multiplier_nodes().iter().map(|n| of[n]).collect();
    let mut ru = vec![0.0; 2 * mesh.num_nodes()];
    let mut rl = vec![0.0; lam.len()];
    pair.contribute(
        &mesh,
        &out.u,
        &lam,
        &mut ru,
        &mut rl,
        &mut Triplets::default(),
        0,
    );
    let (_, master) = pair.surfaces();
    let fx: f64 = master.nodes.iter().map(|&n| ru[2 * n].abs()).sum();
    let fy: f64 = master.nodes.iter().map(|&n| ru[2 * n + 1].abs()).sum();
    Answer {
        peak: samples.iter().fold(0.0f64, |m, s| m.max(s.1)),
        half_width: half_width(&samples).unwrap(),
        pole_upper: probe("pole_upper"),
        pole_lower: probe("pole_lower"),
        midplane_offset: (probe("tip") - 0.5 * (cu + cl)) / (cu - cl),
        master_tangential: fx / fy,
        iterations: out.report.total_iterations,
        samples,
    }
}

fn hertz(axisymmetric: bool) -> (f64, f64) {
    let e_star = E / (2.0 * (1.0 - NU * NU));
    let r_star = R / 2.0;
    if axisymmetric {
        let f = 60000.0;
        let a = (3.0 * f * r_star / (4.0 * e_star)).cbrt();
        (a, 3.0 * f / (2.0 * std::f64::consts::PI * a * a))
    } else {
        let p = 2.0 * 17500.0;
        let a = (4.0 * p * r_star / (std::f64::consts::PI * e_star)).sqrt();
        (a, 2.0 * p / (std::f64::consts::PI * a))
    }
}

fn check(axisymmetric: bool, quadratic: bool, size: f64) {
    let (a, p0) = hertz(axisymmetric);
    let answers: Vec<Answer> = [true, false]
        .iter()
        .map(|&upper| solve(axisymmetric, quadratic, size, upper))
        .collect();
    for (s, x) in ["upper", "lower"].iter().zip(&answers) {
        let what = format!("axisymmetric {axisymmetric}, quadratic {quadratic}, slave {s}");
        println!(
            "{what}: peak {:+.3} %, half-width {:+.3} %, poles {:.1} / {:.1} ({:+.3} %), \
             midplane offset {:.1e}, master tangential/normal {:.1e}, {} iterations",
            100.0 * (x.peak / p0 - 1.0),
            100.0 * (x.half_width / a - 1.0),
            x.pole_upper,
            x.pole_lower,
            100.0 * (x.pole_upper / x.pole_lower - 1.0),
            x.midplane_offset,
            x.master_tangential,
            x.iterations
        );
        assert!(
            (x.peak / p0 - 1.0).abs() < 0.01,
            "{what}: peak {} vs {p0}",
            x.peak
        );
        assert!(
            (x.half_width / a - 1.0).abs() < 0.01,
            "{what}: a {} vs {a}",
            x.half_width
        );
        assert!(
            (x.pole_upper / x.pole_lower - 1.0).abs() < 0.01,
            "{what}: pole stresses"
        );
        // what pressure.csv gives is a pressure at every slave node, vertex and mid-side
        // alike: within 1 % of p0 of Hertz's p0 √(1 − (x/a)²) inside 0.9 a
        let worst = x
            .samples
            .iter()
            .filter(|s| s.0.abs() < 0.9 * a)
            .map(|s| (s.1 - p0 * (1.0 - (s.0 / a).powi(2)).sqrt()).abs() / p0)
            .fold(0.0f64, f64::max);
        println!(
            "{what}: nodal pressures within 0.9 a at most {:.3} % of p0 from Hertz",
            100.0 * worst
        );
        assert!(
            worst < 0.01,
            "{what}: nodal pressure {worst} of p0 from Hertz"
        );
        assert!(
            x.midplane_offset.abs() < 1e-3,
            "{what}: interface off the midplane"
        );
        // the contact pushes along the axis: the exact tangential share is 0, the slave
        // normal alone would give about a/R ~ 4 % here
        assert!(
            x.master_tangential < 0.01,
            "{what}: tangential force on the master"
        );
    }
    let (u, l) = (&answers[0], &answers[1]);
    assert!(
        (u.peak / l.peak - 1.0).abs() < 0.01,
        "slave choice changes the peak"
    );
    assert!(
        (u.pole_upper / l.pole_upper - 1.0).abs() < 0.01,
        "slave choice changes the poles"
    );
    assert!(
        (u.half_width / l.half_width - 1.0).abs() < 0.01,
        "slave choice changes a"
    );
}

#[test]
fn two_quadratic_cylinders_match_hertz_whichever_side_is_the_slave() {
    check(false, true, 0.25);
}

#[test]
fn two_quadratic_spheres_match_hertz_whichever_side_is_the_slave() {
    check(true, true, 0.25);
}

#[test]
fn two_linear_cylinders_match_hertz_whichever_side_is_the_slave() {
    check(false, false, 0.0625);
}

#[test]
fn two_linear_spheres_match_hertz_whichever_side_is_the_slave() {
    check(true, false, 0.0625);
}

#[test]
fn the_multipliers_go_on_the_coarser_arc_whatever_the_naming() {
    for slave_upper in [true, false] {
        let text = case_text(false, false, 0.5, slave_upper, 1.3);
        let c: CaseFile = toml::from_str(&text).unwrap();
        let mesh = case::build_mesh(&c.mesh, Path::new("")).unwrap();
        let pairs = case::build_pairs(&c, &mesh).unwrap();
        assert_eq!(pairs[0].surfaces().0.group, "Lower_arc");
        assert_eq!(pairs[0].surfaces().1.group, "Upper_arc");
    }
}

/// Unequal bodies (the lower disc three times softer, as SSNP154's block): the interface
/// normal weighs the two surfaces' normals by the other body's compliance, so the answer
/// is still the same whichever side carries the multipliers, and Hertz's (with
/// 1/E* = (1 − ν²)/E1 + (1 − ν²)/E2).
#[test]
fn unequal_cylinders_match_hertz_whichever_side_is_the_slave() {
    let soft = 70000.0;
    let e_star = 1.0 / ((1.0 - NU * NU) / E + (1.0 - NU * NU) / soft);
    let p = 2.0 * 17500.0;
    let a = (4.0 * p * (R / 2.0) / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * p / (std::f64::consts::PI * a);
    let mut peaks = vec![];
    for slave_upper in [true, false] {
        let text = case_text(false, true, 0.25, slave_upper, 1.15);
        let lower = text.rfind(&format!("E = {E}")).unwrap();
        let text = format!(
            "{}E = {soft}{}",
            &text[..lower],
            &text[lower + format!("E = {E}").len()..]
        );
        let c: CaseFile = toml::from_str(&text).unwrap();
        let mesh = case::build_mesh(&c.mesh, Path::new("")).unwrap();
        let out = case::run(&c, &mesh, false).unwrap();
        let samples: Vec<(f64, f64)> = out.contact_pressure[0]
            .iter()
            .map(|&(n, p)| (mesh.coords[n][0], p))
            .collect();
        let peak = samples.iter().fold(0.0f64, |m, s| m.max(s.1));
        let hw = half_width(&samples).unwrap();
        println!(
            "slave upper {slave_upper}: peak {:+.3} %, half-width {:+.3} %",
            100.0 * (peak / p0 - 1.0),
            100.0 * (hw / a - 1.0)
        );
        assert!((peak / p0 - 1.0).abs() < 0.01, "peak {peak} vs {p0}");
        assert!((hw / a - 1.0).abs() < 0.01, "a {hw} vs {a}");
        peaks.push(peak);
    }
    assert!((peaks[0] / peaks[1] - 1.0).abs() < 0.01, "{peaks:?}");
}

/// Newton converges quadratically on frictionless mortar contact with large kinematics
/// once the active set has settled: the tangent (dual numbers through the whole mortar
/// kernel) is the exact derivative of the residual. (Full Newton: no chord steps, no
/// frozen bodies' tangent.)
#[test]
fn mortar_newton_converges_quadratically_with_large_kinematics() {
    use tribo::solver::linear::Method;
    use tribo::solver::newton::{solve, NewtonSettings, Nonlinear};
    for (axisymmetric, quadratic, size) in [(false, true, 0.5), (true, false, 0.25)] {
        let text = case_text(axisymmetric, quadratic, size, true, 1.15)
            .replace("kinematics = \"small\"", "kinematics = \"large\"");
        let c: CaseFile = toml::from_str(&text).unwrap();
        let mesh = case::build_mesh(&c.mesh, Path::new("")).unwrap();
        let solid = case::build_problem(&c, &mesh).unwrap();
        let pairs = case::build_pairs(&c, &mesh).unwrap();
        let mut p = tribo::contact::problem::ContactProblem::new(solid, pairs);
        let settings = NewtonSettings {
            tolerance: 1e-12,
            max_iterations: 40,
            chord_steps: false,
            frozen_bodies: false,
            reuse_factor: false,
            ..Default::default()
        };
        let report = solve(&mut p, &settings, Method::SaddleLdlt).unwrap();
        assert!(p.num_unknowns() > 0);
        let it = &report.steps.last().unwrap().iterations;
        let r: Vec<f64> = it.iter().map(|i| i.relative_residual).collect();
        println!("axisymmetric {axisymmetric}, quadratic {quadratic}: residuals {r:?}");
        // the last correction at settled statuses from a small residual to one above
        // round-off (1e-13: the linear stage's converged residuals, 2–6e-14 in these runs,
        // show where it lies): log r_{k+1} / log r_k ≥ 1.8 (2 is quadratic)
        let pair = (0..r.len() - 1)
            .rev()
            .find(|&k| r[k] < 1e-2 && r[k + 1] > 1e-13 && it[k].status_changes == 0)
            .expect("an iteration pair in the asymptotic range");
        let order = r[pair + 1].ln() / r[pair].ln();
        println!("pair {} -> {}: order {order:.2}", r[pair], r[pair + 1]);
        assert!(order >= 1.8, "order {order}: {r:?}");
    }
}

/// Refinement study: two linear cylinders (the default mortar, small kinematics) at cell
/// sizes 0.25, 0.125, 0.0625: the peak pressure and the half-width within 1 % of Hertz at
/// every level, and the peak converging (its changes between levels shrink: measured
/// +0.122, +0.108, +0.102 %, the changes 0.014 then 0.006 %, a rate of about 1.2 toward a
/// limit about 0.1 % above Hertz's half-space value, which finite discs need not meet).
#[test]
fn linear_cylinders_converge_to_hertz_under_refinement() {
    let (a, p0) = hertz(false);
    let sizes = [0.25, 0.125, 0.0625];
    let (mut ep, mut ea) = (vec![], vec![]);
    for &h in &sizes {
        let x = solve(false, false, h, true);
        ep.push((x.peak / p0 - 1.0).abs());
        ea.push((x.half_width / a - 1.0).abs());
        println!(
            "h = {h}: peak {:+.3} %, half-width {:+.3} %",
            100.0 * (x.peak / p0 - 1.0),
            100.0 * (x.half_width / a - 1.0)
        );
    }
    let (rp, ra) = (
        common::fitted_rate(&sizes, &ep),
        common::fitted_rate(&sizes, &ea),
    );
    println!("rates from Hertz: peak {rp:.2}, half-width {ra:.2}");
    assert!(ep.iter().chain(&ea).all(|&e| e < 0.01), "{ep:?} {ea:?}");
    assert!(
        (ep[2] - ep[1]).abs() < (ep[1] - ep[0]).abs(),
        "the peak does not settle: {ep:?}"
    );
}

/// Two linear cylinders with large kinematics, the whole load in one step, from three
/// starts: the touching point, the points within 0.1 closed (a zone of half-width 2.2,
/// smaller than Hertz's 3.1) and within 0.3 (3.9, larger). Each converges without a step
/// cut to the same state (frictionless elastic contact has one solution): the pole
/// displacement within 1e-8 of the touching start's. Iterations, with the linear stage
/// (src/solver/continuation.rs), at 0.25, 0.125, 0.0625: touching 10, 14, 14 (the first
/// iterate, held at one point, closes every overlapping node; the zone then sheds its
/// outer ring a few nodes per iteration); closed 0.1: 6, 10, 10; closed 0.3: 6, 9, 10.
/// Without the stage: 8, 8, 36; 8, 8, 10; 10, 15, 59, and at 0.0625 the touching and 0.3
/// starts cut the step twice. At most 16 (touching) and 12 (closed).
/// (Before the augmentation's curvature left the tangent: 51–182 iterations in 3–10 load
/// steps, the touching start at 0.0625 failing.)
#[test]
fn mortar_with_large_kinematics_converges_in_one_step_from_any_closed_start() {
    for size in [0.25, 0.125, 0.0625] {
        let mut tips = vec![];
        for start in [
            "",
            "initial = \"closed\"\ninitial_gap = 0.1",
            "initial = \"closed\"\ninitial_gap = 0.3",
        ] {
            let text = case_text(false, false, size, true, 1.15)
                .replace("kinematics = \"small\"", "kinematics = \"large\"")
                .replace(
                    "formulation = \"mortar\"",
                    &format!("formulation = \"mortar\"\n{start}"),
                );
            let c: CaseFile = toml::from_str(&text).unwrap();
            let mesh = case::build_mesh(&c.mesh, Path::new("")).unwrap();
            let out =
                case::run(&c, &mesh, false).unwrap_or_else(|e| panic!("{size} {start:?}: {e}"));
            let tip = out.probes.iter().find(|p| p.0 == "tip").unwrap().1;
            let steps = out.report.steps.len();
            let its = out.report.total_iterations;
            println!(
                "size {size}, start {start:?}: tip {tip:.10}, {its} iterations, {steps} steps"
            );
            assert_eq!(steps, 1, "{size} {start:?}: a step cut");
            let most = if start.is_empty() { 16 } else { 12 };
            assert!(its <= most, "{size} {start:?}: {its} iterations");
            tips.push(tip);
        }
        for t in &tips[1..] {
            assert!((t / tips[0] - 1.0).abs() < 1e-8, "size {size}: {tips:?}");
        }
    }
}
