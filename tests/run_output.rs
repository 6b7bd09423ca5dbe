//! `tribo run`'s output folder is written whole or not at all (issue 22): an older run's
//! files never stay beside new ones, a run that fails late keeps its converged steps with
//! "status": "failed", and a killed or interrupted run leaves the previous results intact
//! and no temporary folder for long.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn tribo() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tribo"))
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tribo-run-output-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A cantilever that converges in one step.
const QUICK: &str = r#"
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
"#;

/// A block crushed in large strains: the top goes down 0.02 per step to t = 1 (0.2 of its
/// height, 10 converged steps), then 0.08 per step: the tangent loses its definiteness
/// past t = 1.3 (0.45 of the height), after step cuts.
const FAILS_LATE: &str = r#"
[mesh]
generator = "rectangle"
width = 1.0
height = 1.0
nx = 2
ny = 2
cell = "Quad4"
[model]
kinematics = "large"
[[material]]
group = "Body"
E = 1000.0
nu = 0.3
[[function]]
name = "crush"
table = [[0, 0], [1, 0.2], [2, 1]]
[[displacement]]
group = "Bottom"
dx = 0.0
dy = 0.0
[[displacement]]
group = "Top"
dx = 0.0
dy = -1.0
function = "crush"
[solver]
steps = 20
[[output.probe]]
name = "top"
group = "Top"
field = "dy"
"#;

/// About 2 s on the 2-core machine (40 large-strain steps of 3600 Quad8): time to kill it.
const SLOW: &str = r#"
[mesh]
generator = "rectangle"
width = 4.0
height = 1.0
nx = 120
ny = 30
cell = "Quad8"
[model]
kinematics = "large"
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
[solver]
steps = 40
[output]
vtu = false
"#;

fn run(dir: &Path, case: &str, text: &str, out: &str) -> Output {
    let p = dir.join(case);
    std::fs::write(&p, text).unwrap();
    tribo()
        .arg("run")
        .arg(&p)
        .arg("-o")
        .arg(dir.join(out))
        .output()
        .unwrap()
}

fn results(dir: &Path) -> Value {
    let f = dir.join("results.json");
    let text = std::fs::read_to_string(&f).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
    serde_json::from_str(&text).unwrap()
}

