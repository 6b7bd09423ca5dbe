//! Per-pair contact outputs against exact answers (issue 21, item 6): on SSNP154 the normal
//! resultant carries the applied 17 500 N and the contact length of the half model lies
//! within one cell of the Hertz half-width, in every formulation; a block sheared to
//! sliding with μ = 0.3 gives T/N = μ in every formulation; result.vtu and pressure.csv
//! give open nodes exactly 0 and nodes off the slave surface NaN.

mod common;

use common::{block_contact, block_on_foundation};
use std::path::Path;
use std::process::Command;
use tribo::case::{self, ssnp154};
use tribo::post::contact_state::OPEN;

/// The slave cell (Bottom_C) whose x range holds the Hertz half-width: its length.
fn cell_at_half_width(mesh: &tribo::mesh::Mesh) -> f64 {
    let a = ssnp154::HERTZ_A;
    mesh.cell_group("Bottom_C")
        .unwrap()
        .iter()
        .find_map(|&c| {
            let n = mesh.cell_nodes(c);
            let (p, q) = (mesh.coords[n[0]], mesh.coords[n[1]]);
            let (lo, hi) = (p[0].min(q[0]), p[0].max(q[0]));
            (lo <= a && a <= hi).then(|| (q[0] - p[0]).hypot(q[1] - p[1]))
        })
        .unwrap()
}

/// SSNP154 A (point-to-segment), the same with mortar, and E-free (node-to-segment), all
/// frictionless: the normal resultant's y component equals the applied force (1e-8), its
/// tangential resultant is 0, and the contact length is within one cell of a.
#[test]
fn ssnp154_resultant_carries_the_load_and_the_length_is_hertz() {
    for (id, formulation) in [
        ("A", Some("point-to-segment")),
        ("A", Some("mortar")),
        // (E itself ties B to C besides the contact: E-free is its contact alone)
        ("E-free", None),
    ] {
        let spec = ssnp154::builtin_mesh(false, 1.5);
        let mesh = case::build_mesh(&spec, Path::new("")).unwrap();
        let c = ssnp154::contact_case(id, spec, formulation);
        let out = case::run(&c, &mesh, false).unwrap();
        let s = &out.contact[0].summary;
        let h = cell_at_half_width(&mesh);
        println!(
            "{id} {}: normal force {:?} (|N| {}), T {:?}, length {} (a = {}, cell {h}), \
             centre {:?} (4a/3π = {}), peak {} at {:?}, stick {} slip {} open {}",
            c.contact[0].formulation,
            s.normal_force,
            s.normal_resultant,
            s.tangential_force,
            s.contact_length,
            ssnp154::HERTZ_A,
            s.centre_of_pressure,
            4.0 * ssnp154::HERTZ_A / (3.0 * std::f64::consts::PI),
            s.peak_pressure,
            s.peak_at,
            s.stick,
            s.slip,
            s.open
        );
        // (mortar puts the multipliers on the finer block top: the force on the block)
        let fy = s.normal_force[1].abs();
        assert!((fy / 17500.0 - 1.0).abs() < 1e-8, "{id}: N_y = {fy}");
        assert_eq!(s.tangential_resultant, 0.0, "frictionless");
        assert!(
            (s.contact_length - ssnp154::HERTZ_A).abs() < h,
            "{id}: length {} against a = {} (cell {h})",
            s.contact_length,
            ssnp154::HERTZ_A
        );
        assert_eq!(s.slip, 0);
        assert!(s.stick > 0 && s.open > 0);
        // open nodes report exactly 0, in the summary's nodes and the pressure lists
        for n in &out.contact[0].nodes {
            if n.status == OPEN {
                assert_eq!((n.pressure, n.shear), (0.0, 0.0), "node {}", n.node + 1);
            } else {
                assert!(n.pressure > 0.0);
            }
        }
        let open: Vec<usize> = out.contact[0]
            .nodes
            .iter()
            .filter(|n| n.status == OPEN)
            .map(|n| n.node)
            .collect();
        for &(n, p) in &out.contact_pressure[0] {
            if open.contains(&n) {
                assert_eq!(p, 0.0);
            }
        }
    }
}

