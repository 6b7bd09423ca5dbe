//! `tribo mesh info FILE [--json]`

use crate::error::Result;
use crate::mesh::quality::{bounding_box, quality};
use serde_json::json;
use std::path::Path;

pub fn info(path: &Path, as_json: bool) -> Result<i32> {
    // A case file shows the mesh of its [mesh] table (a file or a built-in generator).
    let mesh = if path.extension().is_some_and(|e| e == "toml") {
        let (case, dir) = crate::case::load(path)?;
        crate::case::build_mesh(&case.mesh, &dir)?
    } else {
        crate::mesh::read(path)?
    };
    let counts = mesh.kind_counts();
    let (lo, hi) = bounding_box(&mesh);
    let q = quality(&mesh);
    let mut groups = serde_json::Map::new();
    for name in mesh.group_names() {
        let cells = mesh.cell_groups.get(&name).map_or(0, |c| c.len());
        let nodes = mesh.node_group(&name)?.len();
        groups.insert(
            name.clone(),
            json!({"dim": mesh.group_dim(&name).unwrap_or(0), "cells": cells, "nodes": nodes}),
        );
    }
    if as_json {
        let cells: serde_json::Map<String, serde_json::Value> = counts
            .iter()
            .map(|(k, v)| (k.name().to_string(), json!(v)))
            .collect();
        let out = json!({
            "nodes": mesh.num_nodes(),
            "cells": cells,
            "groups": groups,
            "reoriented": mesh.reoriented,
            "bounding_box": {"min": lo, "max": hi},
            "quality": q,
        });
        crate::say!("{}", serde_json::to_string_pretty(&out).unwrap());
        return Ok(0);
    }
    crate::say!("{}", path.display());
    crate::say!("  nodes        {}", mesh.num_nodes());
    for (k, v) in &counts {
        crate::say!("  {:<12} {}", k.name(), v);
    }
    crate::say!(
        "  bounding box [{:.6}, {:.6}] x [{:.6}, {:.6}]",
        lo[0],
        hi[0],
        lo[1],
        hi[1]
    );
    crate::say!(
        "  reoriented   {} cells (given clockwise, reordered counter-clockwise)",
        mesh.reoriented
    );
    if let Some(q) = q {
        crate::say!(
            "  quality      min angle {:.1} deg, max aspect ratio {:.2}",
            q.min_angle_deg,
            q.max_aspect_ratio
        );
    }
    crate::say!("  groups:");
    for (name, g) in &groups {
        crate::say!(
            "    {:<16} dim {}  cells {:>6}  nodes {:>6}",
            name,
            g["dim"],
            g["cells"],
            g["nodes"]
        );
    }
    Ok(0)
}

/// Output format of `tribo mesh convert`, from `--format` or the extension of OUT.
fn output_format(out: &Path, format: Option<&str>) -> Result<&'static str> {
    let ext = out
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    let f = match (format, ext.as_deref()) {
        (Some("msh41" | "msh"), _) | (None, Some("msh")) => "msh41",
        (Some("msh22"), _) => "msh22",
        (Some("med"), _) | (None, Some("med" | "mmed")) => "med",
        (Some("vtu"), _) | (None, Some("vtu")) => "vtu",
        (Some(other), _) => {
            return Err(crate::error::Error::model(format!(
                "mesh convert: --format '{other}' is not one of msh41, msh22, med, vtu"
            )))
        }
        (None, _) => {
            return Err(crate::error::Error::model(format!(
                "mesh convert: cannot tell the output format of '{}' from its extension \
                 (.msh, .med, .mmed, .vtu); give --format msh41|msh22|med|vtu",
                out.display()
            )))
        }
    };
    Ok(f)
}

/// `tribo mesh convert IN OUT [--format F]`
pub fn convert(input: &Path, output: &Path, format: Option<&str>) -> Result<i32> {
    let fmt = output_format(output, format)?;
    let mesh = crate::mesh::read(input)?;
    write(input, output, fmt, &mesh)
}

/// `tribo mesh refine IN OUT --split N [--format F]`
pub fn refine(input: &Path, output: &Path, split: usize, format: Option<&str>) -> Result<i32> {
    let fmt = output_format(output, format)?;
    let mesh = crate::mesh::read(input)?;
    let refined = crate::mesh::refine::split(&mesh, split)?;
    write(input, output, fmt, &refined)
}

/// Writes `mesh` (read from `input`) to `output` in format `fmt` and says what it wrote.
fn write(input: &Path, output: &Path, fmt: &str, mesh: &crate::mesh::Mesh) -> Result<i32> {
    use crate::mesh::gmsh_write::{self, MshVersion};
    match fmt {
        "msh41" => gmsh_write::write(output, mesh, MshVersion::V41)?,
        "msh22" => gmsh_write::write(output, mesh, MshVersion::V22)?,
        "med" => {
            let name = input.file_stem().and_then(|s| s.to_str()).unwrap_or("mesh");
            crate::mesh::med_write::write(output, mesh, name)?
        }
        _ => crate::post::vtu::write_mesh(output, mesh)?,
    }
    let groups = mesh.group_names().len();
    crate::say!(
        "{} -> {} ({fmt}): {} nodes, {} cells, {groups} groups",
        input.display(),
        output.display(),
        mesh.num_nodes(),
        mesh.num_cells()
    );
    if fmt.starts_with("msh")
        && (0..mesh.num_cells())
            .any(|c| mesh.kind(c).dim() == 2 && !mesh.cell_groups.values().any(|g| g.contains(&c)))
    {
        crate::say!(
            "note: 2D cells in no group were put in the group '{}' (Gmsh drops ungrouped cells)",
            crate::mesh::gmsh_write::UNGROUPED
        );
    }
    Ok(0)
}

/// `tribo mesh compare A B [--tol T]`: exit status 0 when the meshes are the same.
pub fn compare(a: &Path, b: &Path, tol: f64) -> Result<i32> {
    let ma = crate::mesh::read(a)?;
    let mb = crate::mesh::read(b)?;
    let c = crate::mesh::compare::compare(&ma, &mb, tol);
    let counts = |m: &crate::mesh::Mesh| -> String {
        crate::mesh::compare::compared_counts(m)
            .iter()
            .map(|(k, v)| format!("{v} {}", k.name()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    crate::say!("{}: {} nodes; {}", a.display(), ma.num_nodes(), counts(&ma));
    crate::say!("{}: {} nodes; {}", b.display(), mb.num_nodes(), counts(&mb));
    crate::say!("groups: {}", ma.group_names().join(", "));
    crate::say!(
        "largest node distance {:.3e} (tolerance {tol:e} of the bounding-box diagonal), numbering {}",
        c.max_node_distance,
        if c.same_numbering { "identical" } else { "different" }
    );
    if c.differences.is_empty() {
        crate::say!("same mesh");
        Ok(0)
    } else {
        for d in &c.differences {
            crate::say!("DIFFERENT: {d}");
        }
        Ok(1)
    }
}
