//! The validation report and the refinement study, whole, in-process: `validate --report`
//! on the built-in meshes (all modelisations and variants; median and min of 3 runs) and
//! the default 5-level study (quadratic, mortar, small and large kinematics) and its
//! linear counterpart, once each.
//!
//! Run: `cargo bench --bench report`

use std::time::Instant;
use tribo::cli::{study, validate};
use tribo::fem::solid::Kinematics;

fn main() {
    // as the `tribo` command does
    tribo::cli::keep_freed_memory();
    tribo::cli::on_worker_thread(time_report_and_study);
}

fn time_report_and_study() {
    let dir = std::env::temp_dir().join(format!("tribo-bench-report-{}", std::process::id()));
    let mut t: Vec<f64> = (0..3)
        .map(|_| {
            let t0 = Instant::now();
            let code = validate::validate(None, None, None, None, Some(&dir), false).unwrap();
            assert_eq!(code, 0, "validation failed");
            t0.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    let mut lines = vec![format!(
        "validate --report (built-in meshes, every row): median {:.3} s (min {:.3})",
        t[1], t[0]
    )];
    for quadratic in [true, false] {
        let t0 = Instant::now();
        study::hertz(&study::Options {
            levels: 5,
            formulation: "mortar",
            quadratic,
            kinematics: vec![Kinematics::Small, Kinematics::Large],
            json: None,
            csv: None,
            svg_dir: Some(&dir),
        })
        .unwrap();
        lines.push(format!(
            "study hertz, 5 levels, {} mortar, small + large: {:.1} s",
            if quadratic { "quadratic" } else { "linear" },
            t0.elapsed().as_secs_f64()
        ));
    }
    println!();
    for l in lines {
        println!("{l}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
