//! Nodal fields along an edge group, ordered by arc length (initial geometry): the group's
//! 1D cells must form one open or closed chain; mid-side nodes come between their corners.

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use std::collections::HashMap;

/// (node, arc length from the chain's start) along the edge group, from the end with the
/// smaller (x, y) for an open chain.
pub fn chain(mesh: &Mesh, group: &str) -> Result<Vec<(usize, f64)>> {
    let cells = mesh
        .cell_group(group)
        .map_err(|e| Error::model(format!("curve: {e}")))?;
    let edges: Vec<usize> = cells
        .iter()
        .copied()
        .filter(|&c| mesh.kind(c).dim() == 1)
        .collect();
    if edges.is_empty() {
        return Err(Error::model(format!(
            "curve: group '{group}' holds no edge (Seg2/Seg3) cells"
        )));
    }
    // corner → edges at it
    let mut at: HashMap<usize, Vec<usize>> = HashMap::new();
    for &e in &edges {
        for &n in &mesh.cell_nodes(e)[..2] {
            at.entry(n).or_default().push(e);
        }
    }
    if at.values().any(|v| v.len() > 2) {
        return Err(Error::model(format!(
            "curve: group '{group}' branches (a node joins more than two edges)"
        )));
    }
    let ends: Vec<usize> = at
        .iter()
        .filter(|(_, v)| v.len() == 1)
        .map(|(&n, _)| n)
        .collect();
    let key = |n: usize| (mesh.coords[n][0], mesh.coords[n][1]);
    let start = match ends.len() {
        0 => *at
            .keys()
            .min_by(|&&a, &&b| key(a).partial_cmp(&key(b)).unwrap())
            .unwrap(),
        2 => *ends
            .iter()
            .min_by(|&&a, &&b| key(a).partial_cmp(&key(b)).unwrap())
            .unwrap(),
        _ => {
            return Err(Error::model(format!(
                "curve: group '{group}' is not one chain of edges ({} loose ends)",
                ends.len()
            )))
        }
    };
    let dist = |a: usize, b: usize| {
        (mesh.coords[a][0] - mesh.coords[b][0]).hypot(mesh.coords[a][1] - mesh.coords[b][1])
    };
    let mut out = vec![(start, 0.0)];
    let mut used = vec![];
    let (mut node, mut s) = (start, 0.0);
    while let Some(&e) = at[&node].iter().find(|e| !used.contains(*e)) {
        used.push(e);
        let n = mesh.cell_nodes(e);
        let next = if n[0] == node { n[1] } else { n[0] };
        let mut prev = node;
        for &m in &n[2..] {
            s += dist(prev, m);
            out.push((m, s));
            prev = m;
        }
        s += dist(prev, next);
        if next != start {
            out.push((next, s));
        }
        node = next;
        if node == start {
            break;
        }
    }
    if used.len() != edges.len() {
        return Err(Error::model(format!(
            "curve: group '{group}' is not one chain of edges ({} of {} edges reached)",
            used.len(),
            edges.len()
        )));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::{rectangle, ring};
    use crate::mesh::CellKind;

    #[test]
    fn chains_follow_the_edges_by_arc_length() {
        let m = rectangle([0.0, 0.0], 2.0, 1.0, 4, 2, CellKind::Quad8, 0.0).unwrap();
        let c = chain(&m, "Bottom").unwrap();
        assert_eq!(c.len(), 9);
        for (k, &(n, s)) in c.iter().enumerate() {
            assert!((s - 0.25 * k as f64).abs() < 1e-12);
            assert!((m.coords[n][0] - s).abs() < 1e-12 && m.coords[n][1] == 0.0);
        }
        let r = ring(1.0, 2.0, 2, 12, 90.0, CellKind::Quad4).unwrap();
        let c = chain(&r, "Outer").unwrap();
        assert_eq!(c.len(), 13);
        // chords of a quarter circle of radius 2
        let chord = 2.0 * 2.0 * (std::f64::consts::PI / 48.0).sin();
        assert!((c[12].1 - 12.0 * chord).abs() < 1e-12);
        let e = chain(&m, "Body").unwrap_err().to_string();
        assert_eq!(e, "curve: group 'Body' holds no edge (Seg2/Seg3) cells");
    }
}
