//! Sizes checked against memory before allocation (issue 22): a case or a refinement that
//! needs more than the memory available is refused at once with the estimate, naming the
//! entry; the available memory is set with TRIBO_MEMORY_LIMIT so that the outcome does
//! not depend on the machine.

use std::path::PathBuf;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tribo-mem-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn rectangle(nx: usize, cell: &str) -> String {
    format!(
        "[mesh]\ngenerator = \"rectangle\"\nwidth = 1.0\nheight = 1.0\nnx = {nx}\nny = {nx}\n\
         cell = \"{cell}\"\n[model]\nmodelisation = \"plane_strain\"\n[[material]]\n\
         group = \"Body\"\nE = 1000.0\nnu = 0.3\n[[displacement]]\ngroup = \"Bottom\"\n\
         dx = 0.0\ndy = 0.0\n[[pressure]]\ngroup = \"Top\"\np = 1.0\n"
    )
}

fn tribo(limit: &str, args: &[&std::ffi::OsStr]) -> (Output, Duration) {
    let t = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(args)
        .env("TRIBO_MEMORY_LIMIT", limit)
        .output()
        .unwrap();
    (out, t.elapsed())
}

fn run(d: &std::path::Path, name: &str, case: &str, limit: &str) -> (Output, Duration) {
    let path = d.join(format!("{name}.toml"));
    std::fs::write(&path, case).unwrap();
    tribo(
        limit,
        &[
            "run".as_ref(),
            path.as_os_str(),
            "-o".as_ref(),
            d.join(name).as_os_str(),
        ],
    )
}

#[test]
fn a_rectangle_beyond_memory_is_refused_before_it_is_made() {
    let d = dir("rect");
    // 3000 × 3000 Quad8 passes the cell-count cap (18 M cells) but is 27 M nodes
    let (out, took) = run(&d, "big", &rectangle(3000, "Quad8"), "8G");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains(
            "[mesh] nx × ny = 3000 × 3000 (27012001 nodes, 9000000 Quad8 cells) needs about"
        ) && err.contains("more than the 8.0 GB available (TRIBO_MEMORY_LIMIT)"),
        "{err}"
    );
    assert!(took < Duration::from_secs(5), "refused after {took:?}");
    assert!(!d.join("big").exists(), "an output folder was made");
}

#[test]
fn a_model_beyond_memory_is_refused_before_assembly_and_a_small_one_runs() {
    let d = dir("model");
    let (out, _) = run(&d, "q8", &rectangle(200, "Quad8"), "100M");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("nx × ny = 200 × 200 (120801 nodes, 40000 Quad8 cells) needs about")
            && err.contains("more than the 100 MB available"),
        "{err}"
    );
    let (out, _) = run(&d, "small", &rectangle(4, "Quad4"), "1G");
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_refinement_beyond_memory_is_refused() {
    let d = dir("refine");
    let msh = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/cases/two_quads.msh");
    let out_file = d.join("fine.msh");
    let args = |n: &'static str| {
        [
            "mesh".as_ref(),
            "refine".as_ref(),
            msh.as_os_str(),
            out_file.as_os_str(),
            "--split".as_ref(),
            std::ffi::OsStr::new(n),
        ]
    };
    let (out, _) = tribo("10M", &args("16"));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("mesh refine --split 16 (about 1536 nodes, 594 cells) needs about")
            && err.contains("more than the 10 MB available"),
        "{err}"
    );
    assert!(!out_file.exists());
    let (out, _) = tribo("1G", &args("2"));
    assert_eq!(out.status.code(), Some(0));
    assert!(out_file.exists());
}
