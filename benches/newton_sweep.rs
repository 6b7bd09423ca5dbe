//! Newton's robustness over many meshes and load steppings (issue 23): the SSNP154 A and D
//! set-ups as `tribo validate` builds them, on built-in meshes of several contact cell
//! sizes, each in 1, 2 and 3 load steps; per run the Newton iterations, the step cuts and
//! whether it converged, and per set-up their totals.
//!
//! Why a sweep: the path of a semi-smooth Newton with many contact statuses is chaotic.
//! A change that only reorders a floating-point sum moves single runs by ±10–20 %
//! iterations (SSNP154 D with mortar at 82k unknowns: 43 or 48), so one mesh says little
//! about a change to the Newton method; the totals over a sweep, and its failures, do.
//!
//! Run: `cargo bench --bench newton_sweep [-- A] [D] [FORMULATION] [small] [STEPS...]`
//! (default: both set-ups, mortar, large kinematics, 1 2 3 steps; `small`: small
//! kinematics). About two minutes per set-up.

use std::time::Instant;
use tribo::case::{self, ssnp154};

/// Per set-up (quadratic cells or not) the contact cell sizes (mm) of the built-in meshes:
/// A (linear, frictionless) 6k to 200k unknowns, where its first load step starts to fail
/// (348k); D (quadratic, Coulomb 0.1) 20k to 90k.
const SETUPS: [(&str, bool, &[f64]); 2] = [
    ("A", false, &[0.3, 0.22, 0.16, 0.11, 0.0663, 0.047, 0.033]),
    ("D", true, &[0.3, 0.265, 0.22, 0.1875, 0.16, 0.1326, 0.11]),
];

struct Row {
    iterations: usize,
    /// numeric LDLᵀ factorisations
    factorizations: usize,
    seconds: f64,
    cuts: usize,
    converged: bool,
}

fn run(
    setup: &str,
    quadratic: bool,
    size: f64,
    formulation: &str,
    steps: usize,
    small: bool,
) -> Row {
    let spec = ssnp154::builtin_mesh(quadratic, size);
    let mesh = match case::build_mesh(&spec, std::path::Path::new("")) {
        Ok(m) => m,
        Err(e) => {
            println!("{setup} {size}: mesh failed: {e}");
            return Row {
                iterations: 0,
                factorizations: 0,
                seconds: 0.0,
                cuts: 0,
                converged: false,
            };
        }
    };
    let mut c = ssnp154::contact_case(setup, spec, Some(formulation));
    c.solver.steps = steps;
    if small {
        c.model.kinematics = tribo::fem::solid::Kinematics::Small;
    }
    let t = Instant::now();
    let outcome = case::run_keeping(&c, &mesh, false);
    let seconds = t.elapsed().as_secs_f64();
    let (report, probe, why) = match &outcome {
        Ok(o) => {
            let dy = o.probes.iter().find(|p| p.0 == "DY_B").map(|p| p.1);
            (Some(&o.report), dy, None)
        }
        Err(f) => (f.report.as_deref(), None, Some(f.error.to_string())),
    };
    let iterations = report.map_or(0, |r| r.total_iterations);
    let cuts = report.map_or(0, |r| r.steps.iter().filter(|s| !s.converged).count());
    let factorizations = report.map_or(0, |r| r.numeric_factorizations);
    println!(
        "| {setup} | {size} | {} | {steps} | {iterations} | {factorizations} | {cuts} | {seconds:.2} | {} |",
        mesh.num_nodes(),
        match (probe, &why) {
            (Some(dy), _) => format!("{dy:.7}"),
            (None, Some(w)) => format!("failed: {}", w.chars().take(60).collect::<String>()),
            _ => "-".into(),
        }
    );
    Row {
        iterations,
        factorizations,
        seconds,
        cuts,
        converged: why.is_none(),
    }
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    let setups: Vec<(&str, bool, &[f64])> = SETUPS
        .iter()
        .copied()
        .filter(|s| !args.iter().any(|a| a == "A" || a == "D") || args.iter().any(|a| a == s.0))
        .collect();
    let formulation = args
        .iter()
        .find(|a| a.contains('-') || *a == "mortar")
        .map_or("mortar", String::as_str);
    let small = args.iter().any(|a| a == "small");
    let mut steppings: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
    if steppings.is_empty() {
        steppings = vec![1, 2, 3];
    }
    let kinematics = if small { "small" } else { "large" };
    println!("Newton sweep, {formulation}, {kinematics} kinematics, load steps {steppings:?}\n");
    println!("| set-up | size mm | nodes | steps | Newton it. | LDLᵀ | cuts | s | DY_B |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---|");
    let mut totals = vec![];
    for &(setup, quadratic, sizes) in &setups {
        let (mut its, mut facts, mut cuts, mut failed, mut seconds) = (0, 0, 0, 0, 0.0);
        for &size in sizes {
            for &steps in &steppings {
                let row = run(setup, quadratic, size, formulation, steps, small);
                its += row.iterations;
                facts += row.factorizations;
                seconds += row.seconds;
                cuts += row.cuts;
                failed += usize::from(!row.converged);
            }
        }
        let runs = sizes.len() * steppings.len();
        totals.push((setup, its, facts, cuts, failed, runs, seconds));
    }
    println!();
    for (setup, its, facts, cuts, failed, runs, seconds) in totals {
        println!(
            "{setup}: {its} Newton iterations, {facts} LDLᵀ factorisations, {cuts} step cuts, \
             {failed} failed runs ({runs} runs, {seconds:.1} s)"
        );
    }
}
