//! The `tribo` command end to end: exit codes, outputs, error text.

use std::path::PathBuf;
use std::process::Command;

fn tribo() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tribo"))
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tribo-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const CASE: &str = r#"
title = "cantilever"
[mesh]
generator = "rectangle"
width = 4.0
height = 1.0
nx = 8
ny = 2
cell = "Quad4"
[[material]]
group = "Body"
E = 1000.0
nu = 0.3
[[displacement]]
group = "Left"
dx = 0.0
dy = 0.0
[[force]]
group = "TopRight"
fy = -1.0
[[output.probe]]
name = "tip"
group = "TopRight"
field = "dy"
"#;

#[test]
fn run_writes_results_and_vtu() {
    let d = temp_dir("run");
    let case = d.join("beam.toml");
    std::fs::write(&case, CASE).unwrap();
    let out = tribo()
        .arg("run")
        .arg(&case)
        .arg("-o")
        .arg(d.join("out"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("out/results.json")).unwrap())
            .unwrap();
    let tip = results["probes"]["tip"].as_f64().unwrap();
    assert!(tip < 0.0);
    let ry = results["reactions"]["Left"]["ry"].as_f64().unwrap();
    assert!(
        (ry - 1.0).abs() < 1e-9,
        "reaction {ry} must balance the load"
    );
    let vtu = std::fs::read(d.join("out/result.vtu")).unwrap();
    assert!(vtu.starts_with(b"<?xml"));
    let text = String::from_utf8_lossy(&vtu);
    // 16 quadrilaterals and the 20 boundary edges
    assert!(text.contains("NumberOfCells=\"36\""));
    assert!(text.contains("Name=\"cell_dim\"") && text.contains("Name=\"group_Left\""));
    assert!(text.contains("Name=\"displacement\""));
    assert!(text.contains("Name=\"von_mises\""));
    assert!(text.trim_end().ends_with("</VTKFile>"));
}

#[test]
fn bad_case_exits_2_with_the_message() {
    let d = temp_dir("bad");
    let case = d.join("bad.toml");
    std::fs::write(&case, CASE.replace("group = \"Left\"", "group = \"Wall\"")).unwrap();
    let out = tribo().arg("run").arg(&case).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with(
            "error: [[displacement]]: group 'Wall' is not in the mesh; groups are: Body"
        ),
        "{err}"
    );
    assert!(!d.join("bad").exists(), "no output folder on failure");
}

const MSH: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 1 \"Edge\"\n2 2 \"Plate\"\n$EndPhysicalNames\n\
$Entities\n0 1 1 0\n1 0 0 0 1 0 0 1 1 0\n1 0 0 0 1 1 0 1 2 0\n$EndEntities\n\
$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n\
$Elements\n2 2 1 2\n1 1 1 1\n1 1 2\n2 1 3 1\n2 1 4 3 2\n$EndElements\n";

#[test]
fn mesh_info_json() {
    let d = temp_dir("info");
    let f = d.join("plate.msh");
    std::fs::write(&f, MSH).unwrap();
    let out = tribo()
        .args(["mesh", "info", "--json"])
        .arg(&f)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["nodes"], 4);
    assert_eq!(v["cells"]["Quad4"], 1);
    assert_eq!(v["cells"]["Seg2"], 1);
    assert_eq!(v["reoriented"], 1);
    assert_eq!(v["groups"]["Plate"]["dim"], 2);
    assert_eq!(v["groups"]["Plate"]["nodes"], 4);
    assert_eq!(v["groups"]["Edge"]["cells"], 1);
}

#[test]
fn truncated_mesh_names_the_file() {
    let d = temp_dir("trunc");
    let f = d.join("cut.msh");
    std::fs::write(&f, &MSH[..MSH.len() / 2]).unwrap();
    let out = tribo().args(["mesh", "info"]).arg(&f).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("cut.msh"), "{err}");
}

#[test]
fn hertz_study_writes_levels_and_rates() {
    let d = temp_dir("study");
    let (json, csv) = (d.join("study.json"), d.join("study.csv"));
    let out = tribo()
        .args([
            "study",
            "hertz",
            "--levels",
            "2",
            "--linear",
            "--kinematics",
            "small",
        ])
        .arg("--json")
        .arg(&json)
        .arg("--csv")
        .arg(&csv)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let levels = doc["studies"][0]["levels"].as_array().unwrap();
    assert_eq!(levels.len(), 2);
    for l in levels {
        // coarse levels: the peak within 3 % of Hertz's p0, the half-width within 3 % of a
        let peak = l["peak_MPa"].as_f64().unwrap();
        let a = l["half_width_mm"].as_f64().unwrap();
        assert!((peak / 3585.36 - 1.0).abs() < 0.03, "peak {peak}");
        assert!((a / 6.2146 - 1.0).abs() < 0.03, "half-width {a}");
    }
    // the finer level's pressure profile is closer to Hertz
    let l2: Vec<f64> = levels
        .iter()
        .map(|l| l["l2_error"].as_f64().unwrap())
        .collect();
    assert!(l2[1] < l2[0], "{l2:?}");
    assert_eq!(std::fs::read_to_string(&csv).unwrap().lines().count(), 3);
    let bad = tribo()
        .args(["study", "hertz", "--kinematics", "medium"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr)
        .contains("--kinematics 'medium' is not one of small, large, both"));
}

#[test]
fn mesh_refine_splits_cells_and_keeps_groups() {
    let d = temp_dir("refine");
    let f = d.join("plate.msh");
    std::fs::write(&f, MSH).unwrap();
    let refine = |to: &std::path::Path, split: &str| {
        tribo()
            .args(["mesh", "refine"])
            .arg(&f)
            .arg(to)
            .args(["--split", split])
            .output()
            .unwrap()
    };
    let out_file = d.join("fine.msh");
    let out = refine(&out_file, "3");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = tribo()
        .args(["mesh", "info", "--json"])
        .arg(&out_file)
        .output()
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["nodes"], 16);
    assert_eq!(v["cells"]["Quad4"], 9);
    assert_eq!(v["cells"]["Seg2"], 3);
    assert_eq!(v["groups"]["Plate"]["cells"], 9);
    assert_eq!(v["groups"]["Edge"]["nodes"], 4);
    // a factor out of range: exit 2, the message says what is allowed, nothing written
    let bad = d.join("bad.msh");
    let out = refine(&bad, "0");
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--split must be between 1 and 16"), "{err}");
    assert!(!bad.exists());
}
