//! The malformed-mesh corpus (tests/corpus/meshes/, see its README): every file goes
//! through `tribo mesh info FILE --json` in its own process, so that a panic, an abort or
//! a signal (a memory bomb) shows as such. An `error` row must exit with status 2 and an
//! error naming the file and holding the row's detail; an `ok` row must exit 0 with the
//! row's node and cell counts.

use rayon::prelude::*;
use std::path::PathBuf;
use std::process::Command;

fn check(root: &std::path::Path, file: &str, expect: &str, detail: &str) -> Option<String> {
    let path = root.join("files").join(file);
    let out = Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(["mesh", "info", "--json"])
        .arg(&path)
        .output()
        .expect("cannot run tribo");
    let stderr = String::from_utf8_lossy(&out.stderr);
    let Some(code) = out.status.code() else {
        return Some(format!(
            "{file}: killed by a signal ({:?}): {stderr}",
            out.status
        ));
    };
    match (expect, code) {
        (_, 101) => Some(format!("{file}: panicked: {stderr}")),
        ("error", 2) if !stderr.contains(detail) => Some(format!(
            "{file}: error '{}' lacks '{detail}'",
            stderr.trim()
        )),
        ("error", 2) if !stderr.contains(file) => Some(format!(
            "{file}: error '{}' does not name the file",
            stderr.trim()
        )),
        ("error", 2) => None,
        ("error", c) => Some(format!("{file}: exit status {c}, expected 2: {stderr}")),
        ("ok", 0) => {
            let Ok(v) = serde_json::from_slice::<serde_json::Value>(&out.stdout) else {
                return Some(format!("{file}: the output is not JSON"));
            };
            let nodes = v["nodes"].as_u64().unwrap_or(0);
            let cells: u64 = v["cells"]
                .as_object()
                .map_or(0, |m| m.values().filter_map(|c| c.as_u64()).sum());
            let got = format!("{nodes} nodes, {cells} cells");
            (got != detail).then(|| format!("{file}: read as {got}, expected {detail}"))
        }
        ("ok", c) => Some(format!("{file}: exit status {c}, expected 0: {stderr}")),
        (e, _) => Some(format!("{file}: unknown expectation '{e}'")),
    }
}

#[test]
fn every_corpus_mesh_gives_its_expected_outcome() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/meshes");
    let table = std::fs::read_to_string(root.join("expected.tsv")).unwrap();
    let rows: Vec<Vec<&str>> = table
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.splitn(3, '\t').collect())
        .collect();
    assert!(rows.len() >= 100, "{} meshes", rows.len());
    let errors = rows.iter().filter(|r| r[1] == "error").count();
    assert!(errors >= 100, "{errors} error rows");
    let failures: Vec<String> = rows
        .par_iter()
        .filter_map(|r| check(&root, r[0], r[1], r.get(2).copied().unwrap_or("")))
        .collect();
    println!("{} meshes ({errors} must be refused)", rows.len());
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
