//! Rigid surfaces (`[[rigid]]`) against exact answers: a block pressed by a rigid flat
//! (uniform pressure E'δ/h, every formulation), a punch with rounded edges driven by a
//! force on its reference point (the reaction there balances the force), a block sheared
//! to sliding on a rigid line (tangential / normal = μ); and the bad inputs.

mod common;

use common::case_head;
use tribo::case::{run, schema::CaseFile};
use tribo::mesh::generate::rectangle;
use tribo::mesh::{CellKind, Mesh, MeshBuilder};

const E: f64 = 1000.0;
const NU: f64 = 0.3;
const FORMULATIONS: [&str; 3] = ["mortar", "point-to-segment", "node-to-segment"];

/// The block [0, 1] × [0, h] (groups `Body`, `Top`, `Bottom`, `Left`, `Right`).
fn block(nx: usize, ny: usize, h: f64, kind: CellKind) -> Mesh {
    rectangle([0.0, 0.0], 1.0, h, nx, ny, kind, 0.0).unwrap()
}

fn case(text: &str) -> CaseFile {
    toml::from_str(&format!("{}{text}", case_head(&[("Body", E, NU)]))).unwrap()
}

fn sum_y(mesh: &Mesh, group: &str, r: &[f64]) -> f64 {
    mesh.node_group(group)
        .unwrap()
        .iter()
        .map(|&n| r[2 * n + 1])
        .sum()
}

/// Plane strain, the block's sides free: σ_yy = −p uniform, ε_yy = −p (1 − ν²) / E, so a
/// rigid flat moved down by δ on a block of height h presses p = E'δ/h, E' = E/(1 − ν²).
#[test]
fn rigid_flat_presses_a_uniform_pressure_in_every_formulation() {
    let (h, delta) = (0.5, 1e-3);
    let p = E / (1.0 - NU * NU) * delta / h;
    for kind in [CellKind::Quad4, CellKind::Tri3, CellKind::Quad8] {
        let mesh = block(5, 3, h, kind);
        for f in FORMULATIONS {
            let c = case(&format!(
                r#"
[[displacement]]
group = "Bottom"
dy = 0.0
[[displacement]]
group = "Left"
dx = 0.0
[[rigid]]
name = "flat"
line = {{ point = [0.0, {h}], normal = [0.0, -1.0] }}
reference = [0.5, 1.0]
dy = {d}
[[contact]]
slave = "Top"
master = "flat"
formulation = "{f}"
"#,
                d = -delta
            ));
            let out = run(&c, &mesh, false).unwrap_or_else(|e| panic!("{kind} {f}: {e}"));
            let worst = out.contact_pressure[0]
                .iter()
                .map(|&(_, q)| ((q - p) / p).abs())
                .fold(0.0, f64::max);
            let r = &out.rigid[0];
            println!(
                "{kind} {f}: max |p - E'd/h| / p = {worst:.1e}, reaction {:?}, motion {:?}",
                r.reaction, r.motion
            );
            assert!(worst < 1e-8, "{kind} {f}: pressure off by {worst}");
            // the driver pushes down with p·w, the base pushes up as much
            assert!((r.reaction[1] + p).abs() < 1e-8 * p, "{kind} {f}: {:?}", r);
            assert!((sum_y(&mesh, "Bottom", &out.reactions) - p).abs() < 1e-8 * p);
            assert!((r.motion[1] + delta).abs() < 1e-15 && r.motion[0] == 0.0);
        }
    }
}

/// The block of `block` with a punch above it: an edge chain of no 2D cell (group `Punch`),
/// flat over x ∈ [0.3, 0.7] at y = h (touching the block) with rounded edges of radius 0.1.
fn block_and_punch(h: f64) -> Mesh {
    let body = block(10, 5, h, CellKind::Quad4);
    let mut b = MeshBuilder::new("punch");
    b.append(&body, |g| g.to_string());
    let r = 0.1;
    let mut points = vec![];
    let arc = |c: [f64; 2], a0: f64, a1: f64, n: usize, out: &mut Vec<[f64; 2]>| {
        for k in 0..n {
            let a = (a0 + (a1 - a0) * k as f64 / n as f64).to_radians();
            out.push([c[0] + r * a.cos(), c[1] + r * a.sin()]);
        }
    };
    arc([0.3, h + r], 180.0, 270.0, 8, &mut points);
    for k in 0..8 {
        points.push([0.3 + 0.05 * k as f64, h]);
    }
    arc([0.7, h + r], 270.0, 360.0, 8, &mut points);
    points.push([0.8, h + r]);
    let first = b.num_nodes();
    for &p in &points {
        b.add_node(p);
    }
    for k in 0..points.len() - 1 {
        let c = b.add_cell(CellKind::Seg2, &[first + k, first + k + 1], 0);
        b.add_to_cell_group("Punch", c);
    }
    b.finish().unwrap()
}

