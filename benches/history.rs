//! A 100-step load history on the SSNP154 linear reference mesh (issue target: under 3 s),
//! the whole `tribo run` (solve, per-step probes and reactions, 100 VTU files): the shipped
//! example (C set-up: point-to-segment, Coulomb 0.1, up to the full force and back to half)
//! and the same history on the frictionless A set-up (point-to-segment, Gauss), median of 3.
//! Also the shipped example on its built-in mesh.
//!
//! Run: `cargo bench --bench history`

use std::path::Path;
use std::time::Instant;

fn main() {
    // as the `tribo` command does
    tribo::cli::keep_freed_memory();
    tribo::cli::on_worker_thread(time_histories);
}

fn time_histories() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let example = std::fs::read_to_string(root.join("cases/examples/ssnp154_load_unload.toml"))
        .expect("the shipped example");
    let mesh_table = "generator = \"ssnp154\"\nquadratic = false\nsize = 1.5\n";
    let reference = root.join("../shared/ssnp154/ssnp154a.msh");
    let frictionless = example
        .replace("integration = \"nodal\"", "integration = \"gauss\"")
        .replace("friction = 0.1\n", "")
        .replace("rho_f = 100.0\n", "")
        .replace("friction_exclude = [\"C\"]\n", "");
    let mut runs = vec![("C history, built-in mesh", example.clone())];
    if reference.exists() {
        let file = format!("file = \"{}\"\n", reference.display());
        runs.push((
            "C history, ssnp154a.msh",
            example.replace(mesh_table, &file),
        ));
        runs.push((
            "A history, ssnp154a.msh",
            frictionless.replace(mesh_table, &file),
        ));
    }
    let dir = std::env::temp_dir().join(format!("tribo-bench-history-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in runs {
        let case = dir.join("case.toml");
        std::fs::write(&case, text).unwrap();
        let mut times = vec![];
        for _ in 0..3 {
            let t = Instant::now();
            tribo::cli::run::run(&case, Some(&dir.join("out")), false).unwrap();
            times.push(t.elapsed().as_secs_f64());
        }
        times.sort_by(f64::total_cmp);
        let results: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("out/results.json")).unwrap())
                .unwrap();
        let s = &results["solver"];
        println!(
            "{name:<26} median {:.3} s (min {:.3}); {} steps, {} Newton iterations, {} numeric LDLT; \
             evaluate {:.2} s, factor {:.2} s, solve {:.2} s",
            times[1],
            times[0],
            s["steps"].as_array().map_or(0, |v| v.len()),
            s["total_iterations"],
            s["numeric_factorizations"],
            s["time_evaluate_s"].as_f64().unwrap_or(0.0),
            s["time_factor_s"].as_f64().unwrap_or(0.0),
            s["time_solve_s"].as_f64().unwrap_or(0.0),
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
