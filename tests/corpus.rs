//! The malformed-case corpus (tests/corpus/, see its README): every case runs through the
//! library as `tribo run` would (load, mesh, solve); an `error` row must fail with its
//! message, an `ok` row must run, no case may panic. `todo` rows are known open defects
//! (accepted inputs that should not be): they are listed, and one that has started to fail
//! is reported so that its row can become `error`.

use rayon::prelude::*;
use std::path::{Path, PathBuf};
use tribo::case;

fn outcome(path: &Path) -> Result<(), String> {
    let (c, dir) = case::load(path).map_err(|e| e.to_string())?;
    let mesh = case::build_mesh(&c.mesh, &dir).map_err(|e| e.to_string())?;
    case::run(&c, &mesh, false)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

#[test]
fn every_corpus_case_gives_its_expected_outcome() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/corpus");
    let table = std::fs::read_to_string(root.join("expected.tsv")).unwrap();
    let rows: Vec<(String, String, String)> = table
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.splitn(3, '\t').collect();
            (
                f[0].to_string(),
                f[1].to_string(),
                f.get(2).unwrap_or(&"").to_string(),
            )
        })
        .collect();
    assert!(rows.len() >= 300, "{} cases", rows.len());
    let results: Vec<(usize, std::thread::Result<Result<(), String>>)> = rows
        .par_iter()
        .enumerate()
        .map(|(i, (file, _, _))| {
            let path = root.join("cases").join(file);
            (i, std::panic::catch_unwind(|| outcome(&path)))
        })
        .collect();
    let mut failures = vec![];
    let (mut todo_open, mut todo_refused) = (vec![], vec![]);
    for (i, res) in results {
        let (file, expect, detail) = &rows[i];
        match (expect.as_str(), res) {
            (_, Err(_)) => failures.push(format!("{file}: panicked")),
            ("error", Ok(Ok(()))) => failures.push(format!("{file}: accepted, expected an error")),
            ("error", Ok(Err(e))) if !e.contains(detail.as_str()) => {
                failures.push(format!("{file}: error '{e}' lacks '{detail}'"))
            }
            ("ok", Ok(Err(e))) => failures.push(format!("{file}: failed: {e}")),
            ("todo", Ok(Ok(()))) => todo_open.push(format!("{file}: {detail}")),
            ("todo", Ok(Err(e))) => todo_refused.push(format!("{file}: now refused: {e}")),
            _ => {}
        }
    }
    println!(
        "{} cases; open defects (todo rows still accepted): {}",
        rows.len(),
        todo_open.len()
    );
    for t in &todo_open {
        println!("  todo {t}");
    }
    for t in &todo_refused {
        println!("  {t}");
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
