//! `tribo study hertz`: mesh-refinement study of the SSNP154 geometry on built-in meshes
//! against the Hertz line-contact solution (a = 6.2146 mm, p0 = 3585.36 MPa).
//!
//! Each level halves the element size at the contact (3 mm at level 0). Per level: peak
//! pressure, half-width, relative L2 error of the pressure profile over [0, a], DY_B,
//! Newton iterations and time. Rates are fitted between successive levels: of the error
//! against Hertz (meaningful for small kinematics, which Hertz solves) and of the change
//! from the previous level (convergence to the discrete limit, also for large kinematics,
//! whose limit differs from Hertz by a few %). With large kinematics the profile is the
//! true pressure at the deformed abscissa.

use crate::case::{self, ssnp154};
use crate::error::{write_atomic, Error, Result};
use crate::fem::solid::Kinematics;
use crate::post::contact_pressure::{deformed_profile, half_width};
use serde_json::json;
use std::path::Path;
use std::time::Instant;

use crate::case::ssnp154::{HERTZ_A as A, HERTZ_P0 as P0};
use crate::post::contact_pressure::hertz_pressure;

/// One refinement level's results.
struct Level {
    size: f64,
    nodes: usize,
    slave: String,
    peak: f64,
    half_width: f64,
    l2: f64,
    /// relative L2 difference of the pressure profile from the previous (coarser) level
    profile_change: f64,
    samples: Vec<(f64, f64)>,
    dy_b: f64,
    iterations: usize,
    wall: f64,
}

pub struct Options<'a> {
    pub levels: usize,
    pub formulation: &'a str,
    pub quadratic: bool,
    pub kinematics: Vec<Kinematics>,
    pub json: Option<&'a Path>,
    pub csv: Option<&'a Path>,
    /// Folder for the log-log plots (study_K.svg).
    pub svg_dir: Option<&'a Path>,
}

