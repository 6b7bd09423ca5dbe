//! No units in defaults: the same case in N-mm-MPa and in N-m-Pa, with no contact
//! parameter given, gives the same answer (relative 1e-6), with and without friction: two
//! discs pressed together (plane strain, large kinematics, the lower one softer).

use std::path::Path;
use tribo::case;
use tribo::case::schema::CaseFile;

/// (pole stress of the upper disc / its E, approach of the discs' centres / R) in units
/// where lengths are `l` and stresses `s` (1, 1 for mm-MPa; 1e-3, 1e6 for m-Pa).
fn answer(formulation: &str, friction: f64, l: f64, s: f64) -> (f64, f64) {
    let extra = match formulation {
        "point-to-segment" => "integration = \"nodal\"\n",
        _ => "",
    };
    let fric = if friction > 0.0 {
        format!("friction = {friction}\n")
    } else {
        String::new()
    };
    let text = format!(
        r#"
[mesh]
generator = "disc_pair"
radius = {r}
size = {h}
stretch = 1.15
[model]
kinematics = "large"
thickness = {l}
[[material]]
group = "Upper"
E = {e1}
nu = 0.3
[[material]]
group = "Lower"
E = {e2}
nu = 0.3
[[displacement]]
group = "Bottom"
dy = 0.0
[[displacement]]
group = "Axe"
dx = 0.0
[[force]]
group = "Top"
fy = -{f}
[[contact]]
slave = "Upper_arc"
master = "Lower_arc"
formulation = "{formulation}"
initial = "closed"
initial_gap = {g}
{extra}{fric}[solver]
steps = 2
[[output.probe]]
name = "pole"
group = "Upper_tip"
field = "siyy"
stress_group = "Upper"
[[output.probe]]
name = "cu"
at = [0.0, {r}]
field = "dy"
[[output.probe]]
name = "cl"
at = [0.0, -{r}]
field = "dy"
"#,
        r = 50.0 * l,
        h = 1.0 * l,
        e1 = 210000.0 * s,
        e2 = 70000.0 * s,
        f = 17500.0 * s * l * l,
        g = 0.1 * l,
    );
    let c: CaseFile = toml::from_str(&text).unwrap();
    let mesh = case::build_mesh(&c.mesh, Path::new("")).unwrap();
    let out = case::run(&c, &mesh, false).unwrap_or_else(|e| panic!("{formulation}: {e}"));
    let p = |n: &str| out.probes.iter().find(|q| q.0 == n).unwrap().1;
    (p("pole") / (210000.0 * s), (p("cu") - p("cl")) / (50.0 * l))
}

#[test]
fn mm_mpa_and_m_pa_give_the_same_answer_with_the_defaults() {
    for (formulation, friction) in [
        ("mortar", 0.0),
        ("mortar", 0.2),
        ("point-to-segment", 0.0),
        ("point-to-segment", 0.2),
        ("node-to-segment", 0.0),
        ("node-to-segment", 0.2),
    ] {
        {
            let mm = answer(formulation, friction, 1.0, 1.0);
            let si = answer(formulation, friction, 1e-3, 1e6);
            let d = ((mm.0 / si.0 - 1.0).abs()).max((mm.1 / si.1 - 1.0).abs());
            println!("{formulation} mu {friction}: {mm:?} vs {si:?}: {d:.1e}");
            assert!(d < 1e-6, "{formulation} mu {friction}: {mm:?} vs {si:?}");
        }
    }
}
