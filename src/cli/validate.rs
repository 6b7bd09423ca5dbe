//! `tribo validate [--meshes DIR] [--json FILE]`: the SSNP154 validation.
//!
//! Contact is not implemented yet, so this runs the elastic stage only: the benchmark's
//! bodies, supports and load with B and C glued in y (DY(B) = DY(C)), on the linear and
//! quadratic meshes, small kinematics. The values are printed beside the contact
//! references for orientation only; they are not expected to match them.

use crate::case::{self, ssnp154};
use crate::error::{write_atomic, Result};
use crate::fem::solid::Kinematics;
use serde_json::json;
use std::path::Path;
use std::time::Instant;

pub fn validate(meshes: Option<&Path>, json_out: Option<&Path>, verbose: bool) -> Result<i32> {
    println!("SSNP154 validation: ELASTIC STAGE ONLY (contact is not implemented yet).");
    println!("The bodies are glued at B-C (DY(B) = DY(C)); values are not compared with the contact references.\n");
    println!(
        "{:<6} {:<10} {:<8} {:>14} {:>14} {:>14} {:>14} {:>6} {:>8}",
        "mesh",
        "source",
        "kin.",
        "DY_B",
        "ref. DY_B (A/B)",
        "SIYY_B",
        "ref. SIYY_B",
        "iter",
        "time s"
    );
    let mut rows = vec![];
    for (quadratic, file, reference) in [(false, "ssnp154a.msh", 0usize), (true, "ssnp154b.msh", 1)]
    {
        let (spec, source) = match meshes {
            Some(dir) => {
                let mut spec = ssnp154::builtin_mesh(quadratic, 1.5);
                spec.generator = None;
                spec.file = Some(dir.join(file).display().to_string());
                (spec, file.to_string())
            }
            None => (
                ssnp154::builtin_mesh(quadratic, 1.5),
                "built-in".to_string(),
            ),
        };
        let mesh = case::build_mesh(&spec, Path::new(""))?;
        // Glued at one node pair, the load passes through a point: only small strain is
        // meaningful here (large kinematics buckles the singular point region).
        for kinematics in [Kinematics::Small] {
            let c = ssnp154::glued_case(spec.clone(), kinematics);
            let t0 = Instant::now();
            let out = case::run(&c, &mesh, verbose)?;
            let wall = t0.elapsed().as_secs_f64();
            let get = |n: &str| {
                out.probes
                    .iter()
                    .find(|p| p.0 == n)
                    .map(|p| p.1)
                    .unwrap_or(f64::NAN)
            };
            let (dy, siyy) = (get("DY_B"), get("SIYY_B"));
            let r = ssnp154::REFERENCES[reference];
            let kin = match kinematics {
                Kinematics::Small => "small",
                Kinematics::Large => "large",
            };
            let order = if quadratic { "quad." } else { "linear" };
            println!(
                "{:<6} {:<10} {:<8} {:>14.7} {:>14.7} {:>14.3} {:>14.3} {:>6} {:>8.3}",
                order, source, kin, dy, r.2, siyy, r.3, out.report.total_iterations, wall
            );
            rows.push(json!({
                "stage": "elastic_glued",
                "mesh": source, "quadratic": quadratic, "kinematics": kin,
                "DY_B": dy, "SIYY_B": siyy,
                "newton_iterations": out.report.total_iterations, "wall_s": wall,
            }));
        }
    }
    if let Some(p) = json_out {
        let doc = json!({"stage": "elastic_glued", "contact": false, "cases": rows});
        write_atomic(p, serde_json::to_string_pretty(&doc).unwrap().as_bytes())?;
    }
    Ok(0)
}
