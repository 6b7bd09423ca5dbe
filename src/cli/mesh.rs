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
        println!("{}", serde_json::to_string_pretty(&out).unwrap());
        return Ok(0);
    }
    println!("{}", path.display());
    println!("  nodes        {}", mesh.num_nodes());
    for (k, v) in &counts {
        println!("  {:<12} {}", k.name(), v);
    }
    println!(
        "  bounding box [{:.6}, {:.6}] x [{:.6}, {:.6}]",
        lo[0], hi[0], lo[1], hi[1]
    );
    println!(
        "  reoriented   {} cells (given clockwise, reordered counter-clockwise)",
        mesh.reoriented
    );
    if let Some(q) = q {
        println!(
            "  quality      min angle {:.1} deg, max aspect ratio {:.2}",
            q.min_angle_deg, q.max_aspect_ratio
        );
    }
    println!("  groups:");
    for (name, g) in &groups {
        println!(
            "    {:<16} dim {}  cells {:>6}  nodes {:>6}",
            name, g["dim"], g["cells"], g["nodes"]
        );
    }
    Ok(0)
}
