//! Values as expressions of x, y and t (issue 21): two concentric rings loaded only by
//! radial displacements imposed by expressions on their free circles, in contact: the
//! contact pressure is Lamé's within 0.5 %. Expressions without t follow the default ramp,
//! expressions of t give the total value at t; bad expressions are errors naming the
//! entry and the position, a non-finite value names the node.

mod common;

use common::{bodies, case_head};
use tribo::case::{build_problem, run, schema::CaseFile};
use tribo::mesh::generate::ring;
use tribo::mesh::CellKind;

const E: f64 = 200_000.0;
const NU: f64 = 0.3;
const A: f64 = 10.0; // inner radius of the inner ring
const B: f64 = 15.0; // the interface
const C: f64 = 25.0; // outer radius of the outer ring
const UA: f64 = 0.01; // radial displacement imposed on r = A
const UC: f64 = -0.01; // radial displacement imposed on r = C

/// Lamé, plane strain: (α, β) of u = α r + β / r with u(r_u) = u and σ_rr(r_s) = s.
fn lame(r_u: f64, u: f64, r_s: f64, s: f64) -> (f64, f64) {
    let mu = E / (2.0 * (1.0 + NU));
    let lambda = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
    // α r_u + β / r_u = u;  2(λ + μ) α − 2μ β / r_s² = s
    let (a11, a12, a21, a22) = (r_u, 1.0 / r_u, 2.0 * (lambda + mu), -2.0 * mu / (r_s * r_s));
    let det = a11 * a22 - a12 * a21;
    ((u * a22 - a12 * s) / det, (a11 * s - a21 * u) / det)
}

/// The contact pressure: the rings' radial displacements at B agree (linear in p).
fn interface_pressure() -> f64 {
    let gap = |p: f64| {
        let (a1, b1) = lame(A, UA, B, -p);
        let (a2, b2) = lame(C, UC, B, -p);
        (a2 * B + b2 / B) - (a1 * B + b1 / B)
    };
    let (g0, g1) = (gap(0.0), gap(1.0));
    -g0 / (g1 - g0)
}

/// Quarter rings (angle 90) or whole ones (360: closed contact curves).
fn rings_of(kind: CellKind, angle: f64) -> tribo::mesh::Mesh {
    let n_theta = (24.0 * angle / 90.0) as usize;
    let inner = ring(A, B, 4, n_theta, angle, kind).unwrap();
    let outer = ring(B, C, 6, n_theta, angle, kind).unwrap();
    bodies(&[("In", &inner), ("Out", &outer)])
}

fn rings(kind: CellKind) -> tribo::mesh::Mesh {
    rings_of(kind, 90.0)
}

/// The rings' case: symmetry on the quarter's straight sides, the radial displacements by
/// expressions (inner circle: no t, scaled by the default ramp; outer circle: t in it).
fn rings_case(formulation: &str) -> CaseFile {
    let head = case_head(&[("InBody", E, NU), ("OutBody", E, NU)]);
    let text = format!(
        r#"{head}
[[displacement]]
group = "InStart"
dy = 0.0
[[displacement]]
group = "OutStart"
dy = 0.0
[[displacement]]
group = "InEnd"
dx = 0.0
[[displacement]]
group = "OutEnd"
dx = 0.0
[[displacement]]
group = "InInner"
dx = "{UA:e}*x/sqrt(x^2+y^2)"
dy = "{UA:e}*y/sqrt(x^2+y^2)"
[[displacement]]
group = "OutOuter"
dx = "t*({UC:e})*x/{C:?}"
dy = "t*({UC:e})*y/{C:?}"
[[contact]]
slave = "InOuter"
master = "OutInner"
formulation = "{formulation}"
[solver]
steps = 2
"#
    );
    toml::from_str(&text).unwrap()
}

#[test]
fn rings_pressed_by_imposed_radial_displacements_give_lames_pressure() {
    let p = interface_pressure();
    assert!(p > 0.0, "the rings must press on each other: p = {p}");
    for (formulation, kind) in [
        ("mortar", CellKind::Quad8),
        ("point-to-segment", CellKind::Quad4),
    ] {
        let mesh = rings(kind);
        let case = rings_case(formulation);
        let out = run(&case, &mesh, false).unwrap_or_else(|e| panic!("{formulation}: {e}"));
        let worst = out.contact_pressure[0]
            .iter()
            .map(|&(_, pc)| (pc / p - 1.0).abs())
            .fold(0.0f64, f64::max);
        println!(
            "{formulation} {kind:?}: Lamé p = {p:.4}, worst slave node {:.4} %",
            100.0 * worst
        );
        assert!(
            worst < 5e-3,
            "{formulation}: contact pressure off by {:.3} %",
            100.0 * worst
        );
        // the imposed values, at every node of both circles (they are on the circles)
        for (group, u) in [("InInner", UA), ("OutOuter", UC)] {
            for n in mesh.node_group(group).unwrap() {
                let x = mesh.coords[n];
                let r = x[0].hypot(x[1]);
                for (c, xc) in x.iter().enumerate() {
                    let want = u * xc / r;
                    assert!(
                        (out.u[2 * n + c] - want).abs() <= 1e-15,
                        "{group} node {n}: {} != {want}",
                        out.u[2 * n + c]
                    );
                }
            }
        }
    }
}

