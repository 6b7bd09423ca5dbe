//! Bad case files give errors that name the key, group or entry and list what is valid.

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

fn write_case(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tribo-case-tests-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn error_of(name: &str, text: &str) -> String {
    let p = write_case(name, text);
    let (c, dir) = match case::load(&p) {
        Ok(v) => v,
        Err(e) => return e.to_string(),
    };
    let mesh = match case::build_mesh(&c.mesh, &dir) {
        Ok(m) => m,
        Err(e) => return e.to_string(),
    };
    match case::run(&c, &mesh, false) {
        Ok(_) => panic!("{name}: expected an error"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn good_case_runs() {
    let p = write_case("good.toml", GOOD);
    let (c, dir) = case::load(&p).unwrap();
    let mesh = case::build_mesh(&c.mesh, &dir).unwrap();
    let out = case::run(&c, &mesh, false).unwrap();
    assert!(out.report.total_iterations >= 1);
}

#[test]
fn unknown_key_names_it_and_lists_valid_keys() {
    let e = error_of(
        "unknown.toml",
        &GOOD.replace("nu = 0.3", "nu = 0.3\ndensity = 7.8"),
    );
    assert!(e.contains("unknown.toml"), "{e}");
    assert!(e.contains("line 13"), "{e}");
    assert!(
        e.contains("unknown field `density`, expected one of `group`, `E`, `nu`"),
        "{e}"
    );
}

#[test]
fn missing_group_lists_the_groups() {
    let e = error_of(
        "group.toml",
        &GOOD.replace("group = \"Left\"", "group = \"Clamp\""),
    );
    assert_eq!(
        e,
        "[[displacement]]: group 'Clamp' is not in the mesh; groups are: Body, Bottom, BottomLeft, \
         BottomRight, Left, Right, Top, TopLeft, TopRight"
    );
}

#[test]
fn negative_young_modulus_is_rejected() {
    let e = error_of("young.toml", &GOOD.replace("E = 1000.0", "E = -5.0"));
    assert_eq!(
        e,
        "[[material]] for group 'Body': Young's modulus E must be positive, got -5"
    );
}

#[test]
fn missing_material_is_rejected() {
    let e = error_of(
        "nomat.toml",
        &GOOD.replace("group = \"Body\"", "group = \"Top\""),
    );
    assert_eq!(
        e,
        "[[material]] for group 'Top': the group is not made of 2D cells"
    );
}

#[test]
fn rigid_body_mode_is_reported() {
    let e = error_of("free.toml", &GOOD.replace("dy = 0.0\n", ""));
    assert!(e.starts_with("Newton failed at t ="), "{e}");
    assert!(e.contains("rigid-body mode"), "{e}");
}

#[test]
fn unknown_generator_and_missing_keys() {
    let e = error_of("gen.toml", &GOOD.replace("\"rectangle\"", "\"disc\""));
    assert_eq!(
        e,
        "[mesh] unknown generator 'disc'; generators are: ssnp154, disc_pair, rectangle, ring"
    );
    let e = error_of("nx.toml", &GOOD.replace("nx = 4\n", ""));
    assert_eq!(e, "[mesh] generator 'rectangle' needs the key 'nx'");
}

#[test]
fn bad_probe_field_is_rejected_before_solving() {
    let text = format!(
        "{GOOD}\n[[output.probe]]\nname = \"tip\"\ngroup = \"TopRight\"\nfield = \"temperature\"\n"
    );
    let e = error_of("probe.toml", &text);
    assert_eq!(
        e,
        "probe 'tip': field 'temperature' is not one of dx, dy, sixx, siyy, sizz, sixy, vmis, \
         pk2xx, pk2yy, pk2zz, pk2xy, sirr, sitt, sirt, contact_pressure, contact_shear, \
         contact_gap, contact_status"
    );
}

#[test]
fn missing_mesh_file_names_it() {
    let e = error_of(
        "file.toml",
        "[mesh]\nfile = \"nowhere.msh\"\n[[material]]\ngroup = \"Body\"\nE = 1.0\nnu = 0.3\n",
    );
    assert!(e.contains("nowhere.msh"), "{e}");
    assert!(e.contains("No such file"), "{e}");
}

/// The error of GOOD with a [[contact]] table of these lines added.
fn contact_error(name: &str, lines: &str) -> String {
    error_of(
        name,
        &GOOD.replace("[[force]]", &format!("[[contact]]\n{lines}\n[[force]]")),
    )
}

#[test]
fn bad_contact_entries_are_rejected() {
    let pair = "slave = \"Top\"\nmaster = \"Bottom\"";
    assert_eq!(
        contact_error("same.toml", "slave = \"Top\"\nmaster = \"Top\""),
        "[[contact]] 1 (Top on Top): slave and master must be different groups"
    );
    // two surfaces of one body may be in contact, but not a body's top and bottom
    let e = contact_error("body.toml", pair);
    assert!(
        e.starts_with(
            "[[contact]] 1 (Top on Bottom): 'Top' and 'Bottom' are surfaces of one body that \
             face away from each other: node "
        ) && e.contains(" lies 1.000e0 behind the other surface, inside the body"),
        "{e}"
    );
    assert_eq!(
        contact_error("mu.toml", &format!("{pair}\nfriction = -0.1")),
        "[[contact]] 1 (Top on Bottom): friction must be 0 or positive, got -0.1"
    );
    let e = contact_error("arc.toml", "slave = \"Arc\"\nmaster = \"Bottom\"");
    assert!(e.starts_with("[[contact]] 1 (Arc on Bottom): slave surface: group 'Arc' is not in the mesh; groups are: Body"), "{e}");
    assert_eq!(
        contact_error("pen.toml", &format!("{pair}\npenalty = 1e4")),
        "[[contact]] 1 (Top on Bottom): penalty goes with formulation = \"node-to-segment\""
    );
    assert_eq!(
        contact_error(
            "negpen.toml",
            &format!("{pair}\nformulation = \"node-to-segment\"\npenalty = -3.0")
        ),
        "[[contact]] 1 (Top on Bottom): penalty must be positive, got -3"
    );
    assert_eq!(
        contact_error("gap.toml", &format!("{pair}\ninitial_gap = 0.1")),
        "[[contact]] 1 (Top on Bottom): initial_gap must be 0 or positive and goes with initial = \"closed\", \
         got 0.1 with initial = \"touching (the default)\""
    );
    let e = contact_error("pt.toml", "slave = \"TopLeft\"\nmaster = \"Bottom\"");
    assert!(
        e.contains("holds a Point1 cell; contact surfaces are groups of Seg2/Seg3 edges"),
        "{e}"
    );
}

#[test]
fn probe_at_a_point_takes_the_nearest_node_and_curves_check_their_group() {
    // the corner TopRight is (2, 1): a probe at (1.98, 0.97) reads its node
    let text = format!(
        "{GOOD}[[output.probe]]\nname = \"by_group\"\ngroup = \"TopRight\"\nfield = \"dy\"\n\
         [[output.probe]]\nname = \"by_point\"\nat = [1.98, 0.97]\nfield = \"dy\"\n"
    );
    let p = write_case("probe_at.toml", &text);
    let (c, dir) = case::load(&p).unwrap();
    let mesh = case::build_mesh(&c.mesh, &dir).unwrap();
    let out = case::run(&c, &mesh, false).unwrap();
    assert_eq!(out.probes[0].1, out.probes[1].1);
    assert!(out.probes[0].1 < 0.0);
    let both = format!(
        "{GOOD}[[output.probe]]\nname = \"p\"\ngroup = \"TopRight\"\nat = [0.0, 0.0]\nfield = \"dy\"\n"
    );
    assert_eq!(
        error_of("probe_both.toml", &both),
        "probe 'p': give either group = \"NAME\" or at = [x, y]"
    );
    let curve = format!("{GOOD}[[output.curve]]\nname = \"c\"\ngroup = \"Body\"\n");
    assert_eq!(
        error_of("curve.toml", &curve),
        "[[output.curve]] 'c': curve: group 'Body' holds no edge (Seg2/Seg3) cells"
    );
}

#[test]
fn bad_load_histories_name_the_entry() {
    let with = |extra: &str| format!("{GOOD}{extra}");
    let e = error_of(
        "fn_times.toml",
        &with("[[function]]\nname = \"ramp\"\ntable = [[0, 0], [1, 1], [0.5, 2]]\n"),
    );
    assert_eq!(
        e,
        "[[function]] 'ramp': times must increase strictly, but 0.5 follows 1"
    );
    let e = error_of(
        "fn_unknown.toml",
        &with("[[function]]\nname = \"ramp\"\ntable = [[0, 0], [1, 1]]\n")
            .replace("fy = -1.0", "fy = -1.0\nfunction = \"rampe\""),
    );
    assert_eq!(
        e,
        "[[force]] 1 on 'TopRight': function 'rampe' is not defined (functions: ramp)"
    );
    let e = error_of(
        "fn_twice.toml",
        &with("[[function]]\nname = \"f\"\ntable = [[0, 0], [1, 1]]\n[[function]]\nname = \"f\"\ntable = [[0, 0], [2, 1]]\n"),
    );
    assert_eq!(e, "[[function]] 'f' is defined twice");
    let e = error_of(
        "out_time.toml",
        &with(
            "[[function]]\nname = \"f\"\ntable = [[0, 0], [2, 1]]\n[output]\ntimes = [1.0, 2.5]\n",
        )
        .replace("fy = -1.0", "fy = -1.0\nfunction = \"f\""),
    );
    assert!(
        e.starts_with("[output] times: 2.5 is outside the history (0, 2]"),
        "{e}"
    );
    let e = error_of("out_order.toml", &with("[output]\ntimes = [0.5, 0.25]\n"));
    assert_eq!(
        e,
        "[output] times must increase strictly, but 0.25 follows 0.5"
    );
    let e = error_of("end.toml", &with("[solver]\nend_time = -1.0\n"));
    assert_eq!(e, "[solver] end_time must be positive, got -1");
    let e = error_of(
        "rot_overlap.toml",
        &with("[[rotation]]\ngroup = \"Left\"\ncenter = [0.0, 0.0]\nangle = 10.0\n"),
    );
    assert!(
        e.starts_with("[[rotation]] on 'Left': node ")
            && e.ends_with("also has a [[displacement]]; a node's motion is imposed once"),
        "{e}"
    );
}