pub fn hertz(opts: &Options) -> Result<i32> {
    if opts.levels < 2 {
        return Err(Error::model("study: --levels must be at least 2"));
    }
    let mut doc = vec![];
    let mut csv = String::from(
        "kinematics,level,size_mm,nodes,peak_MPa,half_width_mm,l2_error,dy_b_mm,newton_iterations,wall_s\n",
    );
    for &kin in &opts.kinematics {
        let kname = match kin {
            Kinematics::Small => "small",
            Kinematics::Large => "large",
        };
        crate::say!(
            "SSNP154 refinement study: {} cells, {}, {kname} kinematics (Hertz a = {A} mm, p0 = {P0} MPa)",
            if opts.quadratic { "quadratic" } else { "linear" },
            opts.formulation
        );
        crate::say!(
            "{:>5} {:>7} {:>7} {:>9} {:>10} {:>8} {:>9} {:>9} {:>10} {:>6} {:>7}",
            "level",
            "size",
            "nodes",
            "slave",
            "peak",
            "p/p0-1 %",
            "a_h",
            "a_h/a-1 %",
            "L2 err %",
            "iter",
            "time s"
        );
        let mut levels: Vec<Level> = vec![];
        for k in 0..opts.levels {
            let size = 3.0 / f64::powi(2.0, k as i32);
            let spec = ssnp154::builtin_mesh(opts.quadratic, size);
            let t0 = Instant::now();
            let mesh = case::build_mesh(&spec, Path::new(""))?;
            let id = if opts.quadratic { "B" } else { "A" };
            let mut c = ssnp154::contact_case(id, spec, Some(opts.formulation));
            c.model.kinematics = kin;
            crate::progress::stage(&format!(
                "{kname} kinematics, level {} of {}, h = {size} mm, {} nodes",
                k + 1,
                opts.levels,
                mesh.num_nodes()
            ));
            let out = case::run(&c, &mesh, false)?;
            let wall = t0.elapsed().as_secs_f64();
            // large kinematics: the true pressure at the deformed abscissa, as measured
            let samples: Vec<(f64, f64)> = match kin {
                Kinematics::Small => out.contact_pressure[0]
                    .iter()
                    .map(|&(n, p)| (mesh.coords[n][0].abs(), p))
                    .collect(),
                Kinematics::Large => deformed_profile(
                    &mesh,
                    &out.u,
                    &out.contact_pressure[0],
                    c.contact[0].formulation != "mortar",
                )
                .into_iter()
                .map(|(x, p)| (x.abs(), p))
                .collect(),
            };
            let peak = samples.iter().fold(0.0f64, |m, s| m.max(s.1));
            let level = Level {
                size,
                nodes: mesh.num_nodes(),
                slave: c.contact[0].slave.clone(),
                peak,
                half_width: half_width(&samples).unwrap_or(f64::NAN),
                l2: l2_error(&samples),
                profile_change: levels.last().map_or(f64::NAN, |prev: &Level| {
                    profile_change(&prev.samples, &samples)
                }),
                samples: samples.clone(),
                dy_b: out
                    .probes
                    .iter()
                    .find(|p| p.0 == "DY_B")
                    .map_or(f64::NAN, |p| p.1),
                iterations: out.report.total_iterations,
                wall,
            };
            crate::say!(
                "{k:>5} {size:>7.4} {:>7} {:>9} {:>10.2} {:>8.3} {:>9.4} {:>9.3} {:>10.3} {:>6} {:>7.2}",
                level.nodes,
                level.slave,
                level.peak,
                100.0 * (level.peak / P0 - 1.0),
                level.half_width,
                100.0 * (level.half_width / A - 1.0),
                100.0 * level.l2,
                level.iterations,
                level.wall
            );
            csv.push_str(&format!(
                "{kname},{k},{},{},{},{},{},{},{},{}\n",
                size,
                level.nodes,
                level.peak,
                level.half_width,
                level.l2,
                level.dy_b,
                level.iterations,
                level.wall
            ));
            levels.push(level);
        }
        // rates: against Hertz, and of the change between levels
        let err_peak: Vec<f64> = levels.iter().map(|l| (l.peak / P0 - 1.0).abs()).collect();
        let err_a: Vec<f64> = levels
            .iter()
            .map(|l| (l.half_width / A - 1.0).abs())
            .collect();
        let err_l2: Vec<f64> = levels.iter().map(|l| l.l2).collect();
        let change = |f: &dyn Fn(&Level) -> f64| -> Vec<f64> {
            levels
                .windows(2)
                .map(|w| (f(&w[1]) - f(&w[0])).abs())
                .collect()
        };
        let ch_peak = change(&|l| l.peak / P0);
        let ch_a = change(&|l| l.half_width / A);
        let ch_dy = change(&|l| l.dy_b);
        let ch_profile: Vec<f64> = levels.iter().skip(1).map(|l| l.profile_change).collect();
        let rates = json!({
            "error_vs_hertz": {
                "peak": fitted_rate(&err_peak),
                "half_width": fitted_rate(&err_a),
                "l2": fitted_rate(&err_l2),
            },
            "change_between_levels": {
                "peak": fitted_rate(&ch_peak),
                "half_width": fitted_rate(&ch_a),
                "dy_b": fitted_rate(&ch_dy),
                "profile_l2": fitted_rate(&ch_profile),
            },
        });
        crate::say!(
            "observed rates (least-squares slope in log h): against Hertz: peak {}, half-width {}, L2 {};\n  \
             of the change between levels: peak {}, half-width {}, DY_B {}, profile (L2) {}\n",
            show(fitted_rate(&err_peak)),
            show(fitted_rate(&err_a)),
            show(fitted_rate(&err_l2)),
            show(fitted_rate(&ch_peak)),
            show(fitted_rate(&ch_a)),
            show(fitted_rate(&ch_dy)),
            show(fitted_rate(&ch_profile)),
        );
        doc.push(json!({
            "kinematics": kname,
            "formulation": opts.formulation,
            "quadratic": opts.quadratic,
            "levels": levels.iter().map(|l| json!({
                "size_mm": l.size, "nodes": l.nodes, "slave": l.slave, "peak_MPa": l.peak,
                "half_width_mm": l.half_width, "l2_error": l.l2, "dy_b_mm": l.dy_b,
                "profile_change_l2": if l.profile_change.is_finite() { json!(l.profile_change) } else { json!(null) },
                "newton_iterations": l.iterations, "wall_s": l.wall,
            })).collect::<Vec<_>>(),
            "rates": rates,
        }));
    }
    let doc = json!({"hertz": {"a": A, "p0": P0}, "studies": doc});
    if let Some(p) = opts.json {
        let text = serde_json::to_string_pretty(&doc).expect("JSON of numbers");
        write_atomic(p, text.as_bytes())?;
    }
    if let Some(dir) = opts.svg_dir {
        let n = super::report::study_plots(dir, &doc)?.len();
        crate::say!("{n} log-log plots in {}", dir.display());
    }
    if let Some(p) = opts.csv {
        write_atomic(p, csv.as_bytes())?;
    }
    Ok(0)
}

fn show(r: Option<f64>) -> String {
    r.map_or("-".into(), |v| format!("{v:.2}"))
}

/// Sorted copy of a nodal profile, and its value at x (linear between nodes, constant
/// beyond the ends).
fn profile(samples: &[(f64, f64)]) -> impl Fn(f64) -> f64 {
    let mut s: Vec<(f64, f64)> = samples.to_vec();
    s.sort_by(|l, r| l.0.total_cmp(&r.0));
    move |x: f64| -> f64 {
        match s.iter().position(|p| p.0 >= x) {
            Some(0) => s[0].1,
            Some(i) => {
                let (x0, p0) = s[i - 1];
                let (x1, p1) = s[i];
                p0 + (p1 - p0) * (x - x0) / (x1 - x0)
            }
            None => s.last().map_or(f64::NAN, |p| p.1),
        }
    }
}

