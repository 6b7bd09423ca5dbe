//! Inputs that used to give a silent wrong answer (exit 0) are refused before any work, or
//! fail clearly: each error names the entry. One test per kind of defect of issue 22.

use std::path::PathBuf;
use tribo::case;

const GOOD: &str = r#"
[mesh]
generator = "rectangle"
width = 2.0
height = 1.0
nx = 4
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

fn error_of(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("tribo-input-checks-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p: PathBuf = dir.join(name);
    std::fs::write(&p, text).unwrap();
    let (c, dir) = match case::load(&p) {
        Ok(v) => v,
        Err(e) => return e.to_string(),
    };
    let mesh = match case::build_mesh(&c.mesh, &dir) {
        Ok(m) => m,
        Err(e) => return e.to_string(),
    };
    match case::run(&c, &mesh, false) {
        Ok(_) => panic!("{name}: accepted"),
        Err(e) => e.to_string(),
    }
}

fn expect(name: &str, extra: &str, needle: &str) {
    let e = error_of(name, &format!("{GOOD}{extra}"));
    assert!(e.contains(needle), "{name}: {e}");
}

#[test]
fn a_force_that_turns_cells_inside_out_is_not_a_converged_state() {
    let text = GOOD.replace("fy = -1.0", "fy = -1e6") + "[model]\nkinematics = \"large\"\n";
    let e = error_of("invert.toml", &text);
    assert!(e.contains("turned inside out"), "{e}");
    // small kinematics too: a displacement field that tangles the mesh is not an answer
    let text = GOOD.replace("fy = -1.0", "fy = -1e6");
    let e = error_of("invert_small.toml", &text);
    assert!(e.contains("turned inside out"), "{e}");
}

#[test]
fn conflicts_name_both_entries() {
    expect(
        "two_materials.toml",
        "[[material]]\ngroup = \"Body\"\nE = 5.0\nnu = 0.3\n",
        "[[material]] 1 and 2 are both for group 'Body'",
    );
    expect(
        "dof_twice.toml",
        "[[displacement]]\ngroup = \"BottomLeft\"\ndx = 1.0\n",
        "is also imposed by [[displacement]] 1 on 'Left'",
    );
    expect(
        "rotation_and_displacement.toml",
        "[[displacement]]\ngroup = \"Right\"\ndy = 0.0\n[[rotation]]\ngroup = \"Right\"\ncenter = [0.0, 0.0]\nangle = 1.0\n",
        "also has a [[displacement]]",
    );
    expect(
        "probe_twice.toml",
        "[[output.probe]]\nname = \"p\"\ngroup = \"TopRight\"\nfield = \"dy\"\n[[output.probe]]\nname = \"p\"\ngroup = \"TopRight\"\nfield = \"dx\"\n",
        "has the same name 'p'",
    );
}

#[test]
fn non_finite_and_out_of_range_numbers_are_refused() {
    expect(
        "rel_nan.toml",
        "[[relation]]\nterms = [{ group = \"TopRight\", dof = \"dy\", coef = nan }]\n",
        "coef of TopRight dy must be a finite number",
    );
    expect(
        "rel_zero.toml",
        "[[relation]]\nterms = [{ group = \"TopRight\", dof = \"dy\", coef = 0.0 }]\n",
        "every coefficient is zero",
    );
    expect(
        "tol.toml",
        "[solver]\ntolerance = 10.0\n",
        "[solver] tolerance",
    );
    expect(
        "tol_inf.toml",
        "[solver]\ntolerance = inf\n",
        "[solver] tolerance",
    );
    expect(
        "steps.toml",
        "[solver]\nsteps = 1000000000\n",
        "[solver] steps must lie in",
    );
    expect(
        "probe_nan.toml",
        "[[output.probe]]\nname = \"p\"\nat = [nan, nan]\nfield = \"dy\"\n",
        "at must be a finite number",
    );
    expect(
        "hertz_nan.toml",
        "[output]\nhertz = { a = nan, p0 = 1.0 }\n",
        "[output] hertz: a must be a finite number",
    );
    expect(
        "force_inf.toml",
        "[[force]]\ngroup = \"Right\"\nfx = inf\n",
        "fx must be a finite number",
    );
    let huge = GOOD
        .replace("nx = 4", "nx = 100000")
        .replace("ny = 2", "ny = 100000");
    let e = error_of("huge_mesh.toml", &huge);
    assert!(e.contains("asks for more than"), "{e}");
}

#[test]
fn keys_that_do_nothing_are_refused() {
    let e = error_of(
        "thickness_axisym.toml",
        &format!("{GOOD}[model]\nmodelisation = \"axisymmetric\"\nthickness = 5.0\n"),
    );
    assert!(e.contains("thickness = 5 does nothing"), "{e}");
    let e = error_of("nx_ssnp.toml", "[mesh]\ngenerator = \"ssnp154\"\nnx = 3\n");
    assert!(
        e.contains("[mesh] nx does nothing with the 'ssnp154' generator"),
        "{e}"
    );
}

#[test]
fn output_names_cannot_leave_the_output_folder() {
    for name in [
        "x/../../somewhere",
        "/tmp/abs",
        "..",
        "a\\\\b",
        "with,comma",
        "",
    ] {
        let extra = format!("[[output.curve]]\nname = \"{name}\"\ngroup = \"Top\"\n");
        let e = error_of("curve_name.toml", &format!("{GOOD}{extra}"));
        assert!(e.contains("must be made of letters, digits"), "{name}: {e}");
    }
}

#[test]
fn a_closed_or_full_stdout_ends_quietly_with_a_non_zero_status() {
    use std::process::{Command, Stdio};
    use tribo::mesh::generate::rectangle;
    use tribo::mesh::gmsh_write::{write, MshVersion};
    let dir = std::env::temp_dir().join(format!("tribo-stdout-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let msh = dir.join("m.msh");
    let m = rectangle(
        [0.0, 0.0],
        1.0,
        1.0,
        2,
        2,
        tribo::mesh::CellKind::Quad4,
        0.0,
    )
    .unwrap();
    write(&msh, &m, MshVersion::V41).unwrap();
    // a pipe whose reader is gone before the command starts (closed after the spawn, it
    // raced the command's output: on a busy machine the output fitted in the pipe first)
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(["mesh", "info"])
        .arg(&msh)
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_ne!(out.status.code(), Some(0));
    // a full device
    if let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") {
        let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
            .args(["mesh", "info"])
            .arg(&msh)
            .stdout(full)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert_eq!(out.status.code(), Some(3));
    }
}

#[test]
fn entries_that_say_nothing_or_contradict_another_are_refused() {
    expect(
        "force_none.toml",
        "[[force]]\ngroup = \"Right\"\n",
        "[[force]] 2 on 'Right' imposes nothing: give fx, fy or both",
    );
    expect(
        "traction_none.toml",
        "[[traction]]\ngroup = \"Right\"\n",
        "[[traction]] 1 on 'Right' imposes nothing: give tx, ty or both",
    );
    expect(
        "fn_unused.toml",
        "[[function]]\nname = \"f\"\ntable = [[0, 0], [1, 1]]\n",
        "[[function]] 1 ('f') is used by no load",
    );
    expect(
        "hertz_alone.toml",
        "[output]\nhertz = { a = 1.0, p0 = 1.0 }\n",
        "[output] hertz does nothing without a [[contact]]",
    );
    expect(
        "probe_group_stress_group.toml",
        "[[output.probe]]\nname = \"p\"\ngroup = \"TopRight\"\nfield = \"dx\"\nstress_group = \"Body\"\n",
        "stress_group does nothing on a displacement probe (field = dx)",
    );
    // dy(TopRight) − dy(TopRight) = 0 is no equation; with 1.5 and −1.5 + 0 dx neither
    expect(
        "rel_cancel.toml",
        "[[relation]]\nterms = [{ group = \"TopRight\", dof = \"dy\", coef = 1.5 }, \
         { group = \"TopRight\", dof = \"dy\", coef = -1.5 }]\n",
        "[[relation]] 'relation 1': its terms cancel",
    );
    expect(
        "rotations.toml",
        "[[rotation]]\ngroup = \"Right\"\ncenter = [0.0, 0.0]\nangle = 1.0\n\
         [[rotation]]\ngroup = \"BottomRight\"\ncenter = [0.0, 0.0]\nangle = 2.0\n",
        "[[rotation]] on 'BottomRight' (angle 2): node 13 is also moved by [[rotation]] 1 on 'Right'",
    );
    expect(
        "probe_far.toml",
        "[[output.probe]]\nname = \"p\"\nat = [1e300, 0.0]\nfield = \"dy\"\n",
        "at = [1e300, 0e0] is more than 1e6 times the mesh size",
    );
    let axisym = GOOD.replace(
        "group = \"TopRight\"\nfy",
        "group = \"TopLeft\"\nfx = 1.0\nfy",
    ) + "[model]\nmodelisation = \"axisymmetric\"\n";
    let e = error_of("axis_force.toml", &axisym);
    assert!(
        e.contains("[[force]] 1 on 'TopLeft': node 3 is on the axis (r = 0)"),
        "{e}"
    );
}
