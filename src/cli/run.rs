//! `tribo run CASE.toml [-o DIR] [-v]`

use crate::case;
use crate::error::{write_atomic, Result};
use crate::fem::material::von_mises;
use crate::mesh::Mesh;
use crate::post::vtu::{self, Field};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub fn run(path: &Path, output: Option<&Path>, verbose: bool) -> Result<i32> {
    let t0 = Instant::now();
    let (case, dir) = case::load(path)?;
    let mesh = case::build_mesh(&case.mesh, &dir)?;
    let outcome = case::run(&case, &mesh, verbose)?;
    let out_dir: PathBuf = match output {
        Some(o) => o.to_path_buf(),
        None => dir.join(path.file_stem().unwrap_or_default()),
    };
    let mut files = vec![];
    if case.output.vtu {
        let f = out_dir.join("result.vtu");
        write_vtu(&f, &mesh, &outcome)?;
        files.push(f.display().to_string());
    }
    for (i, pressures) in outcome.contact_pressure.iter().enumerate() {
        let f = out_dir.join(format!("pressure_{}.csv", i + 1));
        let mut rows: Vec<(f64, String)> = pressures
            .iter()
            .map(|&(n, p)| {
                let x = mesh.coords[n];
                let (ux, uy) = (outcome.u[2 * n], outcome.u[2 * n + 1]);
                (
                    x[0],
                    format!(
                        "{},{},{},{},{},{}\n",
                        n + 1,
                        x[0],
                        x[1],
                        x[0] + ux,
                        x[1] + uy,
                        p
                    ),
                )
            })
            .collect();
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut text = String::from("node,x,y,x_deformed,y_deformed,pressure\n");
        for (_, r) in rows {
            text.push_str(&r);
        }
        write_atomic(&f, text.as_bytes())?;
        files.push(f.display().to_string());
    }
    let wall = t0.elapsed().as_secs_f64();
    let mut probes = serde_json::Map::new();
    for (name, v) in &outcome.probes {
        probes.insert(name.clone(), json!(v));
    }
    let mut reactions = serde_json::Map::new();
    for spec in &case.displacement {
        let nodes = mesh.node_group(&spec.group)?;
        let (rx, ry) = nodes.iter().fold((0.0, 0.0), |(a, b), &n| {
            (
                a + outcome.reactions[2 * n],
                b + outcome.reactions[2 * n + 1],
            )
        });
        reactions.insert(spec.group.clone(), json!({"rx": rx, "ry": ry}));
    }
    let results = json!({
        "case": path.display().to_string(),
        "title": case.title,
        "mesh": {"nodes": mesh.num_nodes(), "cells": mesh.num_cells()},
        "modelisation": case.model.modelisation.name(),
        "probes": probes,
        "reactions": reactions,
        "solver": outcome.report,
        "files": files,
        "wall_s": wall,
    });
    let rpath = out_dir.join("results.json");
    write_atomic(
        &rpath,
        serde_json::to_string_pretty(&results).unwrap().as_bytes(),
    )?;
    for (name, v) in &outcome.probes {
        println!("{name:<12} {v:.10e}");
    }
    println!(
        "converged in {} Newton iterations ({} load steps), {:.3} s; results in {}",
        outcome.report.total_iterations,
        outcome.report.steps.len(),
        wall,
        out_dir.display()
    );
    Ok(0)
}

pub fn write_vtu(path: &Path, mesh: &Mesh, outcome: &case::Outcome) -> Result<()> {
    let cells: Vec<usize> = mesh.cells_of_dim(2).collect();
    let disp: Vec<f64> = outcome
        .u
        .chunks(2)
        .flat_map(|d| [d[0], d[1], 0.0])
        .collect();
    // Symmetric tensor as ParaView expects: XX, YY, ZZ, XY, YZ, XZ.
    let sig: Vec<f64> = outcome
        .stress
        .iter()
        .flat_map(|s| [s[0], s[1], s[2], s[3], 0.0, 0.0])
        .collect();
    let vm: Vec<f64> = outcome.stress.iter().map(von_mises).collect();
    let react: Vec<f64> = outcome
        .reactions
        .chunks(2)
        .flat_map(|d| [d[0], d[1], 0.0])
        .collect();
    let mut group_fields = vec![];
    for (name, members) in &mesh.cell_groups {
        if mesh.group_dim(name) != Some(2) {
            continue;
        }
        let mut flag = vec![0i32; mesh.num_cells()];
        for &c in members {
            flag[c] = 1;
        }
        let vals: Vec<i32> = cells.iter().map(|&c| flag[c]).collect();
        group_fields.push((format!("group_{name}"), vals));
    }
    let mut fields = vec![
        Field::Point {
            name: "displacement",
            ncomp: 3,
            values: &disp,
            components: &["DX", "DY", "DZ"],
        },
        Field::Point {
            name: "stress",
            ncomp: 6,
            values: &sig,
            components: &["SIXX", "SIYY", "SIZZ", "SIXY", "SIYZ", "SIXZ"],
        },
        Field::Point {
            name: "von_mises",
            ncomp: 1,
            values: &vm,
            components: &[],
        },
        Field::Point {
            name: "reaction",
            ncomp: 3,
            values: &react,
            components: &["RX", "RY", "RZ"],
        },
    ];
    for (name, vals) in &group_fields {
        fields.push(Field::CellInt { name, values: vals });
    }
    vtu::write(path, mesh, &cells, &fields)
}