/// Every output step's contact outputs are those of its own converged state: the pair's
/// vertical resultant balances the support's reaction at each of 4 steps (1e-6 of the
/// force), frictionless and with friction. (They were once taken after the solve, with the
/// last step's statuses and friction history: at t = 1/4 mortar reported 12 times the load.)
#[test]
fn every_output_step_has_the_contact_forces_of_its_own_state() {
    for (id, formulation) in [
        ("A", Some("point-to-segment")),
        ("A", Some("mortar")),
        ("C", Some("point-to-segment")),
        ("C", Some("mortar")),
    ] {
        let spec = ssnp154::builtin_mesh(false, 1.5);
        let mesh = case::build_mesh(&spec, Path::new("")).unwrap();
        let mut c = ssnp154::contact_case(id, spec, formulation);
        c.solver.steps = 4;
        c.output.history = true;
        let out = case::run(&c, &mesh, false).unwrap();
        assert_eq!(out.steps.len(), 4, "{id} {formulation:?}");
        let base = mesh.node_group("Encast").unwrap();
        for s in &out.steps {
            let support: f64 = base.iter().map(|&n| s.reactions[2 * n + 1]).sum();
            let f = s.contact[0].summary.force;
            println!(
                "{id} {formulation:?} t = {}: contact force {f:?}, support {support}",
                s.time
            );
            // (mortar puts the multipliers on the finer block top: the force on the block)
            assert!(
                (f[1].abs() - support).abs() < 1e-6 * 17500.0 * s.time,
                "{id} {formulation:?} t = {}: contact force {f:?}, support {support}",
                s.time
            );
        }
    }
}

/// The block pressed on the foundation (small kinematics: flat normals), then dragged
/// sideways until every contact node slips: per pair T/N = μ = 0.3 (1e-6), and N, T equal
/// the reactions of the block's top (1e-8), in every formulation.
#[test]
fn sliding_block_resultants_obey_coulomb_in_every_formulation() {
    for formulation in ["mortar", "point-to-segment", "node-to-segment"] {
        let (mesh, head) = block_on_foundation(3.0, 15);
        let contact = block_contact(formulation);
        let text = format!(
            r#"{head}
[[function]]
name = "press"
table = [[0, 0], [1, 1]]
[[function]]
name = "drag"
table = [[0, 0], [1, 0], [3, 1]]
[[displacement]]
group = "LowerBottom"
dx = 0.0
dy = 0.0
[[displacement]]
group = "UpperTop"
dx = 0.05
function = "drag"
[[displacement]]
group = "UpperTop"
dy = -0.005
function = "press"
{contact}
[solver]
steps = 3
tolerance = 1e-10
"#
        );
        let c: case::schema::CaseFile = toml::from_str(&text).unwrap();
        let out = case::run(&c, &mesh, false).unwrap();
        let last = out.steps.last().unwrap();
        let s = &last.contact[0].summary;
        let (rx, ry) = common::group_sum(&mesh, "UpperTop", &last.reactions);
        let ratio = s.tangential_resultant / s.normal_resultant;
        println!(
            "{formulation}: N {:?}, T {:?}, T/N = {ratio}, top reactions ({rx}, {ry}), \
             stick {} slip {} open {}",
            s.normal_force, s.tangential_force, s.stick, s.slip, s.open
        );
        assert_eq!(s.stick, 0, "{formulation}: every node slips");
        assert!(s.slip > 0);
        assert!(
            (ratio / 0.3 - 1.0).abs() < 1e-6,
            "{formulation}: T/N {ratio}"
        );
        // the contact force on the block balances the reactions at its top
        let scale = ry.abs();
        assert!((s.force[0] + rx).abs() < 1e-8 * scale, "{formulation}");
        assert!((s.force[1] + ry).abs() < 1e-8 * scale, "{formulation}");
        let length = s.contact_length;
        assert!(
            (length - 1.0).abs() < 1e-12,
            "{formulation}: length {length}"
        );
        let cx = s.centre_of_pressure.unwrap()[0] - 0.05;
        println!("{formulation}: centre of pressure at x = {cx} (block 0 … 1)");
        assert!(cx > 0.0 && cx < 1.0);
    }
}

