//! Are two meshes the same? Nodes matched by coordinates (to a tolerance relative to the
//! bounding box), cells compared as node sets in a canonical order (corner cycle starting
//! at its smallest node, segments either way), groups compared as sets of matched nodes
//! and of canonical cells. Used by `tribo mesh compare` (MED against MSH, round trips).
//!
//! Cells of dimension 1 that belong to no group are not compared: Gmsh drops them when a
//! file has physical groups, MED keeps them, and no computation uses them. Point cells are
//! compared as the node sets of their groups only: a node group is point cells in Gmsh
//! and a node family in MED.

use super::{CellKind, Mesh};
use std::collections::{BTreeMap, BTreeSet};

pub struct Comparison {
    /// Differences found, each a sentence; empty when the meshes are the same.
    pub differences: Vec<String>,
    /// Largest coordinate distance between matched nodes.
    pub max_node_distance: f64,
    /// Whether node i of the first mesh is node i of the second.
    pub same_numbering: bool,
}

/// Canonical key of a cell: kind and its node list in a rotation/direction-free order.
type CellKey = (CellKind, Vec<usize>);

fn canonical(kind: CellKind, nodes: &[usize]) -> CellKey {
    let k = kind.num_corners();
    let mut v: Vec<usize> = nodes.to_vec();
    if kind.dim() == 2 {
        let r = (0..k).min_by_key(|&i| nodes[i]).unwrap_or(0);
        for i in 0..k {
            v[i] = nodes[(i + r) % k];
            if nodes.len() > k {
                v[k + i] = nodes[k + (i + r) % k];
            }
        }
    } else if kind.dim() == 1 && nodes[0] > nodes[1] {
        v.swap(0, 1);
    }
    (kind, v)
}

/// Node of `b` for each node of `a`, or None where no node lies within `tol`.
fn match_nodes(a: &Mesh, b: &Mesh, tol: f64) -> Vec<Option<usize>> {
    if a.num_nodes() == b.num_nodes()
        && a.coords
            .iter()
            .zip(&b.coords)
            .all(|(p, q)| dist(p, q) <= tol)
    {
        return (0..a.num_nodes()).map(Some).collect();
    }
    // Sort b by x; for each node of a, scan the x-window [x - tol, x + tol].
    let mut order: Vec<usize> = (0..b.num_nodes()).collect();
    order.sort_by(|&i, &j| b.coords[i][0].total_cmp(&b.coords[j][0]));
    let xs: Vec<f64> = order.iter().map(|&i| b.coords[i][0]).collect();
    a.coords
        .iter()
        .map(|p| {
            let start = xs.partition_point(|&x| x < p[0] - tol);
            let mut best: Option<(f64, usize)> = None;
            for (k, &x) in xs.iter().enumerate().skip(start) {
                if x > p[0] + tol {
                    break;
                }
                let d = dist(p, &b.coords[order[k]]);
                if d <= tol && best.is_none_or(|(bd, _)| d < bd) {
                    best = Some((d, order[k]));
                }
            }
            best.map(|(_, j)| j)
        })
        .collect()
}

fn dist(p: &[f64; 2], q: &[f64; 2]) -> f64 {
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt()
}

/// Cells worth comparing: every 2D cell, and grouped 1D ones.
fn compared_cells(m: &Mesh) -> Vec<usize> {
    let mut grouped = vec![false; m.num_cells()];
    for cells in m.cell_groups.values() {
        for &c in cells {
            grouped[c] = true;
        }
    }
    (0..m.num_cells())
        .filter(|&c| m.kind(c).dim() == 2 || (m.kind(c).dim() == 1 && grouped[c]))
        .collect()
}