/// Force control: the punch's reference point carries fy = −F and a zero moment (its
/// rotation an unknown), its x held. At equilibrium the contact forces on the punch,
/// condensed on the reference point (its reaction), balance the applied force and moment,
/// and the block carries F to its base.
#[test]
fn punch_driven_by_a_force_balances_it_at_its_reference_point() {
    let (h, f) = (0.5, 1.5);
    let mesh = block_and_punch(h);
    for form in FORMULATIONS {
        let c = case(&format!(
            r#"
[solver]
tolerance = 1e-12
[[displacement]]
group = "Bottom"
dy = 0.0
[[displacement]]
group = "Left"
dx = 0.0
[[rigid]]
group = "Punch"
reference = [0.5, 0.8]
dx = 0.0
fy = {fy}
moment = 0.0
[[contact]]
slave = "Top"
master = "Punch"
formulation = "{form}"
"#,
            fy = -f
        ));
        let out = run(&c, &mesh, false).unwrap_or_else(|e| panic!("{form}: {e}"));
        let r = &out.rigid[0];
        let s = &out.contact[0].summary;
        let base = sum_y(&mesh, "Bottom", &out.reactions);
        println!(
            "{form}: reaction {:?}, motion {:?}, slave force {:?}, base {base}, contact length {}",
            r.reaction, r.motion, s.force, s.contact_length
        );
        assert!((r.reaction[1] + f).abs() < 1e-8 * f, "{form}: {:?}", r);
        assert!(r.reaction[2].abs() < 1e-8 * f, "{form}: {:?}", r);
        assert!((s.force[1] + f).abs() < 1e-8 * f, "{form}: {:?}", s.force);
        assert!((base - f).abs() < 1e-8 * f, "{form}: base {base}");
        assert!(r.motion[1] < 0.0 && r.motion[0] == 0.0);
    }
}

/// A block pressed on a rigid line (held) by a pressure, then its top moved sideways far
/// enough that every contact node slips: the contact forces are then μ times the normal
/// ones, on the line (its reaction) as on the block (the pair's resultants).
#[test]
fn block_sheared_to_sliding_on_a_rigid_line_has_tangential_over_normal_mu() {
    let mesh = block(5, 3, 0.5, CellKind::Quad4);
    for form in FORMULATIONS {
        let integration = if form == "point-to-segment" {
            "integration = \"nodal\"\n"
        } else {
            ""
        };
        let c = case(&format!(
            r#"
[[function]]
name = "press"
table = [[0.0, 0.0], [1.0, 1.0], [2.0, 1.0]]
[[function]]
name = "shear"
table = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]
[solver]
steps = 8
[[pressure]]
group = "Top"
p = 10.0
function = "press"
[[displacement]]
group = "Top"
dx = 0.05
function = "shear"
[[rigid]]
name = "base"
line = {{ point = [0.0, 0.0], normal = [0.0, 1.0] }}
reference = [0.0, -1.0]
[[contact]]
slave = "Bottom"
master = "base"
formulation = "{form}"
friction = 0.3
initial = "all"
{integration}"#
        ));
        let out = run(&c, &mesh, false).unwrap_or_else(|e| panic!("{form}: {e}"));
        let r = &out.rigid[0];
        let s = &out.contact[0].summary;
        let on_line = (r.reaction[0] / r.reaction[1]).abs();
        let on_block = s.tangential_resultant / s.normal_resultant;
        println!(
            "{form}: reaction {:?}, on the line {on_line:.12}, on the block {on_block:.12}, \
             stick {} slip {}",
            r.reaction, s.stick, s.slip
        );
        assert!(s.stick == 0 && s.slip > 0, "{form}: not sliding");
        assert!((on_line - 0.3).abs() < 1e-6, "{form}: {on_line}");
        assert!((on_block - 0.3).abs() < 1e-6, "{form}: {on_block}");
        // the line carries the pressure: 10 over the width 1
        assert!(
            (r.reaction[1] - 10.0).abs() < 1e-8 * 10.0,
            "{form}: {:?}",
            r
        );
    }
}

