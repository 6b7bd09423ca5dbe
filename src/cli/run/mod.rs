//! `tribo run CASE.toml [-o DIR] [-v]`
//!
//! | file | what |
//! |---|---|
//! | `staging.rs` | the output folder written whole in a temporary one, then swapped in |
//! | `signals.rs` | SIGINT / SIGTERM delete the temporary folder of a run in progress |
//! | `write.rs` | the files of an outcome and their results.json entries |
//! | `contact.rs` | per contact pair: results.json entries and history.csv columns |
//! | `rigid.rs` | per rigid surface: its reference point's motion and reaction |
//!
//! results.json has `"status": "converged"`, or `"failed"` with `"failure"` (the time of
//! the step that failed, the reason, the last converged time): a solve that fails after
//! some converged steps still writes the files of its last converged state and of its
//! converged output steps, and exits non-zero.

mod contact;
mod rigid;
pub mod signals;
mod staging;
mod write;

use crate::case::{self, Failure};
use crate::error::{write_atomic, Result};
use serde_json::json;
use staging::Staging;
use std::path::{Path, PathBuf};
use std::time::Instant;
use write::{outcome_files, Dir};

pub fn run(path: &Path, output: Option<&Path>, verbose: bool) -> Result<i32> {
    let t0 = Instant::now();
    let (case, dir) = case::load(path)?;
    let mesh = case::build_mesh(&case.mesh, &dir)?;
    let out_dir: PathBuf = match output {
        Some(o) => o.to_path_buf(),
        None => dir.join(path.file_stem().unwrap_or_default()),
    };
    // before the solve: a folder that cannot be written or replaced is known at once
    let staging = Staging::begin(&out_dir)?;
    let mut results = json!({
        "case": path.display().to_string(),
        "title": case.title,
        "mesh": {"nodes": mesh.num_nodes(), "cells": mesh.num_cells()},
        "modelisation": case.model.modelisation.name(),
    });
    let (outcome, failure) = match case::run_keeping(&case, &mesh, verbose) {
        Ok(o) => (Some(o), None),
        // an input error: nothing solved, the old results stay (`staging` is deleted)
        Err(Failure {
            error,
            report: None,
            ..
        }) => return Err(error),
        Err(f) => {
            let last = f.report.as_deref().and_then(last_time);
            results["status"] = json!("failed");
            results["failure"] = json!({
                "time": f.time,
                "reason": f.error.to_string(),
                "last_converged_time": last,
            });
            results["solver"] = json!(f.report);
            results["files"] = json!([]);
            (f.partial.map(|p| *p), Some(f.error))
        }
    };
    if failure.is_none() {
        results["status"] = json!("converged");
    }
    staging.commit(|temp| {
        let dir = Dir {
            write: temp,
            shown: &out_dir,
        };
        if let Some(o) = &outcome {
            let entries = outcome_files(&case, &mesh, o, &dir)?;
            if let (Some(all), Some(add)) = (results.as_object_mut(), entries.as_object()) {
                all.extend(add.clone());
            }
        }
        results["wall_s"] = json!(t0.elapsed().as_secs_f64());
        let text = serde_json::to_string_pretty(&results)
            .map_err(|e| crate::error::Error::model(format!("results.json: {e}")))?;
        write_atomic(&temp.join("results.json"), text.as_bytes())
    })?;
    if let Some(error) = failure {
        let kept = outcome.as_ref().map_or(0, |o| o.steps.len());
        eprintln!(
            "the run failed; results.json (\"status\": \"failed\") and the {kept} converged \
             output steps are in {}",
            out_dir.display()
        );
        return Err(error);
    }
    let Some(outcome) = outcome else {
        return Ok(0);
    };
    for (name, v) in &outcome.probes {
        println!("{name:<12} {v:.10e}");
    }
    println!(
        "converged in {} Newton iterations ({} load steps), {:.3} s; results in {}",
        outcome.report.total_iterations,
        outcome.report.steps.len(),
        t0.elapsed().as_secs_f64(),
        out_dir.display()
    );
    Ok(0)
}

/// The time of the last converged step of a report.
fn last_time(report: &crate::solver::newton::NewtonReport) -> Option<f64> {
    report
        .steps
        .iter()
        .rev()
        .find(|s| s.converged)
        .map(|s| s.time)
}
