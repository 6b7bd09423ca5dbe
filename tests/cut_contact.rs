//! Contact between two edge groups of one connected mesh: a block cut along y = 0 into two
//! halves that share the end node of the cut (x = W), pressed across the cut by a uniform
//! pressure on top, the bottom held. The exact state is uniform (σ_yy = −P, continuous
//! across the cut, the shared node included), so the contact pressure is P on every lip
//! node; the shared node is left out of contact by itself.

mod common;

use common::{bodies_joined_at, case_head};
use tribo::case::{run, schema::CaseFile};
use tribo::mesh::generate::rectangle;
use tribo::mesh::topology::node_bodies;
use tribo::mesh::CellKind;

const P: f64 = 25.0;
const W: f64 = 2.0;
const E: f64 = 1000.0;
const NU: f64 = 0.3;

fn case_text(formulation: &str, extra: &str) -> String {
    let head = case_head(&[("LowerBody", E, NU), ("UpperBody", E, NU)]);
    format!(
        r#"{head}
[[displacement]]
group = "LowerBottom"
dy = 0.0
[[displacement]]
group = "LowerLeft"
dx = 0.0
[[displacement]]
group = "UpperLeft"
dx = 0.0
[[pressure]]
group = "UpperTop"
p = {P}
[[contact]]
slave = "UpperBottom"
master = "LowerTop"
formulation = "{formulation}"
{extra}
"#
    )
}

struct Outcome {
    /// (x, p) of the reported lip nodes, along the cut
    pressures: Vec<(f64, f64)>,
    /// largest |u − u_exact| over the nodes, relative to the largest |u_exact|
    u_error: f64,
    /// the shared node's reported pressure, if any
    shared: Option<f64>,
}

/// The cut block: lower half nx_l cells wide, upper half nx_u (equal: the lips of one
/// cut mesh match), joined at (W, 0); the upper lip named slave, the lower one if `swap`.
fn solve(
    kind: CellKind,
    (nx_l, nx_u, swap): (usize, usize, bool),
    formulation: &str,
    extra: &str,
) -> Outcome {
    let lower = rectangle([0.0, -1.0], W, 1.0, nx_l, 2, kind, 0.0).unwrap();
    let upper = rectangle([0.0, 0.0], W, 1.0, nx_u, 2, kind, 0.0).unwrap();
    let mesh = bodies_joined_at(&[("Lower", &lower), ("Upper", &upper)], [W, 0.0]);
    // one connected mesh
    let b = node_bodies(&mesh);
    assert!(b.iter().all(|&x| x == b[0]), "one body");
    let mut text = case_text(formulation, extra);
    if swap {
        // the finer lip as slave
        text = text
            .replace("slave = \"UpperBottom\"", "slave = \"X\"")
            .replace("master = \"LowerTop\"", "master = \"UpperBottom\"")
            .replace("slave = \"X\"", "slave = \"LowerTop\"");
    }
    let case: CaseFile = toml::from_str(&text).unwrap();
    let out = run(&case, &mesh, false).unwrap();
    let joint = (0..mesh.num_nodes())
        .find(|&n| mesh.coords[n] == [W, 0.0])
        .unwrap();
    // exact plane strain uniform state: ε_yy = −P(1−ν²)/E, ε_xx = P ν(1+ν)/E, u = 0 at
    // x = 0 and at y = −1
    let eyy = -P * (1.0 - NU * NU) / E;
    let exx = P * NU * (1.0 + NU) / E;
    let (mut err, mut scale) = (0.0f64, 0.0f64);
    for (n, x) in mesh.coords.iter().enumerate() {
        let ex = [exx * x[0], eyy * (x[1] + 1.0)];
        err = err
            .max((out.u[2 * n] - ex[0]).abs())
            .max((out.u[2 * n + 1] - ex[1]).abs());
        scale = scale.max(ex[0].abs()).max(ex[1].abs());
    }
    let mut pressures: Vec<(f64, f64)> = out.contact_pressure[0]
        .iter()
        .filter(|&&(n, _)| n != joint)
        .map(|&(n, p)| (mesh.coords[n][0], p))
        .collect();
    pressures.sort_by(|a, b| a.0.total_cmp(&b.0));
    let shared = out.contact_pressure[0]
        .iter()
        .find(|&&(n, _)| n == joint)
        .map(|&(_, p)| p);
    println!(
        "{kind} {nx_l}/{nx_u} swap {swap} {formulation} {extra}: u error {:.2e}, shared {shared:?}, p {pressures:?}",
        err / scale
    );
    Outcome {
        pressures,
        u_error: err / scale,
        shared,
    }
}