/// The names in `dir` that start with `.NAME.` (temporary or moved-aside folders).
fn leftovers(dir: &Path, name: &str) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| f.starts_with(&format!(".{name}.")))
        .collect()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn a_new_run_replaces_the_whole_folder() {
    let d = temp_dir("replace");
    let out = d.join("out");
    std::fs::create_dir_all(out.join("steps")).unwrap();
    std::fs::write(out.join("results.json"), r#"{"status": "old"}"#).unwrap();
    std::fs::write(out.join("pressure_7.csv"), "of an older case\n").unwrap();
    std::fs::write(out.join("steps/step_0099.vtu"), "old").unwrap();
    let o = run(&d, "beam.toml", QUICK, "out");
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(results(&out)["status"], "converged");
    assert!(!out.join("pressure_7.csv").exists(), "an old file stayed");
    assert!(
        !out.join("steps/step_0099.vtu").exists(),
        "an old step stayed"
    );
    assert!(out.join("steps/step_0001.vtu").is_file());
    // every file listed is there, under its final name
    for f in results(&out)["files"].as_array().unwrap() {
        assert!(Path::new(f.as_str().unwrap()).is_file(), "{f} missing");
    }
    assert_eq!(leftovers(&d, "out"), Vec::<String>::new());
}

#[test]
fn a_run_that_fails_late_keeps_its_converged_steps() {
    let d = temp_dir("late");
    let out = d.join("out");
    let o = run(&d, "crush.toml", FAILS_LATE, "out");
    assert!(!o.status.success(), "the run must fail");
    assert!(stderr(&o).contains("Newton failed"), "{}", stderr(&o));
    let r = results(&out);
    assert_eq!(r["status"], "failed");
    let failure = &r["failure"];
    let t = failure["time"].as_f64().unwrap();
    assert!(t > 1.0 && t < 2.0, "failure time {t}");
    let reason = failure["reason"].as_str().unwrap();
    assert!(
        reason.starts_with(&format!("Newton failed at t = {t:.4}")),
        "{reason}"
    );
    let last = failure["last_converged_time"].as_f64().unwrap();
    assert!(
        last >= 1.0 && last < t,
        "last converged {last}, failed at {t}"
    );
    // the ten steps to t = 1 and the cut ones after it, each in the history, the series
    // and history.csv
    let history = r["history"].as_array().unwrap();
    assert!(history.len() >= 10, "{} steps kept", history.len());
    assert_eq!(history.last().unwrap()["time"].as_f64(), Some(last));
    let top = history[9]["probes"]["top"].as_f64().unwrap();
    assert!((top + 0.2).abs() < 1e-12, "top at t = 1: {top}");
    let pvd = std::fs::read_to_string(out.join("steps/step.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), history.len());
    for k in 1..=history.len() {
        assert!(out.join(format!("steps/step_{k:04}.vtu")).is_file());
    }
    let csv = std::fs::read_to_string(out.join("history.csv")).unwrap();
    assert_eq!(csv.lines().count(), history.len() + 1, "{csv}");
    assert!(out.join("result.vtu").is_file());
    assert_eq!(leftovers(&d, "out"), Vec::<String>::new());
}

#[test]
fn an_input_error_leaves_the_old_results() {
    let d = temp_dir("input");
    let out = d.join("out");
    let o = run(&d, "beam.toml", QUICK, "out");
    assert!(o.status.success(), "{}", stderr(&o));
    let before = std::fs::read(out.join("results.json")).unwrap();
    let bad = QUICK.replace("group = \"TopRight\"", "group = \"Nowhere\"");
    let o = run(&d, "beam.toml", &bad, "out");
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("Nowhere"), "{}", stderr(&o));
    assert_eq!(std::fs::read(out.join("results.json")).unwrap(), before);
    assert_eq!(leftovers(&d, "out"), Vec::<String>::new());
}

#[test]
fn a_folder_of_other_files_is_not_replaced() {
    let d = temp_dir("foreign");
    let out = d.join("out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let o = run(&d, "beam.toml", QUICK, "out");
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("out") && e.contains("no results.json"), "{e}");
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
    assert_eq!(leftovers(&d, "out"), Vec::<String>::new());
}

/// Starts the slow case into `d/out` and waits until its temporary folder exists.
fn start_slow(d: &Path) -> (std::process::Child, PathBuf) {
    let p = d.join("slow.toml");
    std::fs::write(&p, SLOW).unwrap();
    let mut child = tribo()
        .arg("run")
        .arg(&p)
        .arg("-o")
        .arg(d.join("out"))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let temp = d.join(format!(".out.tmp-{}", child.id()));
    let t0 = Instant::now();
    while !temp.is_dir() {
        let done = child.try_wait().unwrap();
        assert!(
            done.is_none(),
            "the slow case ended before its folder was seen"
        );
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "no temporary folder"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
    (child, temp)
}

#[test]
fn a_killed_run_leaves_the_old_results_and_the_next_run_cleans_up() {
    let d = temp_dir("killed");
    let out = d.join("out");
    let o = run(&d, "beam.toml", QUICK, "out");
    assert!(o.status.success(), "{}", stderr(&o));
    let before = std::fs::read(out.join("results.json")).unwrap();
    let (mut child, temp) = start_slow(&d);
    child.kill().unwrap(); // SIGKILL: nothing runs after it
    let status = child.wait().unwrap();
    assert!(!status.success());
    assert_eq!(std::fs::read(out.join("results.json")).unwrap(), before);
    assert!(
        temp.is_dir(),
        "SIGKILL cannot clean up: the folder stays for the next run"
    );
    let o = run(&d, "beam.toml", QUICK, "out");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        !temp.exists(),
        "the stale folder of the killed run is still there"
    );
    assert_eq!(leftovers(&d, "out"), Vec::<String>::new());
}

#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[test]
fn sigterm_and_sigint_delete_the_temporary_folder() {
    use std::os::unix::process::ExitStatusExt;
    for sig in [libc::SIGTERM, libc::SIGINT] {
        let d = temp_dir(&format!("signal{sig}"));
        let out = d.join("out");
        let o = run(&d, "beam.toml", QUICK, "out");
        assert!(o.status.success(), "{}", stderr(&o));
        let before = std::fs::read(out.join("results.json")).unwrap();
        let (mut child, temp) = start_slow(&d);
        // SAFETY: a signal to the child we started (still running: start_slow checked).
        assert_eq!(unsafe { libc::kill(child.id() as i32, sig) }, 0);
        let status = child.wait().unwrap();
        assert_eq!(
            status.signal(),
            Some(sig),
            "ended by the signal: {status:?}"
        );
        assert!(!temp.exists(), "signal {sig}: the temporary folder stayed");
        assert_eq!(std::fs::read(out.join("results.json")).unwrap(), before);
        assert_eq!(leftovers(&d, "out"), Vec::<String>::new());
    }
}