#[test]
fn whole_rings_with_closed_contact_curves_give_lames_pressure() {
    // no symmetry conditions: the imposed circles hold the rings
    let p = interface_pressure();
    for (formulation, kind) in [
        ("mortar", CellKind::Quad8),
        ("point-to-segment", CellKind::Quad4),
    ] {
        let mesh = rings_of(kind, 360.0);
        let mut case = rings_case(formulation);
        case.displacement.drain(..4);
        assert_eq!(case.displacement[0].group, "InInner");
        let out = run(&case, &mesh, false).unwrap_or_else(|e| panic!("{formulation}: {e}"));
        let slave = &out.contact_pressure[0];
        assert_eq!(slave.len(), mesh.node_group("InOuter").unwrap().len());
        let worst = slave
            .iter()
            .map(|&(_, pc)| (pc / p - 1.0).abs())
            .fold(0.0f64, f64::max);
        println!(
            "whole rings, {formulation} {kind:?}: Lamé p = {p:.4}, worst slave node {:.4} %",
            100.0 * worst
        );
        assert!(
            worst < 5e-3,
            "{formulation}: contact pressure off by {:.3} %",
            100.0 * worst
        );
    }
}

#[test]
fn expressions_of_t_give_the_total_value_at_t() {
    // half-way: the ramped inner circle and the outer circle's t are both at half
    let mesh = rings(CellKind::Quad4);
    let mut case = rings_case("mortar");
    case.solver.steps = 4;
    case.output.times = Some(vec![0.5, 1.0]);
    let out = run(&case, &mesh, false).unwrap();
    let half = out.steps.iter().find(|s| s.time == 0.5).unwrap();
    let full = out.steps.iter().find(|s| s.time == 1.0).unwrap();
    for n in mesh.node_group("OutOuter").unwrap() {
        let x = mesh.coords[n];
        let want = 0.5 * UC * x[0] / C;
        assert!(
            (half.u[2 * n] - want).abs() <= 1e-15,
            "{} != {want}",
            half.u[2 * n]
        );
        assert!((full.u[2 * n] - 2.0 * want).abs() <= 1e-15);
    }
    // linear problem: the half-way state is half the final one
    let worst = half
        .u
        .iter()
        .zip(&full.u)
        .map(|(h, f)| (2.0 * h - f).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-9 * UA.abs(), "{worst}");
}

fn error_of(case: &CaseFile, mesh: &tribo::mesh::Mesh) -> String {
    match run(case, mesh, false) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_expressions_name_the_entry_and_the_place() {
    let mesh = rings(CellKind::Quad4);
    let edit = |from: &str, to: &str| -> CaseFile {
        let text = toml::to_string(&rings_case("mortar")).unwrap();
        assert!(text.contains(from), "{from}");
        toml::from_str(&text.replacen(from, to, 1)).unwrap()
    };
    let e = error_of(&edit("*x/sqrt(x^2+y^2)", "*z/sqrt(x^2+y^2)"), &mesh);
    assert_eq!(
        e,
        "[[displacement]] 5 on 'InInner': dx = \"1e-2*z/sqrt(x^2+y^2)\", character 6: unknown \
         name 'z'; the variables are x, y, t (functions: abs, signum, sin, cos, tan, asin, \
         acos, atan, sinh, cosh, tanh, asinh, acosh, atanh, floor, round, ceil, trunc, fract, \
         exp, sqrt, cbrt, ln, log2, log10, log, atan2, min, max; constants: PI, E)"
    );
    let e = error_of(&edit("*x/sqrt(x^2+y^2)", "*x/sqrt(x^2+y^2"), &mesh);
    assert_eq!(
        e,
        "[[displacement]] 5 on 'InInner': dx = \"1e-2*x/sqrt(x^2+y^2\", character 12: '(' is \
         not closed"
    );
    // 1/y on the quarter's side y = 0: infinite at the node (10, 0)
    let e = error_of(&edit("*x/sqrt(x^2+y^2)", "/y"), &mesh);
    assert!(
        e.starts_with("[[displacement]] 5 on 'InInner': dx = \"1e-2/y\" is inf at node "),
        "{e}"
    );
    assert!(
        e.ends_with("(x = 10, y = 0): it must be finite there"),
        "{e}"
    );
    // the same with t: found at the first step end (t = 0.5)
    let e = error_of(&edit("t*(-1e-2)*x/25.0", "t*(-1e-2)/y"), &mesh);
    assert!(
        e.starts_with("[[displacement]] 6 on 'OutOuter': dx = \"t*(-1e-2)/y\" is -inf at node"),
        "{e}"
    );
    assert!(
        e.ends_with("(x = 25, y = 0) at t = 0.5: it must be finite there"),
        "{e}"
    );
    // an expression of t is the value at t: a function cannot scale it too
    let mut c = edit("t*(-1e-2)*x/25.0", "t*(-1e-2)*x/25.0");
    c.displacement[5].function = Some("f".into());
    c.function.push(tribo::case::schema::FunctionSpec {
        name: "f".into(),
        table: vec![[0.0, 0.0], [1.0, 1.0]],
    });
    let e = error_of(&c, &mesh);
    assert!(
        e.contains("is an expression of t, which gives the value at time t itself"),
        "{e}"
    );
    // a plain non-finite number is still refused before any work
    let mut c = rings_case("mortar");
    c.displacement[0].dy = Some(f64::NAN.into());
    let e = build_problem(&c, &mesh).err().unwrap().to_string();
    assert_eq!(
        e,
        "[[displacement]] 1 on 'InStart': dy must be a finite number, got NaN"
    );
}
