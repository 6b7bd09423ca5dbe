//! `tribo validate --report DIR`: a self-contained `report.html` (inline SVG, no script)
//! with the validation table, and per modelisation the contact pressure against Hertz
//! (multipliers and extrapolated stresses), the shear against μ·p with the stick and slip
//! zones, the deformed contact region coloured by von Mises, and the Newton history; the
//! refinement study of `DIR/study.json` (`tribo study hertz --report DIR`; `validate --report`
//! runs a short one when there is none), or a note saying how to add it, and that of
//! `DIR/refine.json` (`tribo study refine CASE --report DIR`) when there is one. Every
//! plot is also a standalone SVG beside the page, with the plotted data as CSV.

use crate::case::{schema::CaseFile, Outcome};
use crate::error::{write_atomic, Result};
use crate::fem::material::von_mises;
use crate::mesh::Mesh;
use crate::post::contact_picture::{self, Picture};
use crate::post::contact_pressure::surface_tractions;
use crate::post::contact_state::{statuses, SLIP, STICK};
use crate::post::plot::{self, escape, sig, Band, Options, Series, Style};
use std::fmt::Write;
use std::path::Path;

use crate::case::ssnp154::{HERTZ_A as A, HERTZ_P0 as P0};
use crate::post::contact_pressure::hertz_pressure;

/// One checked value of the table.
pub struct Check {
    pub quantity: &'static str,
    pub value: f64,
    pub reference: f64,
    pub rel_error: f64,
    pub tolerance: f64,
    pub pass: bool,
}

/// What the report shows of one modelisation.
pub struct Row {
    pub id: String,
    pub setup: String,
    pub mesh_name: String,
    pub case: CaseFile,
    pub mesh: Mesh,
    pub outcome: Outcome,
    pub checks: Vec<Check>,
    pub wall: f64,
}

/// Writes a plot as DIR/NAME.svg and its data as DIR/NAME.csv (series,x,y); returns the SVG.
/// The CSV goes through the `csv` crate: labels hold commas ("stresses, slave"), which it
/// quotes as RFC 4180 readers expect.
pub fn plot_files(dir: &Path, name: &str, svg: String, series: &[Series]) -> Result<String> {
    write_atomic(&dir.join(format!("{name}.svg")), svg.as_bytes())?;
    let mut w = csv::Writer::from_writer(vec![]);
    let csv_error = |e: csv::Error| crate::error::Error::model(format!("{name}.csv: {e}"));
    w.write_record(["series", "x", "y"]).map_err(csv_error)?;
    for s in series {
        for &(x, y) in s.points {
            w.write_record([s.label, &x.to_string(), &y.to_string()])
                .map_err(csv_error)?;
        }
    }
    let bytes = w
        .into_inner()
        .map_err(|e| crate::error::Error::model(format!("{name}.csv: {e}")))?;
    write_atomic(&dir.join(format!("{name}.csv")), &bytes)?;
    Ok(svg)
}

/// x-ranges where consecutive slave nodes (sorted by x) have status `code`, split halfway
/// between nodes.
fn zones(nodes: &[(f64, i32)], code: i32) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = vec![];
    for (i, &(x, s)) in nodes.iter().enumerate() {
        if s != code {
            continue;
        }
        let left = if i > 0 { 0.5 * (nodes[i - 1].0 + x) } else { x };
        let right = if i + 1 < nodes.len() {
            0.5 * (x + nodes[i + 1].0)
        } else {
            x
        };
        match out.last_mut() {
            Some(last) if (last.1 - left).abs() < 1e-12 => last.1 = right,
            _ => out.push((left, right)),
        }
    }
    out
}

