//! What the `tribo` command prints: piped output holds no control characters (the status
//! line is for terminals only), `--quiet` prints nothing but errors, `-v` names each load
//! step, and on a terminal (a pseudo-terminal by `script`) the status line is drawn.

use std::path::PathBuf;
use std::process::{Command, Output};

fn tribo() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tribo"))
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tribo-progress-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A cantilever in 3 load steps.
const CASE: &str = r#"
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
[solver]
steps = 3
[[output.probe]]
name = "tip"
group = "TopRight"
field = "dy"
"#;

fn case(name: &str) -> (PathBuf, PathBuf) {
    let d = temp_dir(name);
    let case = d.join("beam.toml");
    std::fs::write(&case, CASE).unwrap();
    (case, d)
}

/// Control characters other than newline and tab (escape sequences, carriage returns).
fn control_chars(bytes: &[u8]) -> usize {
    bytes
        .iter()
        .filter(|&&b| (b < 0x20 && b != b'\n' && b != b'\t') || b == 0x7f)
        .count()
}

fn ok(out: &Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn piped_output_has_no_control_characters() {
    let (c, d) = case("piped");
    let run = tribo()
        .arg("run")
        .arg(&c)
        .arg("-o")
        .arg(d.join("out"))
        .output()
        .unwrap();
    ok(&run);
    assert!(String::from_utf8_lossy(&run.stdout).contains("converged in"));
    let study = tribo()
        .args(["study", "hertz", "--levels", "2", "--kinematics", "small"])
        .output()
        .unwrap();
    ok(&study);
    for (what, out) in [("run", &run), ("study hertz", &study)] {
        assert_eq!(control_chars(&out.stdout), 0, "{what}: stdout");
        assert_eq!(control_chars(&out.stderr), 0, "{what}: stderr");
        assert!(out.stderr.is_empty(), "{what}: stderr not empty");
    }
}

#[test]
fn quiet_prints_nothing_but_errors() {
    let (c, d) = case("quiet");
    for args in [vec!["--quiet", "run"], vec!["run", "-q"]] {
        let out = tribo()
            .args(&args)
            .arg(&c)
            .arg("-o")
            .arg(d.join("out"))
            .output()
            .unwrap();
        ok(&out);
        assert!(out.stdout.is_empty() && out.stderr.is_empty(), "{args:?}");
        assert!(d.join("out/results.json").is_file(), "the run still writes");
    }
    // with -v too: quiet wins
    let out = tribo()
        .args(["run", "-q", "-v"])
        .arg(&c)
        .arg("-o")
        .arg(d.join("out"))
        .output()
        .unwrap();
    ok(&out);
    assert!(out.stdout.is_empty() && out.stderr.is_empty());
    // an error still reaches stderr
    let bad = d.join("bad.toml");
    std::fs::write(&bad, CASE.replace("group = \"Left\"", "group = \"Wall\"")).unwrap();
    let out = tribo().args(["run", "--quiet"]).arg(&bad).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("error: [[displacement]]: group 'Wall'"),
        "{err}"
    );
}

#[test]
fn verbose_names_each_load_step() {
    let (c, d) = case("verbose");
    let out = tribo()
        .args(["run", "-v"])
        .arg(&c)
        .arg("-o")
        .arg(d.join("out"))
        .output()
        .unwrap();
    ok(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    for (k, t) in [(1, "0.3333"), (2, "0.6667"), (3, "1.0000")] {
        assert!(
            err.contains(&format!("load step {k} of 3: t = {t}")),
            "step {k}: {err}"
        );
    }
    assert_eq!(control_chars(&out.stderr), 0);
}

/// `script` runs the command on a pseudo-terminal: the status line (load step, iteration,
/// residual) is drawn and cleared; with `--quiet` nothing is.
#[test]
fn a_terminal_gets_the_status_line() {
    if Command::new("script").arg("--version").output().is_err() {
        eprintln!("no `script` (util-linux): pseudo-terminal check skipped");
        return;
    }
    let (c, d) = case("tty");
    let on_tty = |quiet: &str| -> String {
        let cmd = format!(
            "{} {quiet} study hertz --levels 3 --kinematics small; {} {quiet} run {} -o {}",
            env!("CARGO_BIN_EXE_tribo"),
            env!("CARGO_BIN_EXE_tribo"),
            c.display(),
            d.join("out").display()
        );
        let out = Command::new("script")
            .args(["-qec", &cmd, "/dev/null"])
            .output()
            .unwrap();
        ok(&out);
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let shown = on_tty("");
    assert!(shown.contains(" of 3, h = "), "{shown}");
    assert!(shown.contains("load step 1 of"), "{shown}");
    assert!(shown.contains("residual"), "{shown}");
    assert!(shown.contains("converged in"), "{shown}");
    let quiet = on_tty("--quiet");
    assert!(quiet.trim().is_empty(), "{quiet}");
}
