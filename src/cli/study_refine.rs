//! `tribo study refine CASE.toml --levels N [--report DIR]`: a mesh-refinement study of any
//! case. Level k has the element size h0 / 2^k: a generator's `size` halved (ssnp154,
//! disc_pair), its cell counts doubled (rectangle: nx, ny; ring: n_r, n_theta), or a mesh
//! file's every cell split 2^k × 2^k (`mesh::refine::split`, new nodes on the curved
//! quadratic edges). Per level: every probe and, per contact pair, its normal and tangential
//! resultants, contact length and peak pressure.
//!
//! From the last three levels (f1, f2, f3 at h, h/2, h/4) the observed order is
//! p = log2((f2 − f1) / (f3 − f2)), the Richardson-extrapolated value f3 + (f3 − f2) /
//! (2^p − 1) and its error estimate |extrapolated − f3| (the error left on the finest
//! level); changes of opposite sign (not yet in the asymptotic range) give no order.
//! DIR gets refine.json, refine.csv (level, h, quantity, value), one SVG + CSV plot per
//! quantity and refine.html; `validate --report DIR` shows the same section.

use crate::case::{self, schema::CaseFile};
use crate::error::{write_atomic, Error, Result};
use crate::mesh::Mesh;
use crate::post::plot::{self, escape, sig, Options, Series, Style};
use serde_json::json;
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

/// The observed order, extrapolated value and error estimate of one quantity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Richardson {
    pub order: f64,
    pub extrapolated: f64,
    pub error_estimate: f64,
}

/// Richardson analysis of the last three values of a sequence at h, h/2, h/4; None with
/// fewer than three, with a zero change, or with changes of opposite signs.
pub fn richardson(values: &[f64]) -> Option<Richardson> {
    let [f1, f2, f3] = values.get(values.len().checked_sub(3)?..)? else {
        return None;
    };
    let (d1, d2) = (f2 - f1, f3 - f2);
    // (NaN compares as no order)
    if (d1 * d2).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let order = (d1 / d2).log2();
    if order <= 0.0 {
        return None;
    }
    let extrapolated = f3 + d2 / (2f64.powf(order) - 1.0);
    Some(Richardson {
        order,
        extrapolated,
        error_estimate: (extrapolated - f3).abs(),
    })
}

/// The mesh of level k (element size h0 / 2^k) and a description of it.
fn level_mesh(case: &CaseFile, dir: &Path, base: Option<&Mesh>, k: usize) -> Result<Mesh> {
    let f = 1usize << k;
    if let Some(base) = base {
        return if k == 0 {
            Ok(base.clone())
        } else {
            crate::mesh::refine::split(base, f)
        };
    }
    let mut spec = case.mesh.clone();
    let g = spec.generator.clone().unwrap_or_default();
    let need = |v: Option<usize>, key: &str| {
        v.ok_or_else(|| {
            Error::model(format!(
                "study refine: [mesh] generator '{g}' needs '{key}' to be refined"
            ))
        })
    };
    match g.as_str() {
        "ssnp154" | "disc_pair" => {
            // (the ssnp154 generator's default size is 1.5 mm)
            let size = spec.size.unwrap_or(1.5);
            spec.size = Some(size / f as f64);
        }
        "rectangle" => {
            spec.nx = Some(need(spec.nx, "nx")? * f);
            spec.ny = Some(need(spec.ny, "ny")? * f);
        }
        "ring" => {
            spec.n_r = Some(need(spec.n_r, "n_r")? * f);
            spec.n_theta = Some(need(spec.n_theta, "n_theta")? * f);
        }
        _ => {}
    }
    case::build_mesh(&spec, dir)
}

/// The quantities of one solved level: probes, then per pair its resultants.
fn quantities(out: &case::Outcome) -> Vec<(String, f64)> {
    let mut q = out.probes.clone();
    for (i, p) in out.contact.iter().enumerate() {
        let s = &p.summary;
        let pair = format!("pair {}", i + 1);
        q.push((format!("{pair} normal force"), s.normal_resultant));
        q.push((format!("{pair} tangential force"), s.tangential_resultant));
        q.push((format!("{pair} contact length"), s.contact_length));
        q.push((format!("{pair} peak pressure"), s.peak_pressure));
    }
    q
}