fn worst(p: &[(f64, f64)]) -> f64 {
    p.iter()
        .map(|&(_, p)| ((p - P) / P).abs())
        .fold(0.0, f64::max)
}

/// Mortar (the default): uniform pressure to 1e-8 on every lip node but the shared one,
/// which carries no multiplier (and reports no pressure of its own, or 0), and the exact
/// uniform displacement field.
#[test]
fn mortar_passes_the_patch_test_across_a_cut() {
    for kind in [
        CellKind::Quad4,
        CellKind::Quad8,
        CellKind::Tri3,
        CellKind::Tri6,
    ] {
        // matching lips (a mesh cut along a line), and lips that do not match, either one
        // named slave (the multipliers go on the lip finer at the shared node by themselves)
        // (the default start: the touching nodes; every node; with friction)
        let starts = ["", "initial = \"all\"", "friction = 0.3"];
        for (mesh, extra) in [
            (4, 4, false),
            (4, 5, false),
            (5, 4, false),
            (5, 4, true),
            (4, 5, true),
        ]
        .into_iter()
        .flat_map(|m| starts.map(|e| (m, e)))
        {
            let o = solve(kind, mesh, "mortar", extra);
            let what = format!("{kind} {mesh:?} {extra}");
            assert!(o.pressures.len() >= 4, "{what}: {:?}", o.pressures);
            assert!(worst(&o.pressures) < 1e-8, "{what}: {:?}", o.pressures);
            assert!(o.u_error < 1e-8, "{what}: u error {}", o.u_error);
            assert!(o.shared.is_none_or(|p| p == 0.0), "{what}: {:?}", o.shared);
        }
    }
}

/// Point-to-segment (Gauss and nodal integration) and node-to-segment: the exact uniform
/// displacement field to 1e-8 (the lips transmit exactly the uniform traction, in the
/// weak sense of each formulation), and the nodal pressures uniform to 1e-8 where the
/// multipliers are nodal (nodal integration, node-to-segment). With Gauss integration the
/// interpolated multiplier, held at zero on the shared node, oscillates about P near it
/// (the weak resultant is still exact: so is u).
#[test]
fn point_and_node_to_segment_are_exact_across_a_cut() {
    for kind in [
        CellKind::Quad4,
        CellKind::Quad8,
        CellKind::Tri3,
        CellKind::Tri6,
    ] {
        for (f, i) in [
            ("point-to-segment", "gauss"),
            ("point-to-segment", "nodal"),
            ("node-to-segment", "nodal"),
        ] {
            let o = solve(
                kind,
                (4, 4, false),
                f,
                &format!("integration = \"{i}\"\ninitial = \"all\""),
            );
            assert!(o.u_error < 1e-8, "{kind} {f} {i}: u error {}", o.u_error);
            assert!(o.pressures.len() >= 4, "{kind} {f} {i}: {:?}", o.pressures);
            if i == "nodal" {
                assert!(worst(&o.pressures) < 1e-8, "{kind} {f}: {:?}", o.pressures);
            }
            assert!(o.shared.is_none_or(|p| p == 0.0), "{kind}: {:?}", o.shared);
        }
    }
}

/// True self-contact (one surface folding onto itself) is not supported: one surface
/// under two names is refused, as are a body's top and bottom (see case_errors).
#[test]
fn one_surface_under_two_names_is_refused() {
    let lower = rectangle([0.0, -1.0], W, 1.0, 4, 2, CellKind::Quad4, 0.0).unwrap();
    let upper = rectangle([0.0, 0.0], W, 1.0, 4, 2, CellKind::Quad4, 0.0).unwrap();
    let mut mesh = bodies_joined_at(&[("Lower", &lower), ("Upper", &upper)], [W, 0.0]);
    let top = mesh.cell_groups["UpperBottom"].clone();
    mesh.cell_groups.insert("Lip".into(), top);
    let text = case_text("mortar", "").replace("master = \"LowerTop\"", "master = \"Lip\"");
    let case: CaseFile = toml::from_str(&text).unwrap();
    let e = run(&case, &mesh, false).err().expect("refused").to_string();
    assert_eq!(
        e,
        "[[contact]] 1 (UpperBottom on Lip): every node of 'UpperBottom' is also a node of \
         'Lip': the surfaces must be distinct (self-contact of one surface folding onto \
         itself is not supported)"
    );
}