fn row_section(dir: &Path, row: &Row, html: &mut String) -> Result<()> {
    let (mesh, out) = (&row.mesh, &row.outcome);
    let id = &row.id;
    let f = &row.case.contact[0].formulation;
    let _ = writeln!(
        html,
        "<section><h2>{} — {}</h2><p>{} formulation, {} mesh, {} Newton iterations, {:.2} s.</p>",
        escape(id),
        escape(&row.setup),
        escape(f),
        escape(&row.mesh_name),
        out.report.total_iterations,
        row.wall
    );
    let xmax = 1.6 * A;
    // pressure: multipliers, stresses extrapolated to both surfaces, Hertz
    let mut mult: Vec<(f64, f64)> = out.contact_pressure[0]
        .iter()
        .map(|&(n, p)| (mesh.coords[n][0], p))
        .filter(|p| p.0 <= xmax)
        .collect();
    mult.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (slave, master) = &out.contact_surfaces[0];
    let extrapolated = |s| {
        let mut v: Vec<(f64, f64)> = surface_tractions(mesh, s, &out.stress, None)
            .into_iter()
            .map(|(n, p, _)| (mesh.coords[n][0], p))
            .filter(|p| p.0 <= xmax)
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    };
    let (ps, pm) = (extrapolated(slave), extrapolated(master));
    let curve: Vec<(f64, f64)> = (0..=200)
        .map(|k| {
            let x = xmax * k as f64 / 200.0;
            (x, hertz_pressure(A, P0, x))
        })
        .collect();
    let series = [
        Series {
            label: "Hertz",
            color: "#1f77b4",
            points: &curve,
            style: Style::Line,
        },
        Series {
            label: "stresses, slave (-n.sigma.n)",
            color: "#2ca02c",
            points: &ps,
            style: Style::Line,
        },
        Series {
            label: "stresses, master (-n.sigma.n)",
            color: "#9467bd",
            points: &pm,
            style: Style::Line,
        },
        Series {
            label: "multipliers",
            color: "#d62728",
            points: &mult,
            style: Style::Markers,
        },
    ];
    let svg = plot::svg_with(
        &format!("{id}: contact pressure"),
        "x, initial position (mm)",
        "pressure (MPa)",
        &series,
        &Options::default(),
    );
    let svg = plot_files(dir, &format!("{id}_pressure"), svg, &series)?;
    let _ = writeln!(html, "<figure>{svg}</figure>");

    // shear against μ p, with the stick and slip zones
    let (mu, shear) = out
        .contact_shear
        .first()
        .map_or((0.0, &[][..]), |s| (s.0, &s.1[..]));
    let status = statuses(&out.contact_pressure[0], shear, mu);
    if mu > 0.0 && !shear.is_empty() {
        let mut t: Vec<(f64, f64)> = shear
            .iter()
            .map(|&(n, v)| (mesh.coords[n][0], v.abs()))
            .filter(|p| p.0 <= xmax)
            .collect();
        t.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mup: Vec<(f64, f64)> = mult.iter().map(|&(x, p)| (x, mu * p)).collect();
        let mut by_x: Vec<(f64, i32)> = status
            .iter()
            .map(|&(n, s)| (mesh.coords[n][0], s))
            .filter(|p| p.0 <= xmax)
            .collect();
        by_x.sort_by(|a, b| a.0.total_cmp(&b.0));
        let series = [
            Series {
                label: "mu p (multipliers)",
                color: "#1f77b4",
                points: &mup,
                style: Style::Line,
            },
            Series {
                label: "|shear| (multipliers)",
                color: "#d62728",
                points: &t,
                style: Style::Markers,
            },
        ];
        let o = Options {
            bands: vec![
                Band {
                    label: "stick",
                    color: "#2ca02c",
                    ranges: zones(&by_x, STICK),
                },
                Band {
                    label: "slip",
                    color: "#ff7f0e",
                    ranges: zones(&by_x, SLIP),
                },
            ],
            ..Default::default()
        };
        let svg = plot::svg_with(
            &format!("{id}: shear traction, mu = {mu}"),
            "x, initial position (mm)",
            "traction (MPa)",
            &series,
            &o,
        );
        let svg = plot_files(dir, &format!("{id}_shear"), svg, &series)?;
        let _ = writeln!(html, "<figure>{svg}</figure>");
    }

    // the deformed contact region
    let vm: Vec<f64> = out.stress.iter().map(von_mises).collect();
    let pic = contact_picture::svg(&Picture {
        title: &format!("{id}: deformed contact region, von Mises"),
        mesh,
        u: &out.u,
        von_mises: &vm,
        window: [[0.0, 2.5 * A], [-1.5 * A, 1.5 * A]],
        status: &status,
    });
    write_atomic(&dir.join(format!("{id}_contact.svg")), pic.as_bytes())?;
    let _ = writeln!(html, "<figure>{pic}</figure>");

    // Newton history: relative residual per iteration, one curve per load step
    let mut steps: Vec<Vec<(f64, f64)>> = vec![];
    let mut k = 0.0;
    for s in &out.report.steps {
        let pts = s
            .iterations
            .iter()
            .map(|it| {
                k += 1.0;
                (k, it.relative_residual.max(1e-300))
            })
            .collect();
        steps.push(pts);
    }
    let colors = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"];
    let labels: Vec<String> = out
        .report
        .steps
        .iter()
        .map(|s| {
            format!(
                "step to {:.3}{}",
                s.time,
                if s.converged { "" } else { " (cut)" }
            )
        })
        .collect();
    let series: Vec<Series> = steps
        .iter()
        .zip(&labels)
        .enumerate()
        .map(|(i, (p, l))| Series {
            label: l,
            color: colors[i % colors.len()],
            points: p,
            style: Style::LineMarkers,
        })
        .collect();
    let o = Options {
        log_y: true,
        ..Default::default()
    };
    let svg = plot::svg_with(
        &format!("{id}: Newton convergence"),
        "iteration (all steps)",
        "relative residual",
        &series,
        &o,
    );
    let svg = plot_files(dir, &format!("{id}_newton"), svg, &series)?;
    let _ = writeln!(html, "<figure>{svg}</figure></section>");
    Ok(())
}

