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
    assert!(text.contains("NumberOfCells=\"16\""));
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