/// ‖f − g‖ / ‖g‖ in L2 over [0, end], by a fine trapezoid rule.
fn relative_l2(f: impl Fn(f64) -> f64, g: impl Fn(f64) -> f64, end: f64) -> f64 {
    let n = 4000;
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..=n {
        let x = end * i as f64 / n as f64;
        let w = if i == 0 || i == n { 0.5 } else { 1.0 };
        num += w * (f(x) - g(x)).powi(2);
        den += w * g(x).powi(2);
    }
    (num / den).sqrt()
}

/// Where a profile's loaded part ends (at least a), with a 5 % margin.
fn loaded_end(samples: &[(f64, f64)]) -> f64 {
    let pmax = samples.iter().fold(0.0f64, |m, p| m.max(p.1));
    samples
        .iter()
        .filter(|p| p.1 > 1e-3 * pmax)
        .map(|p| p.0)
        .fold(A, f64::max)
        * 1.05
}

/// Relative L2 error of a nodal pressure profile (x ≥ 0, linear between nodes) against
/// Hertz over [0, max(a, last loaded x)], by a fine trapezoid rule.
pub fn l2_error(samples: &[(f64, f64)]) -> f64 {
    if samples.len() < 2 {
        return f64::NAN;
    }
    let hertz = |x: f64| hertz_pressure(A, P0, x);
    relative_l2(profile(samples), hertz, loaded_end(samples))
}

/// Relative L2 difference between the profile of one level and that of the next finer
/// one (the discretisation error of the pressure, free of what the model itself differs
/// from Hertz).
pub fn profile_change(coarse: &[(f64, f64)], fine: &[(f64, f64)]) -> f64 {
    if coarse.len() < 2 || fine.len() < 2 {
        return f64::NAN;
    }
    let end = loaded_end(fine).max(loaded_end(coarse));
    relative_l2(profile(coarse), profile(fine), end)
}

/// Least-squares slope of log e against log h for levels h_k = h_0 / 2^k (the rate p in
/// e ~ h^p), over the entries above round-off; None with fewer than two.
pub fn fitted_rate(errors: &[f64]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = errors
        .iter()
        .enumerate()
        .filter(|(_, e)| **e > 1e-12 && e.is_finite())
        .map(|(k, e)| (-(k as f64) * 2f64.ln(), e.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
    let (mx, my) = (sx / n, sy / n);
    let (num, den) = pts.iter().fold((0.0, 0.0), |a, p| {
        (a.0 + (p.0 - mx) * (p.1 - my), a.1 + (p.0 - mx).powi(2))
    });
    Some(num / den)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profile_change_is_the_relative_l2_difference() {
        let fine: Vec<(f64, f64)> = (0..=40)
            .map(|k| {
                let x = 8.0 * k as f64 / 40.0;
                (x, hertz_pressure(A, P0, x))
            })
            .collect();
        assert_eq!(profile_change(&fine, &fine), 0.0);
        let scaled: Vec<(f64, f64)> = fine.iter().map(|&(x, p)| (x, 1.1 * p)).collect();
        assert!((profile_change(&scaled, &fine) - 0.1).abs() < 1e-12);
        // a coarser sampling of the same curve differs by its interpolation error only
        let coarse: Vec<(f64, f64)> = fine.iter().step_by(4).copied().collect();
        let d = profile_change(&coarse, &fine);
        assert!(d > 0.0 && d < 0.03, "{d}");
    }

    #[test]
    fn rate_of_a_power_law_is_its_exponent() {
        let e: Vec<f64> = (0..5).map(|k| 0.3 * 0.5f64.powi(k).powf(1.5)).collect();
        assert!((fitted_rate(&e).unwrap() - 1.5).abs() < 1e-12);
        assert_eq!(fitted_rate(&[0.1]), None);
    }

    #[test]
    fn hertz_sampled_at_nodes_has_a_small_l2_error_that_falls_with_spacing() {
        let profile = |h: f64| -> Vec<(f64, f64)> {
            let n = (2.0 * A / h).ceil() as usize;
            (0..=n)
                .map(|i| {
                    let x = i as f64 * h;
                    (x, hertz_pressure(A, P0, x))
                })
                .collect()
        };
        let (e1, e2) = (l2_error(&profile(0.5)), l2_error(&profile(0.25)));
        assert!(e1 < 0.05 && e2 < e1, "{e1} {e2}");
        // the exact profile has no error
        assert!(l2_error(&profile(1e-3)) < 1e-3);
    }
}