/// Log-log plots of a refinement study document (as `tribo study hertz` writes it), each
/// written as DIR/study_K.svg (+ .csv); returns (SVG, caption) per study.
pub fn study_plots(dir: &Path, doc: &serde_json::Value) -> Result<Vec<(String, String)>> {
    let mut out = vec![];
    let empty = vec![];
    for (k, st) in doc["studies"]
        .as_array()
        .unwrap_or(&empty)
        .iter()
        .enumerate()
    {
        let name = format!(
            "{} {} {} kinematics",
            st["formulation"].as_str().unwrap_or("?"),
            if st["quadratic"].as_bool() == Some(true) {
                "quadratic"
            } else {
                "linear"
            },
            st["kinematics"].as_str().unwrap_or("?")
        );
        let levels = st["levels"].as_array().unwrap_or(&empty);
        let get = |k: &str| -> Vec<(f64, f64)> {
            levels
                .iter()
                .map(|l| {
                    (
                        l["size_mm"].as_f64().unwrap_or(f64::NAN),
                        l[k].as_f64().unwrap_or(f64::NAN),
                    )
                })
                .collect()
        };
        let peak: Vec<(f64, f64)> = get("peak_MPa")
            .into_iter()
            .map(|(h, p)| (h, (p / P0 - 1.0).abs()))
            .collect();
        let half: Vec<(f64, f64)> = get("half_width_mm")
            .into_iter()
            .map(|(h, a)| (h, (a / A - 1.0).abs()))
            .collect();
        let l2 = get("l2_error");
        let profile_change: Vec<(f64, f64)> = get("profile_change_l2")
            .into_iter()
            .filter(|p| p.1.is_finite())
            .collect();
        let dy = get("dy_b_mm");
        let change: Vec<(f64, f64)> = dy
            .windows(2)
            .map(|w| (w[1].0, ((w[1].1 - w[0].1) / w[1].1).abs()))
            .collect();
        let series = [
            Series {
                label: "|peak/p0 - 1|",
                color: "#d62728",
                points: &peak,
                style: Style::LineMarkers,
            },
            Series {
                label: "|a_h/a - 1|",
                color: "#1f77b4",
                points: &half,
                style: Style::LineMarkers,
            },
            Series {
                label: "L2 error of the profile",
                color: "#2ca02c",
                points: &l2,
                style: Style::LineMarkers,
            },
            Series {
                label: "DY_B change from the coarser level",
                color: "#9467bd",
                points: &change,
                style: Style::LineMarkers,
            },
            Series {
                label: "profile change from the coarser level (L2)",
                color: "#ff7f0e",
                points: &profile_change,
                style: Style::LineMarkers,
            },
        ];
        let o = Options {
            log_x: true,
            log_y: true,
            ..Default::default()
        };
        let svg = plot::svg_with(
            &format!("refinement: {name}"),
            "element size at the contact h (mm)",
            "relative error",
            &series,
            &o,
        );
        let svg = plot_files(dir, &format!("study_{}", k + 1), svg, &series)?;
        let rates = &st["rates"];
        let rate = |v: &serde_json::Value| v.as_f64().map_or("-".into(), |r| format!("{r:.2}"));
        let caption = format!(
            "Observed rates (slope in log h) against Hertz: peak {}, half-width {}, L2 {}; \
             of the change between levels: peak {}, DY_B {}, pressure profile (L2) {}.",
            rate(&rates["error_vs_hertz"]["peak"]),
            rate(&rates["error_vs_hertz"]["half_width"]),
            rate(&rates["error_vs_hertz"]["l2"]),
            rate(&rates["change_between_levels"]["peak"]),
            rate(&rates["change_between_levels"]["dy_b"]),
            rate(&rates["change_between_levels"]["profile_l2"])
        );
        out.push((svg, caption));
    }
    Ok(out)
}