pub fn refine(path: &Path, levels: usize, report: Option<&Path>) -> Result<i32> {
    if levels < 3 {
        return Err(Error::model(
            "study refine: --levels must be at least 3 (the observed order needs three levels)",
        ));
    }
    let (case, dir) = case::load(path)?;
    let base = match &case.mesh.file {
        Some(_) => Some(case::build_mesh(&case.mesh, &dir)?),
        None => None,
    };
    if base.is_some() && (1usize << (levels - 1)) > crate::mesh::refine::MAX_SPLIT {
        return Err(Error::model(format!(
            "study refine: a mesh file is split up to {0} x {0}: --levels is at most {1}",
            crate::mesh::refine::MAX_SPLIT,
            crate::mesh::refine::MAX_SPLIT.ilog2() + 1
        )));
    }
    let how = if base.is_some() {
        "every cell of the mesh file split 2^k x 2^k"
    } else {
        "the generator's element size halved per level"
    };
    crate::say!("refinement study of {} ({how})", path.display());
    let mut names: Vec<String> = vec![];
    let mut rows: Vec<serde_json::Value> = vec![];
    let mut values: Vec<Vec<f64>> = vec![];
    for k in 0..levels {
        let t0 = Instant::now();
        let mesh = level_mesh(&case, &dir, base.as_ref(), k)?;
        crate::progress::stage(&format!(
            "level {} of {levels}, h0/{}, {} nodes",
            k + 1,
            1usize << k,
            mesh.num_nodes()
        ));
        let out = case::run(&case, &mesh, false)
            .map_err(|e| Error::model(format!("study refine: level {k}: {e}")))?;
        let q = quantities(&out);
        if k == 0 {
            names = q.iter().map(|p| p.0.clone()).collect();
            if names.is_empty() {
                return Err(Error::model(
                    "study refine: the case has no [[output.probe]] and no contact pair: \
                     nothing to follow from level to level",
                ));
            }
            crate::say!(
                "{:>5} {:>8} {:>8} {}",
                "level",
                "h/h0",
                "nodes",
                names.iter().map(|n| format!("{n:>16}")).collect::<String>()
            );
        }
        let v: Vec<f64> = names
            .iter()
            .map(|n| q.iter().find(|p| &p.0 == n).map_or(f64::NAN, |p| p.1))
            .collect();
        let wall = t0.elapsed().as_secs_f64();
        crate::say!(
            "{k:>5} {:>8} {:>8} {}",
            format!("1/{}", 1usize << k),
            mesh.num_nodes(),
            v.iter().map(|x| format!("{x:>16.9e}")).collect::<String>()
        );
        rows.push(json!({
            "level": k, "h_relative": 1.0 / (1usize << k) as f64, "nodes": mesh.num_nodes(),
            "cells": mesh.num_cells(), "newton_iterations": out.report.total_iterations,
            "wall_s": wall,
        }));
        values.push(v);
    }
    let mut results = vec![];
    crate::say!(
        "\n{:<24} {:>8} {:>18} {:>14}",
        "quantity",
        "order",
        "extrapolated",
        "error estimate"
    );
    for (i, name) in names.iter().enumerate() {
        let seq: Vec<f64> = values.iter().map(|v| v[i]).collect();
        let r = richardson(&seq);
        crate::say!(
            "{name:<24} {:>8} {:>18} {:>14}",
            r.map_or("-".into(), |r| format!("{:.2}", r.order)),
            r.map_or("-".into(), |r| format!("{:.9e}", r.extrapolated)),
            r.map_or("-".into(), |r| format!("{:.2e}", r.error_estimate)),
        );
        // the order of every three consecutive levels: does it settle?
        let orders: Vec<Option<f64>> = (3..=seq.len())
            .map(|n| richardson(&seq[..n]).map(|r| r.order))
            .collect();
        results.push(json!({
            "quantity": name, "values": seq, "order": r.map(|r| r.order),
            "extrapolated": r.map(|r| r.extrapolated),
            "error_estimate": r.map(|r| r.error_estimate),
            "orders_of_consecutive_triples": orders,
        }));
    }
    let doc = json!({
        "case": path.display().to_string(),
        "refinement": how,
        "levels": rows,
        "quantities": results,
    });
    if let Some(dir) = report {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        let text = serde_json::to_string_pretty(&doc).expect("JSON of numbers");
        write_atomic(&dir.join("refine.json"), text.as_bytes())?;
        let mut csv = csv::Writer::from_writer(vec![]);
        let csv_error = |e: csv::Error| Error::model(format!("refine.csv: {e}"));
        csv.write_record(["level", "h_relative", "nodes", "quantity", "value"])
            .map_err(csv_error)?;
        for (k, v) in values.iter().enumerate() {
            for (name, x) in names.iter().zip(v) {
                csv.write_record([
                    k.to_string(),
                    (1.0 / (1usize << k) as f64).to_string(),
                    rows[k]["nodes"].to_string(),
                    name.clone(),
                    x.to_string(),
                ])
                .map_err(csv_error)?;
            }
        }
        let bytes = csv
            .into_inner()
            .map_err(|e| Error::model(format!("refine.csv: {e}")))?;
        write_atomic(&dir.join("refine.csv"), &bytes)?;
        let section = section(dir, &doc)?;
        let page = super::report::page(
            &format!("tribo: refinement study of {}", path.display()),
            &section,
        );
        write_atomic(&dir.join("refine.html"), page.as_bytes())?;
        crate::say!(
            "\nrefine.json, refine.csv, refine.html and a plot per quantity in {}",
            dir.display()
        );
    }
    Ok(0)
}

