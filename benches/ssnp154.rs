//! SSNP154 end-to-end timings (median of 5 runs each): every validation row (A–F and the
//! node-to-segment variants) with its own formulation, and A–D with mortar, on the
//! reference meshes (../shared/ssnp154, when present) and on the built-in meshes.
//!
//! Run: `cargo bench --bench ssnp154`

use std::path::Path;
use std::time::Instant;
use tribo::case::{self, ssnp154};

fn main() {
    // as the `tribo` command does
    tribo::cli::keep_freed_memory();
    tribo::cli::on_worker_thread(time_every_row);
}

fn time_every_row() {
    let shared = Path::new("../shared/ssnp154");
    let mut runs: Vec<(&str, Option<&str>)> = ssnp154::ROWS.iter().map(|r| (r.id, None)).collect();
    runs.extend(["A", "B", "C", "D"].map(|id| (id, Some("mortar"))));
    for (id, formulation) in runs {
        let reference = ssnp154::ROWS.iter().find(|r| r.id == id).unwrap().reference;
        let quadratic = ssnp154::REFERENCES
            .iter()
            .find(|r| r.0 == reference)
            .unwrap()
            .1;
        let mut sources = vec![("built-in", ssnp154::builtin_mesh(quadratic, 1.5))];
        if shared.exists() {
            let mut spec = ssnp154::builtin_mesh(quadratic, 1.5);
            spec.generator = None;
            // a mesh file takes no generator keys
            spec.size = None;
            spec.quadratic = false;
            let file = if quadratic {
                "ssnp154b.msh"
            } else {
                "ssnp154a.msh"
            };
            spec.file = Some(shared.join(file).display().to_string());
            sources.push(("reference", spec));
        }
        for (name, spec) in sources {
            let mut times = vec![];
            let mut iters = 0;
            let mut label = String::new();
            for _ in 0..5 {
                let t = Instant::now();
                let mesh = case::build_mesh(&spec, Path::new("")).unwrap();
                let c = ssnp154::contact_case(id, spec.clone(), formulation);
                let out = case::run(&c, &mesh, false).unwrap();
                times.push(t.elapsed().as_secs_f64());
                iters = out.report.total_iterations;
                label.clone_from(&c.contact[0].formulation);
            }
            times.sort_by(f64::total_cmp);
            println!(
                "{id:<6} {label:<17} {name:<10} median {:.3} s (min {:.3}), {iters} Newton iterations",
                times[2], times[0]
            );
        }
    }
}