/// Compares `a` with `b`; `rel_tol` is relative to the bounding-box diagonal of `a`.
pub fn compare(a: &Mesh, b: &Mesh, rel_tol: f64) -> Comparison {
    let mut diffs = vec![];
    let (lo, hi) = super::quality::bounding_box(a);
    let diag = dist(&lo, &hi).max(f64::MIN_POSITIVE);
    let tol = rel_tol * diag;
    if a.num_nodes() != b.num_nodes() {
        diffs.push(format!(
            "node counts differ: {} and {}",
            a.num_nodes(),
            b.num_nodes()
        ));
    }
    let map = match_nodes(a, b, tol);
    let unmatched = map.iter().filter(|m| m.is_none()).count();
    if unmatched > 0 {
        let first = map.iter().position(|m| m.is_none()).unwrap_or(0);
        diffs.push(format!(
            "{unmatched} nodes of the first mesh have no node of the second within {tol:.3e} \
             (first: node {} at ({}, {}))",
            first + 1,
            a.coords[first][0],
            a.coords[first][1]
        ));
    }
    let max_node_distance = map
        .iter()
        .enumerate()
        .filter_map(|(i, m)| m.map(|j| dist(&a.coords[i], &b.coords[j])))
        .fold(0.0, f64::max);
    let same_numbering = map.iter().enumerate().all(|(i, m)| *m == Some(i));
    let mapped = |n: usize| map[n].unwrap_or(usize::MAX);

    let key_a = |c: usize| {
        let nodes: Vec<usize> = a.cell_nodes(c).iter().map(|&n| mapped(n)).collect();
        canonical(a.kind(c), &nodes)
    };
    let key_b = |c: usize| canonical(b.kind(c), b.cell_nodes(c));
    let cells_a: BTreeSet<CellKey> = compared_cells(a).into_iter().map(key_a).collect();
    let cells_b: BTreeSet<CellKey> = compared_cells(b).into_iter().map(key_b).collect();
    let only_a = cells_a.difference(&cells_b).count();
    let only_b = cells_b.difference(&cells_a).count();
    if only_a + only_b > 0 {
        diffs.push(format!(
            "cells differ: {only_a} only in the first mesh, {only_b} only in the second"
        ));
    }

    let names_a: BTreeSet<String> = a.group_names().into_iter().collect();
    let names_b: BTreeSet<String> = b.group_names().into_iter().collect();
    for n in names_a.symmetric_difference(&names_b) {
        let which = if names_a.contains(n) {
            "first"
        } else {
            "second"
        };
        diffs.push(format!("group '{n}' is only in the {which} mesh"));
    }
    for name in names_a.intersection(&names_b) {
        let na: BTreeSet<usize> = a
            .node_group(name)
            .unwrap_or_default()
            .into_iter()
            .map(mapped)
            .collect();
        let nb: BTreeSet<usize> = b.node_group(name).unwrap_or_default().into_iter().collect();
        if na != nb {
            diffs.push(format!(
                "group '{name}': node sets differ ({} and {} nodes, {} in common)",
                na.len(),
                nb.len(),
                na.intersection(&nb).count()
            ));
        }
        let ca = group_cells(a, name, key_a);
        let cb = group_cells(b, name, key_b);
        // A node group may be point cells in one format and a plain node set in the
        // other: only groups of dimension >= 1 on both sides compare their cells.
        if !ca.is_empty() && !cb.is_empty() && ca != cb {
            diffs.push(format!(
                "group '{name}': cell sets differ ({} and {} cells)",
                ca.len(),
                cb.len()
            ));
        }
    }
    Comparison {
        differences: diffs,
        max_node_distance,
        same_numbering,
    }
}

fn group_cells(m: &Mesh, name: &str, key: impl Fn(usize) -> CellKey) -> BTreeSet<CellKey> {
    m.cell_groups
        .get(name)
        .map(|cells| {
            cells
                .iter()
                .filter(|&&c| m.kind(c).dim() >= 1)
                .map(|&c| key(c))
                .collect()
        })
        .unwrap_or_default()
}

/// Per kind counts of the compared cells, for the report.
pub fn compared_counts(m: &Mesh) -> BTreeMap<CellKind, usize> {
    let mut out = BTreeMap::new();
    for c in compared_cells(m) {
        *out.entry(m.kind(c)).or_insert(0) += 1;
    }
    out
}