/// The error of a case on the block-and-punch mesh (the case must fail).
fn error_of(text: &str) -> String {
    let mesh = block_and_punch(0.5);
    let c = case(text);
    match run(&c, &mesh, false) {
        Ok(_) => panic!("the case ran:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const HELD: &str = r#"
[[displacement]]
group = "Bottom"
dx = 0.0
dy = 0.0
"#;

#[test]
fn bad_rigid_input_is_refused_naming_the_entry() {
    let contact = "[[contact]]\nslave = \"Top\"\nmaster = \"Punch\"\n";
    // the edge group without a [[rigid]] entry
    let e = error_of(&format!("{HELD}{contact}"));
    assert!(
        e.contains("edge cell") && e.contains("[[rigid]] entry with its reference point"),
        "{e}"
    );
    // no reference point
    let e = error_of(&format!("{HELD}[[rigid]]\ngroup = \"Punch\"\n{contact}"));
    assert!(
        e.contains("[[rigid]] 'Punch' has no reference point"),
        "{e}"
    );
    // a force and an imposed displacement on the same dof
    let e = error_of(&format!(
        "{HELD}[[rigid]]\ngroup = \"Punch\"\nreference = [0.5, 1.0]\ndy = -0.001\nfy = -1.0\n{contact}"
    ));
    assert!(e.contains("[[rigid]] 'Punch': dy and fy both given"), "{e}");
    let e = error_of(&format!(
        "{HELD}[[rigid]]\ngroup = \"Punch\"\nreference = [0.5, 1.0]\nrotation = 0.0\nmoment = 1.0\n{contact}"
    ));
    assert!(
        e.contains("[[rigid]] 'Punch': rotation and moment both given"),
        "{e}"
    );
    // a rigid surface as slave
    let e = error_of(&format!(
        "{HELD}[[rigid]]\ngroup = \"Punch\"\nreference = [0.5, 1.0]\n{contact}\
         [[contact]]\nslave = \"Punch\"\nmaster = \"Right\"\n"
    ));
    assert!(
        e.contains("[[contact]] 2 (Punch on Right): the slave 'Punch' is the rigid surface [[rigid]] 'Punch'"),
        "{e}"
    );
    // a rigid surface that is the master of no pair
    let e = error_of(&format!(
        "{HELD}[[rigid]]\nname = \"floor\"\nline = {{ point = [0.0, 0.0], normal = [0.0, 1.0] }}\n\
         reference = [0.0, 0.0]\n[[rigid]]\ngroup = \"Punch\"\nreference = [0.5, 1.0]\n{contact}"
    ));
    assert!(
        e.contains("[[rigid]] 'floor' is the master of no [[contact]]"),
        "{e}"
    );
    // a group that bounds a body
    let e = error_of(&format!(
        "{HELD}[[rigid]]\ngroup = \"Top\"\nreference = [0.5, 1.0]\n\
         [[contact]]\nslave = \"Bottom\"\nmaster = \"Top\"\n"
    ));
    assert!(
        e.contains("[[rigid]] 'Top': edge cell") && e.contains("is a side of the 2D cell"),
        "{e}"
    );
    // a line with neither geometry nor group
    let e = error_of(&format!(
        "{HELD}[[rigid]]\nname = \"x\"\nreference = [0.5, 1.0]\n{contact}"
    ));
    assert!(
        e.contains("[[rigid]] 'x': give exactly one of group"),
        "{e}"
    );
    // another entry moving a node of the rigid surface
    let e = error_of(&format!(
        "{HELD}[[displacement]]\ngroup = \"Punch\"\ndy = 0.0\n[[rigid]]\ngroup = \"Punch\"\n\
         reference = [0.5, 1.0]\n{contact}"
    ));
    assert!(
        e.contains("[[displacement]] on 'Punch': node")
            && e.contains("belongs to the rigid surface"),
        "{e}"
    );
    // a moment (free rotation) with large kinematics
    let e = error_of(
        &format!(
            "[model]\nkinematics = \"large\"\n{HELD}[[rigid]]\ngroup = \"Punch\"\nreference = [0.5, 1.0]\nmoment = 0.0\n{contact}"
        )
        ,
    );
    assert!(
        e.contains("[[rigid]] 'Punch': moment makes the rotation an unknown"),
        "{e}"
    );
}

/// An imposed rotation moves the surface rigidly (exact rotation): a punch turned by 0.3
/// rad about its reference point, away from the block (nothing touches), keeps every
/// distance between its nodes; its reaction is zero.
#[test]
fn imposed_rotation_is_an_exact_rigid_motion() {
    let mesh = block_and_punch(0.5);
    let c = case(
        r#"
[[displacement]]
group = "Bottom"
dx = 0.0
dy = 0.0
[[rigid]]
group = "Punch"
reference = [0.5, 0.8]
dy = "0.5*t"
rotation = 0.3
[[contact]]
slave = "Top"
master = "Punch"
formulation = "mortar"
"#,
    );
    let out = run(&c, &mesh, false).unwrap();
    let r = &out.rigid[0];
    assert_eq!(r.motion, [0.0, 0.5, 0.3]);
    assert!(r.reaction.iter().all(|v| v.abs() < 1e-12), "{:?}", r);
    let nodes = mesh.node_group("Punch").unwrap();
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    for &n in &nodes {
        let x = mesh.coords[n];
        let d = [x[0] - 0.5, x[1] - 0.8];
        let expect = [0.5 + c * d[0] - s * d[1], 0.8 + 0.5 + s * d[0] + c * d[1]];
        let got = [x[0] + out.u[2 * n], x[1] + out.u[2 * n + 1]];
        assert!(
            (got[0] - expect[0]).abs() < 1e-14 && (got[1] - expect[1]).abs() < 1e-14,
            "node {n}: {got:?} vs {expect:?}"
        );
    }
}