/// The report section of a study document (as `refine` writes it): the table of values,
/// orders and extrapolations, and per quantity a log-log plot of its change between levels
/// and of its distance to the extrapolated value against h (written as DIR/refine_K.svg
/// and .csv).
pub fn section(dir: &Path, doc: &serde_json::Value) -> Result<String> {
    let empty = vec![];
    let levels = doc["levels"].as_array().unwrap_or(&empty);
    let quantities = doc["quantities"].as_array().unwrap_or(&empty);
    let mut html = format!(
        "<section><h2>Refinement study of {}</h2><p>{}; {} levels. Observed order p = \
         log2((f2 − f1)/(f3 − f2)) from the last three levels, Richardson-extrapolated value \
         f3 + (f3 − f2)/(2^p − 1), and its error estimate |extrapolated − f3|.</p>\
         <table><tr><th class=\"l\">quantity</th>",
        escape(doc["case"].as_str().unwrap_or("?")),
        escape(doc["refinement"].as_str().unwrap_or("")),
        levels.len()
    );
    for l in levels {
        let _ = write!(
            html,
            "<th>h0/{} ({} nodes)</th>",
            1u64 << l["level"].as_u64().unwrap_or(0),
            l["nodes"]
        );
    }
    html.push_str("<th>order</th><th>extrapolated</th><th>error estimate</th></tr>\n");
    let num = |v: &serde_json::Value, d: usize| v.as_f64().map_or("-".into(), |x| sig(x, d));
    for q in quantities {
        let _ = write!(
            html,
            "<tr><td class=\"l\">{}</td>",
            escape(q["quantity"].as_str().unwrap_or("?"))
        );
        for v in q["values"].as_array().unwrap_or(&empty) {
            let _ = write!(html, "<td>{}</td>", num(v, 6));
        }
        let _ = writeln!(
            html,
            "<td>{}</td><td>{}</td><td>{}</td></tr>",
            q["order"]
                .as_f64()
                .map_or("-".into(), |p| format!("{p:.2}")),
            num(&q["extrapolated"], 6),
            num(&q["error_estimate"], 2)
        );
    }
    html.push_str("</table>\n");
    for (i, q) in quantities.iter().enumerate() {
        let name = q["quantity"].as_str().unwrap_or("?");
        let vals: Vec<f64> = q["values"]
            .as_array()
            .unwrap_or(&empty)
            .iter()
            .map(|v| v.as_f64().unwrap_or(f64::NAN))
            .collect();
        let h = |k: usize| 1.0 / (1u64 << k) as f64;
        let change: Vec<(f64, f64)> = vals
            .windows(2)
            .enumerate()
            .map(|(k, w)| (h(k + 1), (w[1] - w[0]).abs()))
            .collect();
        let to_ext: Vec<(f64, f64)> = match q["extrapolated"].as_f64() {
            Some(e) => vals
                .iter()
                .enumerate()
                .map(|(k, v)| (h(k), (v - e).abs()))
                .collect(),
            None => vec![],
        };
        let series = [
            Series {
                label: "|f_k - f_(k-1)|, change from the coarser level",
                color: "#d62728",
                points: &change,
                style: Style::LineMarkers,
            },
            Series {
                label: "|f_k - extrapolated|",
                color: "#1f77b4",
                points: &to_ext,
                style: Style::LineMarkers,
            },
        ];
        let o = Options {
            log_x: true,
            log_y: true,
            ..Default::default()
        };
        let title = match q["order"].as_f64() {
            Some(p) => format!("{name}: observed order {p:.2}"),
            None => format!("{name}: no observed order"),
        };
        let svg = plot::svg_with(&title, "h / h0", "difference", &series, &o);
        let svg = super::report::plot_files(dir, &format!("refine_{}", i + 1), svg, &series)?;
        let _ = writeln!(html, "<figure>{svg}</figure>");
    }
    html.push_str("</section>\n");
    Ok(html)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn richardson_recovers_the_order_and_limit_of_a_power_law() {
        // f(h) = 2 + 0.3 h^1.7 at h = 1, 1/2, 1/4, 1/8
        let f: Vec<f64> = (0..4)
            .map(|k| 2.0 + 0.3 * 0.5f64.powi(k).powf(1.7))
            .collect();
        let r = richardson(&f).unwrap();
        assert!((r.order - 1.7).abs() < 1e-12, "{r:?}");
        assert!((r.extrapolated - 2.0).abs() < 1e-12, "{r:?}");
        assert!((r.error_estimate - 0.3 * 0.125f64.powf(1.7)).abs() < 1e-12);
        // changes of opposite signs, or none, give no order
        assert_eq!(richardson(&[1.0, 2.0, 1.5]), None);
        assert_eq!(richardson(&[1.0, 1.0, 1.0]), None);
        assert_eq!(richardson(&[1.0, 2.0]), None);
    }
}