/// The values of the Float64 point array `name` of a VTU file written by tribo (raw
/// appended data, UInt64 block headers).
fn vtu_point_array(text: &[u8], name: &str) -> Vec<f64> {
    let s = String::from_utf8_lossy(text);
    let tag = s
        .find(&format!("Name=\"{name}\""))
        .unwrap_or_else(|| panic!("no array {name}"));
    let rest = &s[tag..];
    let off: usize = rest[rest.find("offset=\"").unwrap() + 8..]
        .split('"')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let start = s.find("<AppendedData encoding=\"raw\">\n_").unwrap() + 31;
    let data = &text[start + off..];
    let len = u64::from_le_bytes(data[..8].try_into().unwrap()) as usize;
    data[8..8 + len]
        .chunks(8)
        .map(|b| f64::from_le_bytes(b.try_into().unwrap()))
        .collect()
}

/// `tribo run` on SSNP154 A: in result.vtu the contact fields are NaN off the slave
/// surface, exactly 0 on its open nodes; pressure.csv gives open nodes exactly 0; the
/// boundary edges are line cells with their groups; results.json has the per-pair entry.
#[test]
fn result_files_leave_off_surface_nodes_empty_and_open_nodes_zero() {
    let dir = std::env::temp_dir().join(format!("tribo-contact-outputs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let case_file = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/ssnp154/a.toml");
    let run = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .arg("run")
        .arg(&case_file)
        .arg("-o")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let (c, cdir) = case::load(&case_file).unwrap();
    let mesh = case::build_mesh(&c.mesh, &cdir).unwrap();
    let slave = mesh.node_group("Bottom_C").unwrap();
    let vtu = std::fs::read(dir.join("result.vtu")).unwrap();
    let p = vtu_point_array(&vtu, "contact_pressure");
    let status = vtu_point_array(&vtu, "contact_status");
    let gap = vtu_point_array(&vtu, "contact_gap");
    let (mut open, mut closed) = (0, 0);
    for n in 0..mesh.num_nodes() {
        if slave.contains(&n) {
            assert!(p[n].is_finite() && gap[n].is_finite());
            if status[n] == 0.0 {
                assert_eq!(p[n], 0.0, "open node {}", n + 1);
                open += 1;
            } else {
                assert!(p[n] > 0.0);
                closed += 1;
            }
        } else {
            assert!(
                p[n].is_nan() && status[n].is_nan() && gap[n].is_nan(),
                "node {}",
                n + 1
            );
        }
    }
    assert!(open > 0 && closed > 0);
    // pressure.csv: a row per slave node, open ones exactly 0
    let csv = std::fs::read_to_string(dir.join("pressure.csv")).unwrap();
    let mut zeros = 0;
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (node, pressure): (usize, f64) = (f[0].parse().unwrap(), f[5].parse().unwrap());
        assert!(slave.contains(&(node - 1)));
        if status[node - 1] == 0.0 {
            assert_eq!(f[5], "0", "node {node}");
            zeros += 1;
        } else {
            assert!(pressure > 0.0);
        }
    }
    assert_eq!(zeros, open);
    // the edges come as line cells with their groups: reading result.vtu back gives them
    let back = tribo::mesh::read(&dir.join("result.vtu")).unwrap();
    for g in ["Bottom_C", "Top_B", "Encast"] {
        assert_eq!(
            back.cell_group(g).unwrap().len(),
            mesh.cell_group(g).unwrap().len(),
            "{g}"
        );
    }
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    let entry = &results["contact"][0];
    let fy = entry["normal_force"][1].as_f64().unwrap();
    assert!((fy / 17500.0 - 1.0).abs() < 1e-8, "{fy}");
    assert!(entry["contact_length"].as_f64().unwrap() > 0.0);
    // the history has the pair at every output time, in results.json and history.csv
    let history = std::fs::read_to_string(dir.join("history.csv")).unwrap();
    let head: Vec<&str> = history.lines().next().unwrap().split(',').collect();
    let col = head
        .iter()
        .position(|h| *h == "contact1_normal_fy")
        .unwrap();
    let last: Vec<&str> = history.lines().last().unwrap().split(',').collect();
    let fy_csv: f64 = last[col].parse().unwrap();
    assert_eq!(fy_csv, fy);
    assert_eq!(
        results["history"][1]["contact"][0]["normal_force"][1].as_f64(),
        Some(fy)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The same beyond SSNP154: an axisymmetric steel punch (r ≤ 10 mm) pressed step by step
/// into an aluminium foundation, in N-m-Pa, with either surface as slave, frictionless
/// and with Coulomb 0.3, in every formulation. At each of 4 steps the pair's axial
/// resultant balances the reaction on the punch's top (1e-6 of it): each step's outputs
/// are those of its own state, not of the last one.
#[test]
fn every_output_step_balances_its_own_reactions_in_axisymmetry_and_si_units() {
    use tribo::mesh::generate::rectangle;
    use tribo::mesh::CellKind;
    let lower = rectangle([0.0, -0.02], 0.03, 0.02, 12, 6, CellKind::Quad4, 0.0).unwrap();
    let upper = rectangle([0.0, 0.0], 0.01, 0.005, 8, 3, CellKind::Quad4, 0.0).unwrap();
    let mesh = common::bodies(&[("Lower", &lower), ("Upper", &upper)]);
    let head = common::case_head(&[("LowerBody", 70e9, 0.33), ("UpperBody", 210e9, 0.3)]);
    for formulation in ["point-to-segment", "node-to-segment", "mortar"] {
        for (slave, master) in [("UpperBottom", "LowerTop"), ("LowerTop", "UpperBottom")] {
            for friction in [0.0, 0.3] {
                let text = format!(
                    r#"{head}
[model]
modelisation = "axisymmetric"
[[function]]
name = "press"
table = [[0, 0], [1, 1]]
[[displacement]]
group = "LowerBottom"
dx = 0.0
dy = 0.0
[[displacement]]
group = "UpperTop"
dy = -2e-5
function = "press"
[[contact]]
slave = "{slave}"
master = "{master}"
formulation = "{formulation}"
friction = {friction:?}
[solver]
steps = 4
tolerance = 1e-9
[output]
history = true
"#
                );
                let what = format!("{formulation}, slave {slave}, friction {friction}");
                let c: case::schema::CaseFile = toml::from_str(&text).unwrap();
                let out = case::run(&c, &mesh, false).unwrap_or_else(|e| panic!("{what}: {e}"));
                // (every converged step is output: a cut step adds one)
                for t in [0.25, 0.5, 0.75, 1.0] {
                    let at = out.steps.iter().any(|s| (s.time - t).abs() < 1e-12);
                    assert!(at, "{what}: an output at t = {t}");
                }
                let mut last = 0.0;
                for s in &out.steps {
                    let (_, ry) = common::group_sum(&mesh, "UpperTop", &s.reactions);
                    let f = s.contact[0].summary.force;
                    println!(
                        "{what} t = {}: contact force {f:?}, top reaction {ry}",
                        s.time
                    );
                    assert!(ry.abs() > last, "{what}: the load grows");
                    last = ry.abs();
                    assert!(
                        (f[1].abs() - ry.abs()).abs() < 1e-6 * ry.abs(),
                        "{what} t = {}: contact force {f:?}, top reaction {ry}",
                        s.time
                    );
                }
            }
        }
    }
}
