//! Two concentric rings in contact under an external pressure q, plane strain, small
//! kinematics, both of one material: together they are one thick ring a..c, so the contact
//! pressure at r = b is Lamé's −σ_rr(b) = q c²/(c² − a²) (1 − a²/b²). The interface is
//! discretised differently on the two sides (linear cells on one ring, quadratic on the
//! other, different cell counts): the chords of the linear side lie inside the arcs of
//! the quadratic one.

mod common;

use common::{bodies, case_head};
use tribo::case::{run, schema::CaseFile};
use tribo::mesh::generate::ring;
use tribo::mesh::CellKind;

const E: f64 = 200_000.0;
const NU: f64 = 0.3;
const A: f64 = 10.0;
const B: f64 = 15.0;
const C: f64 = 25.0;
const Q: f64 = 100.0;

fn lame_pressure() -> f64 {
    Q * C * C / (C * C - A * A) * (1.0 - A * A / (B * B))
}

/// Worst relative error of the contact pressure over the slave nodes.
fn rings(
    inner: CellKind,
    outer: CellKind,
    slave_inner: bool,
    formulation: &str,
    extra: &str,
) -> f64 {
    let inner_ring = ring(A, B, 6, 24, 90.0, inner).unwrap();
    let outer_ring = ring(B, C, 8, 31, 90.0, outer).unwrap();
    let mesh = bodies(&[("In", &inner_ring), ("Out", &outer_ring)]);
    let head = case_head(&[("InBody", E, NU), ("OutBody", E, NU)]);
    let (slave, master) = if slave_inner {
        ("InOuter", "OutInner")
    } else {
        ("OutInner", "InOuter")
    };
    let text = format!(
        r#"{head}
[model]
modelisation = "plane_strain"
kinematics = "small"
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
[[pressure]]
group = "OutOuter"
p = {Q}
[[contact]]
slave = "{slave}"
master = "{master}"
formulation = "{formulation}"
initial = "all"
{extra}
"#
    );
    let case: CaseFile = toml::from_str(&text).unwrap();
    let out = run(&case, &mesh, false).unwrap();
    let p = lame_pressure();
    let mut worst: f64 = 0.0;
    for &(_, pc) in &out.contact_pressure[0] {
        worst = worst.max((pc / p - 1.0).abs());
    }
    worst
}

const ADJUST: &str = "adjust = 0.05";

#[test]
fn linear_slave_on_quadratic_master_gives_lame_with_adjust() {
    // the linear ring's chords lie inside the quadratic ring's arcs by h²/8r = 0.008, as
    // much as the radial displacement: without adjust the pressure is 25 % off
    for (inner, outer) in [
        (CellKind::Quad4, CellKind::Quad8),
        (CellKind::Quad8, CellKind::Quad4),
    ] {
        for slave_inner in [true, false] {
            let w = rings(inner, outer, slave_inner, "mortar", ADJUST);
            println!(
                "inner {inner}, outer {outer}, slave inner {slave_inner}: worst {:.3} %",
                100.0 * w
            );
            assert!(
                w < 5e-3,
                "inner {inner}, outer {outer}, slave inner {slave_inner}: {:.3} %",
                100.0 * w
            );
        }
    }
}

#[test]
fn non_matching_linear_rings_give_lame_with_adjust() {
    // two polygons of 24 and 31 sides cross each other: without adjust 52 % off
    for slave_inner in [true, false] {
        let w = rings(
            CellKind::Quad4,
            CellKind::Quad4,
            slave_inner,
            "mortar",
            ADJUST,
        );
        println!(
            "linear rings, slave inner {slave_inner}: worst {:.3} %",
            100.0 * w
        );
        assert!(w < 5e-3, "{:.3} %", 100.0 * w);
    }
}

#[test]
fn quadratic_rings_give_lame_without_adjust() {
    for slave_inner in [true, false] {
        let w = rings(CellKind::Quad8, CellKind::Quad8, slave_inner, "mortar", "");
        println!(
            "quadratic rings, slave inner {slave_inner}: worst {:.3} %",
            100.0 * w
        );
        assert!(w < 5e-3, "{:.3} %", 100.0 * w);
    }
}

#[test]
fn adjust_is_refused_where_it_does_nothing() {
    let inner_ring = ring(A, B, 2, 4, 90.0, CellKind::Quad4).unwrap();
    let outer_ring = ring(B, C, 2, 4, 90.0, CellKind::Quad4).unwrap();
    let mesh = bodies(&[("In", &inner_ring), ("Out", &outer_ring)]);
    let head = case_head(&[("InBody", E, NU), ("OutBody", E, NU)]);
    for (formulation, adjust) in [
        ("point-to-segment", "0.05"),
        ("mortar", "-1.0"),
        ("mortar", "nan"),
    ] {
        let text = format!(
            "{head}\n[[contact]]\nslave = \"InOuter\"\nmaster = \"OutInner\"\nformulation = \"{formulation}\"\nadjust = {adjust}\n"
        );
        let case: CaseFile = toml::from_str(&text).unwrap();
        let e = run(&case, &mesh, false).err().expect("refused").to_string();
        assert!(e.contains("adjust"), "{e}");
    }
}