/// The refinement-study section (from DIR/study.json), or, when no study was run into DIR,
/// a section that says so and gives the command that adds it.
fn study_section(dir: &Path) -> Result<String> {
    let Ok(text) = std::fs::read_to_string(dir.join("study.json")) else {
        return Ok(format!(
            "<section><h2>Refinement study against Hertz</h2><p class=\"missing\">Not in this \
             report: no refinement study was run into this folder. To add it, run \
             <code>tribo study hertz --levels 3 --kinematics small --report {0}</code> (under a \
             second), then <code>tribo validate --report {0}</code> again.</p></section>",
            escape(&dir.display().to_string())
        ));
    };
    let doc: serde_json::Value = serde_json::from_str(&text).map_err(|e| {
        crate::error::Error::parse(dir.join("study.json").display().to_string(), e.to_string())
    })?;
    let mut html = String::from(
        "<section><h2>Refinement study against Hertz</h2><p>Hertz's solution is for two \
         half-spaces in small strain; the SSNP154 bodies are finite (a/R = 0.12) and, with large \
         kinematics, strained by several per cent at the contact, so the errors against Hertz level \
         off at what the model itself differs from Hertz, while the change between levels (the \
         discretisation error: of the pressure profile in L2, of DY_B) keeps falling at the \
         element's rate.</p>",
    );
    for (svg, caption) in study_plots(dir, &doc)? {
        let _ = writeln!(
            html,
            "<figure>{svg}<figcaption>{}</figcaption></figure>",
            escape(&caption)
        );
    }
    html.push_str("</section>");
    Ok(html)
}

/// The head of a report page (its style: text wraps, pictures shrink to the page width).
fn head(title: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>{}</title><style>\
         body{{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}}\
         table{{border-collapse:collapse}}td,th{{border:1px solid #bbb;padding:3px 8px;text-align:right}}\
         td.l,th.l{{text-align:left}}.pass{{color:#1a7f1a}}.fail{{color:#c00;font-weight:bold}}\
         figure{{margin:1em 0}}svg{{max-width:100%;height:auto}}\
         pre{{white-space:pre-wrap;overflow-wrap:anywhere}}code,td.l{{overflow-wrap:anywhere}}\
         .missing{{background:#fff6d5;padding:6px}}</style></head><body>\n",
        escape(title)
    )
}

/// A standalone page holding `body` (HTML).
pub fn page(title: &str, body: &str) -> String {
    format!(
        "{}<h1>{}</h1>\n{body}</body></html>\n",
        head(title),
        escape(title)
    )
}

/// The section of a `tribo study refine --report DIR` run into the same folder, if any.
fn refine_section(dir: &Path) -> Result<Option<String>> {
    let Ok(text) = std::fs::read_to_string(dir.join("refine.json")) else {
        return Ok(None);
    };
    let doc: serde_json::Value = serde_json::from_str(&text).map_err(|e| {
        crate::error::Error::parse(dir.join("refine.json").display().to_string(), e.to_string())
    })?;
    super::study_refine::section(dir, &doc).map(Some)
}

pub fn write(dir: &Path, rows: &[Row], source: &str, settings: &str) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| crate::error::Error::io(dir, e))?;
    let mut html = head("tribo: SSNP154 validation");
    let all_pass = rows.iter().all(|r| r.checks.iter().all(|c| c.pass));
    let _ = writeln!(
        html,
        "<h1>SSNP154 — NAFEMS contact benchmark 1 (cylinder roller contact)</h1>\
         <p>Validation by tribo {} on {}. Hertz: a = {A} mm, p0 = {P0} MPa. \
         Result: <b class=\"{}\">{}</b>.</p>",
        env!("CARGO_PKG_VERSION"),
        escape(source),
        if all_pass { "pass" } else { "fail" },
        if all_pass {
            "all values within tolerance"
        } else {
            "some values out of tolerance"
        }
    );
    html.push_str(
        "<table><tr><th class=\"l\">id</th><th class=\"l\">set-up</th><th class=\"l\">formulation</th>\
         <th class=\"l\">quantity</th><th>value</th><th>reference</th><th>error %</th><th>tolerance %</th>\
         <th>pass</th><th>Newton</th><th>time s</th></tr>\n",
    );
    for r in rows {
        for c in &r.checks {
            let _ = writeln!(
                html,
                "<tr><td class=\"l\">{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td>\
                 <td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"{}\">{}</td><td>{}</td><td>{:.2}</td></tr>",
                escape(&r.id),
                escape(&r.setup),
                escape(&r.case.contact[0].formulation),
                c.quantity,
                sig(c.value, 6),
                sig(c.reference, 6),
                sig(100.0 * c.rel_error, 2),
                sig(100.0 * c.tolerance, 2),
                if c.pass { "pass" } else { "fail" },
                if c.pass { "yes" } else { "NO" },
                r.outcome.report.total_iterations,
                r.wall
            );
        }
    }
    html.push_str("</table>\n");
    for r in rows {
        row_section(dir, r, &mut html)?;
    }
    html.push_str(&study_section(dir)?);
    if let Some(s) = refine_section(dir)? {
        html.push_str(&s);
    }
    let _ = writeln!(
        html,
        "<section><h2>Versions and settings</h2><pre>{}</pre></section></body></html>",
        escape(settings)
    );
    write_atomic(&dir.join("report.html"), html.as_bytes())
}
