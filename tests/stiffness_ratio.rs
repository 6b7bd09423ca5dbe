//! Two bodies whose stiffnesses differ by 1e4 (a steel disc on a rubber-like one, or Pa
//! mixed with MPa by mistake): every formulation converges with its default parameters,
//! whichever body carries the multipliers, and the contact carries the load (the base
//! reaction equals the applied force to 1e-6). The load makes a contact about 5 cells
//! wide and strains of about 6 % in the soft disc.

use std::path::Path;
use tribo::case;
use tribo::case::schema::CaseFile;

fn run(formulation: &str, slave: &str, master: &str, kinematics: &str) -> (usize, f64) {
    let text = format!(
        r#"
[mesh]
generator = "disc_pair"
radius = 50.0
size = 1.0
stretch = 1.15
[model]
kinematics = "{kinematics}"
[[material]]
group = "Upper"
E = 210000.0
nu = 0.3
[[material]]
group = "Lower"
E = 21.0
nu = 0.3
[[displacement]]
group = "Bottom"
dy = 0.0
[[displacement]]
group = "Axe"
dx = 0.0
[[force]]
group = "Top"
fy = -5.0
[[contact]]
slave = "{slave}"
master = "{master}"
formulation = "{formulation}"
initial = "closed"
initial_gap = 0.1
[output]
vtu = false
"#
    );
    let c: CaseFile = toml::from_str(&text).unwrap();
    let mesh = case::build_mesh(&c.mesh, Path::new("")).unwrap();
    let out = case::run(&c, &mesh, false)
        .unwrap_or_else(|e| panic!("{formulation} {slave} {kinematics}: {e}"));
    let base = mesh.node_group("Bottom").unwrap();
    let ry: f64 = base.iter().map(|&n| out.reactions[2 * n + 1]).sum();
    let top = mesh.node_group("Top").unwrap().len() as f64;
    (out.report.total_iterations, ry / (5.0 * top))
}

#[test]
fn a_stiffness_ratio_of_1e4_converges_with_every_formulation() {
    for formulation in ["mortar", "point-to-segment", "node-to-segment"] {
        for (slave, master) in [("Upper_arc", "Lower_arc"), ("Lower_arc", "Upper_arc")] {
            for kinematics in ["small", "large"] {
                let (iterations, balance) = run(formulation, slave, master, kinematics);
                println!(
                    "{formulation:>16} slave {slave:<9} {kinematics}: {iterations} iterations, \
                     base reaction / force {balance:.9}"
                );
                assert!((balance - 1.0).abs() < 1e-6, "reaction / force {balance}");
            }
        }
    }
}
