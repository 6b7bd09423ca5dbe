//! The files of a run's outcome: result.vtu and the steps' series, curves, pressures,
//! tractions, history.csv, and the results.json entries that describe them.

use crate::case::schema::CaseFile;
use crate::case::Outcome;
use crate::error::{write_atomic, Result};
use crate::mesh::Mesh;
use crate::post::contact_pressure::surface_tractions;
use crate::post::plot;
use crate::post::probe::polar;
use crate::post::result_vtu::{write_series, write_state, Setting, State};
use serde_json::json;
use std::path::{Path, PathBuf};

/// Where the files are written (the temporary folder) and where they are listed (the
/// output folder they end up in).
pub struct Dir<'a> {
    pub write: &'a Path,
    pub shown: &'a Path,
}

impl Dir<'_> {
    /// The path to write `rel` at; its final name goes to `files`.
    pub fn file(&self, rel: &str, files: &mut Vec<String>) -> PathBuf {
        files.push(self.shown.join(rel).display().to_string());
        self.write.join(rel)
    }
    /// The final name of a written path.
    fn shown(&self, written: &Path) -> String {
        let rel = written.strip_prefix(self.write).unwrap_or(written);
        self.shown.join(rel).display().to_string()
    }
}

/// Writes the files of `outcome` in `dir`; returns the results.json entries: probes,
/// reactions, history, contact, solver, files (the caller adds the run's own).
pub fn outcome_files(
    case: &CaseFile,
    mesh: &Mesh,
    outcome: &Outcome,
    dir: &Dir,
) -> Result<serde_json::Value> {
    let mut files = vec![];
    if case.output.vtu {
        let materials = crate::post::results::material_groups(case);
        let setting = Setting {
            mesh,
            material_groups: &materials,
        };
        write_state(
            &dir.file("result.vtu", &mut files),
            &setting,
            &crate::post::results::final_state(outcome),
        )?;
        let states: Vec<(f64, State)> = outcome
            .steps
            .iter()
            .map(|s| {
                let st = State {
                    u: &s.u,
                    reactions: &s.reactions,
                    stress: &s.stress,
                    pk2: s.pk2.as_deref(),
                    contact: &s.contact,
                    multipliers: &s.contact_multipliers,
                };
                (s.time, st)
            })
            .collect();
        for f in write_series(&dir.write.join("steps"), "step", &setting, &states)? {
            files.push(dir.shown(&f));
        }
    }
    let large = outcome.pk2.is_some();
    let contact_at = crate::post::results::node_contact(outcome);
    for spec in &case.output.curve {
        let nodes = crate::post::curve::chain(mesh, &spec.group)?;
        let mut text = String::from("s,node,x,y,dx,dy,sixx,siyy,sizz,sixy,vmis");
        if large {
            text.push_str(",pk2xx,pk2yy,pk2zz,pk2xy");
        }
        if spec.center.is_some() {
            text.push_str(",sirr,sitt,sirt");
        }
        if !outcome.contact.is_empty() {
            text.push_str(",contact_pressure,contact_shear,contact_gap,contact_status");
        }
        text.push('\n');
        for (n, s) in nodes {
            let (x, st) = (mesh.coords[n], outcome.stress[n]);
            text.push_str(&format!(
                "{s},{},{},{},{},{},{},{},{},{},{}",
                n + 1,
                x[0],
                x[1],
                outcome.u[2 * n],
                outcome.u[2 * n + 1],
                st[0],
                st[1],
                st[2],
                st[3],
                crate::fem::material::von_mises(&st)
            ));
            if let Some(pk2) = &outcome.pk2 {
                let p = pk2[n];
                text.push_str(&format!(",{},{},{},{}", p[0], p[1], p[2], p[3]));
            }
            if let Some(c) = spec.center {
                // the frame at the node's position in the stress's configuration
                let at = if large {
                    [x[0] + outcome.u[2 * n], x[1] + outcome.u[2 * n + 1]]
                } else {
                    x
                };
                let p = polar(&st, at, c);
                text.push_str(&format!(",{},{},{}", p[0], p[1], p[2]));
            }
            if !outcome.contact.is_empty() {
                // off the slave surfaces a node has no contact values
                let v = contact_at.get(&n).map_or([f64::NAN; 4], |c| {
                    [c.pressure, c.shear, c.gap, c.status as f64]
                });
                text.push_str(&format!(",{},{},{},{}", v[0], v[1], v[2], v[3]));
            }
            text.push('\n');
        }
        write_atomic(
            &dir.file(&format!("curve_{}.csv", spec.name), &mut files),
            text.as_bytes(),
        )?;
    }
    let n_pairs = outcome.contact_pressure.len();
    for (i, pressures) in outcome.contact_pressure.iter().enumerate() {
        let stem = if n_pairs == 1 {
            "pressure".to_string()
        } else {
            format!("pressure_{}", i + 1)
        };
        let hertz = |x: f64| {
            case.output
                .hertz
                .as_ref()
                .map(|h| crate::post::contact_pressure::hertz_pressure(h.a, h.p0, x))
        };
        let mut rows: Vec<(f64, usize, f64)> = pressures
            .iter()
            .map(|&(n, p)| (mesh.coords[n][0], n, p))
            .collect();
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        let shear: std::collections::HashMap<usize, f64> = outcome
            .contact_shear
            .get(i)
            .map(|s| s.1.iter().copied().collect())
            .unwrap_or_default();
        let mut text = String::from("node,x,y,x_deformed,y_deformed,pressure,shear,hertz\n");
        for &(x, n, p) in &rows {
            let y = mesh.coords[n][1];
            let (ux, uy) = (outcome.u[2 * n], outcome.u[2 * n + 1]);
            let hz = hertz(x).map_or(String::new(), |v| v.to_string());
            let sh = shear.get(&n).map_or(String::new(), |v| v.to_string());
            text.push_str(&format!(
                "{},{x},{y},{},{},{p},{sh},{hz}\n",
                n + 1,
                x + ux,
                y + uy
            ));
        }
        write_atomic(
            &dir.file(&format!("{stem}.csv"), &mut files),
            text.as_bytes(),
        )?;
        let computed: Vec<(f64, f64)> = rows.iter().map(|r| (r.0, r.2)).collect();
        let pmax = computed.iter().fold(0.0f64, |m, p| m.max(p.1.abs()));
        let xmax = computed
            .iter()
            .filter(|p| p.1.abs() > 1e-6 * pmax)
            .map(|p| p.0)
            .fold(0.0, f64::max)
            * 1.3;
        let shown: Vec<(f64, f64)> = computed
            .into_iter()
            .filter(|p| p.0 <= xmax.max(1e-9))
            .collect();
        let curve: Vec<(f64, f64)> = match &case.output.hertz {
            Some(h) => (0..=200)
                .map(|k| {
                    let x = xmax.max(h.a) * k as f64 / 200.0;
                    (x, hertz(x).unwrap_or(0.0))
                })
                .collect(),
            None => vec![],
        };
        let mut series = vec![plot::Series {
            label: "multipliers (-lambda)",
            color: "#d62728",
            points: &shown,
            style: plot::Style::Markers,
        }];
        if !curve.is_empty() {
            series.insert(
                0,
                plot::Series {
                    label: "Hertz",
                    color: "#1f77b4",
                    points: &curve,
                    style: plot::Style::Line,
                },
            );
        }
        let svg = plot::svg(
            "Contact pressure",
            "x (initial position on the slave surface)",
            "pressure",
            &series,
        );
        write_atomic(
            &dir.file(&format!("{stem}.svg"), &mut files),
            svg.as_bytes(),
        )?;
    }
    // Tractions recovered from the nodal stresses on both surfaces, and per-pair figures.
    for (i, (slave, master)) in outcome.contact_surfaces.iter().enumerate() {
        let stem = if n_pairs == 1 {
            "tractions".to_string()
        } else {
            format!("tractions_{}", i + 1)
        };
        let mut text = String::from(
            "surface,node,x,y,pressure_initial,shear_initial,pressure_deformed,shear_deformed\n",
        );
        // (a rigid master has no stresses)
        let sides = [("slave", slave), ("master", master)];
        for (name, surf) in sides.into_iter().filter(|s| !s.1.is_rigid()) {
            let init = surface_tractions(mesh, surf, &outcome.stress, None);
            let def = surface_tractions(mesh, surf, &outcome.stress, Some(&outcome.u));
            let mut rows: Vec<_> = init.iter().zip(&def).collect();
            rows.sort_by(|a, b| mesh.coords[a.0 .0][0].total_cmp(&mesh.coords[b.0 .0][0]));
            for (&(n, p, t), &(_, pd, td)) in rows {
                let x = mesh.coords[n];
                text.push_str(&format!(
                    "{name},{},{},{},{p},{t},{pd},{td}\n",
                    n + 1,
                    x[0],
                    x[1]
                ));
            }
        }
        write_atomic(
            &dir.file(&format!("{stem}.csv"), &mut files),
            text.as_bytes(),
        )?;
    }
    let summary = crate::post::results::summary(case, mesh, outcome)?;
    if let Some(text) = &summary.history_csv {
        write_atomic(&dir.file("history.csv", &mut files), text.as_bytes())?;
    }
    let mut results = summary.json;
    results["files"] = json!(files);
    Ok(results)
}
