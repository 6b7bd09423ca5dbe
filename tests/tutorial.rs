//! The README's tutorial case (cases/tutorial: roller.geo meshed by Gmsh 4.8 into
//! roller.msh, roller.toml) runs as the README says, and its answer is Hertz's: a steel
//! roller pressed on a steel block in plane strain is a line contact whose half-width and
//! peak pressure follow from the contact force, a = √(4FR/(πE*)), p0 = 2F/(πa) with
//! E* = E / (2(1 − ν²)) (F for the whole roller: twice the half model's).

use std::process::Command;

#[test]
fn tutorial_roller_runs_and_matches_hertz() {
    let dir = std::env::temp_dir().join(format!("tribo-tutorial-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let case = concat!(env!("CARGO_MANIFEST_DIR"), "/cases/tutorial/roller.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(["run", case, "-o"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in ["results.json", "result.vtu", "steps/step.pvd"] {
        assert!(
            dir.join(f).is_file(),
            "{f} (the tutorial opens it in ParaView)"
        );
    }
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    let c = &r["contact"][0];
    let half = c["normal_resultant"].as_f64().unwrap();
    // equilibrium: what pushes the roller down is what the contact carries
    let top = r["reactions"]["RollerTop"]["ry"].as_f64().unwrap();
    let fy = c["force"][1].as_f64().unwrap();
    assert!((top + fy).abs() < 1e-6 * fy.abs(), "{top} vs {fy}");
    let (e, nu, radius, h) = (210000.0, 0.3, 10.0, 0.1);
    let f = 2.0 * half;
    let e_star = e / (2.0 * (1.0 - nu * nu));
    let a = (4.0 * f * radius / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * f / (std::f64::consts::PI * a);
    let peak = c["peak_pressure"].as_f64().unwrap();
    // quadratic cells of 0.1 mm at the contact, a ≈ 0.51 mm: the peak within 1 % and the
    // contact length (the closed nodes' shares) within one cell of a
    assert!((peak / p0 - 1.0).abs() < 0.01, "peak {peak} vs Hertz {p0}");
    let length = c["contact_length"].as_f64().unwrap();
    assert!((length - a).abs() < h, "contact length {length} vs a = {a}");
}
