//! Gmsh MSH writers, ASCII: format 4.1 (entities carry the physical groups) and 2.2 (an
//! element in several groups is written once per group with the same number, as Gmsh
//! does). Explicit node groups become point elements in a physical group of dimension 0.
//! Cells in no group are written without physical group, so Gmsh (and our reader) drop
//! the 0D/1D ones as usual; 2D cells in no group are put in the group `ungrouped` so
//! that no body is lost.

use super::families::{cell_families, node_families};
use super::{CellKind, Mesh};
use crate::error::Result;
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::Path;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MshVersion {
    V41,
    V22,
}

pub fn write(path: &Path, mesh: &Mesh, version: MshVersion) -> Result<()> {
    crate::error::write_atomic(path, to_string(mesh, version).as_bytes())
}

fn gmsh_type(kind: CellKind) -> u8 {
    match kind {
        CellKind::Point1 => 15,
        CellKind::Seg2 => 1,
        CellKind::Seg3 => 8,
        CellKind::Tri3 => 2,
        CellKind::Tri6 => 9,
        CellKind::Quad4 => 3,
        CellKind::Quad8 => 16,
    }
}

pub const UNGROUPED: &str = super::DEFAULT_GROUP;

/// The element list: (dim, group-set index, kind, nodes) in write order.
struct Plan {
    /// Physical groups: (dim, name) → tag.
    physicals: BTreeMap<(usize, String), usize>,
    /// Group sets, index 0 = none.
    sets: Vec<Vec<String>>,
    /// (kind, nodes, set) per element; node groups as Point1 elements at the end.
    elements: Vec<(CellKind, Vec<usize>, usize)>,
}

fn plan(mesh: &Mesh) -> Plan {
    let cf = cell_families(mesh);
    let mut sets = cf.sets.clone();
    let ungrouped_2d = (0..mesh.num_cells()).any(|c| mesh.kind(c).dim() == 2 && cf.of[c] == 0);
    let ungrouped_set = if ungrouped_2d {
        sets.push(vec![UNGROUPED.to_string()]);
        sets.len() - 1
    } else {
        0
    };
    let mut elements: Vec<(CellKind, Vec<usize>, usize)> = (0..mesh.num_cells())
        .map(|c| {
            let mut set = cf.of[c];
            if set == 0 && mesh.kind(c).dim() == 2 {
                set = ungrouped_set;
            }
            (mesh.kind(c), mesh.cell_nodes(c).to_vec(), set)
        })
        .collect();
    let nf = node_families(mesh);
    let base = sets.len();
    sets.extend(nf.sets.iter().skip(1).cloned());
    for (n, &f) in nf.of.iter().enumerate() {
        if f > 0 {
            elements.push((CellKind::Point1, vec![n], base + f - 1));
        }
    }
    // Stable order: by dimension, then set, then original order.
    elements.sort_by_key(|e| (e.0.dim(), e.2));
    let mut physicals = BTreeMap::new();
    for e in &elements {
        for name in &sets[e.2] {
            let next = physicals.len() + 1;
            physicals.entry((e.0.dim(), name.clone())).or_insert(next);
        }
    }
    Plan {
        physicals,
        sets,
        elements,
    }
}

fn physical_names(p: &Plan, out: &mut String) {
    if p.physicals.is_empty() {
        return;
    }
    out.push_str("$PhysicalNames\n");
    let _ = writeln!(out, "{}", p.physicals.len());
    let mut by_tag: Vec<(&(usize, String), &usize)> = p.physicals.iter().collect();
    by_tag.sort_by_key(|x| *x.1);
    for ((dim, name), tag) in by_tag {
        let _ = writeln!(out, "{dim} {tag} \"{name}\"");
    }
    out.push_str("$EndPhysicalNames\n");
}

pub fn to_string(mesh: &Mesh, version: MshVersion) -> String {
    let p = plan(mesh);
    let mut out = String::with_capacity(64 * (mesh.num_nodes() + p.elements.len()));
    let v = if version == MshVersion::V41 {
        "4.1"
    } else {
        "2.2"
    };
    let _ = writeln!(out, "$MeshFormat\n{v} 0 8\n$EndMeshFormat");
    physical_names(&p, &mut out);
    match version {
        MshVersion::V41 => body41(mesh, &p, &mut out),
        MshVersion::V22 => body22(mesh, &p, &mut out),
    }
    out
}

fn body22(mesh: &Mesh, p: &Plan, out: &mut String) {
    let _ = writeln!(out, "$Nodes\n{}", mesh.num_nodes());
    for (i, x) in mesh.coords.iter().enumerate() {
        let _ = writeln!(out, "{} {:e} {:e} 0", i + 1, x[0], x[1]);
    }
    out.push_str("$EndNodes\n");
    let mut lines = String::new();
    let mut count = 0;
    for (tag, (kind, nodes, set)) in p.elements.iter().enumerate() {
        let dim = kind.dim();
        let names = &p.sets[*set];
        let physicals: Vec<usize> = if names.is_empty() {
            vec![0]
        } else {
            names
                .iter()
                .map(|n| p.physicals[&(dim, n.clone())])
                .collect()
        };
        for phys in physicals {
            let _ = write!(
                lines,
                "{} {} 2 {phys} {}",
                tag + 1,
                gmsh_type(*kind),
                set + 1
            );
            for n in nodes {
                let _ = write!(lines, " {}", n + 1);
            }
            lines.push('\n');
            count += 1;
        }
    }
    let _ = writeln!(out, "$Elements\n{count}");
    out.push_str(&lines);
    out.push_str("$EndElements\n");
}

fn body41(mesh: &Mesh, p: &Plan, out: &mut String) {
    // One entity per (dimension, group set); its tag is the set index + 1.
    let mut entities: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
    for (i, e) in p.elements.iter().enumerate() {
        entities.entry((e.0.dim(), e.2)).or_default().push(i);
    }
    let count_dim = |d: usize| entities.keys().filter(|k| k.0 == d).count();
    out.push_str("$Entities\n");
    let _ = writeln!(out, "{} {} {} 0", count_dim(0), count_dim(1), count_dim(2));
    for (&(dim, set), members) in &entities {
        let phys: Vec<usize> = p.sets[set]
            .iter()
            .map(|n| p.physicals[&(dim, n.clone())])
            .collect();
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for &i in members {
            for &n in &p.elements[i].1 {
                for d in 0..2 {
                    lo[d] = lo[d].min(mesh.coords[n][d]);
                    hi[d] = hi[d].max(mesh.coords[n][d]);
                }
            }
        }
        let tag = set + 1;
        if dim == 0 {
            let _ = write!(out, "{tag} {:e} {:e} 0 {}", lo[0], lo[1], phys.len());
        } else {
            let _ = write!(
                out,
                "{tag} {:e} {:e} 0 {:e} {:e} 0 {}",
                lo[0],
                lo[1],
                hi[0],
                hi[1],
                phys.len()
            );
        }
        for t in &phys {
            let _ = write!(out, " {t}");
        }
        out.push_str(if dim == 0 { "\n" } else { " 0\n" });
    }
    out.push_str("$EndEntities\n");
    // All nodes in one block, attached to the first entity of the highest dimension.
    let n = mesh.num_nodes();
    let (edim, etag) = entities
        .keys()
        .max_by_key(|k| (k.0, std::cmp::Reverse(k.1)))
        .map_or((2, 1), |&(d, s)| (d, s + 1));
    let _ = writeln!(out, "$Nodes\n1 {n} 1 {n}\n{edim} {etag} 0 {n}");
    for i in 0..n {
        let _ = writeln!(out, "{}", i + 1);
    }
    for x in &mesh.coords {
        let _ = writeln!(out, "{:e} {:e} 0", x[0], x[1]);
    }
    out.push_str("$EndNodes\n");
    // One element block per (entity, kind).
    let mut blocks: Vec<((usize, usize), CellKind, Vec<usize>)> = vec![];
    for (&key, members) in &entities {
        let mut by_kind: BTreeMap<CellKind, Vec<usize>> = BTreeMap::new();
        for &i in members {
            by_kind.entry(p.elements[i].0).or_default().push(i);
        }
        for (kind, list) in by_kind {
            blocks.push((key, kind, list));
        }
    }
    let ne = p.elements.len();
    let _ = writeln!(out, "$Elements\n{} {ne} 1 {ne}", blocks.len());
    for ((dim, set), kind, list) in &blocks {
        let _ = writeln!(out, "{dim} {} {} {}", set + 1, gmsh_type(*kind), list.len());
        for &i in list {
            let _ = write!(out, "{}", i + 1);
            for nd in &p.elements[i].1 {
                let _ = write!(out, " {}", nd + 1);
            }
            out.push('\n');
        }
    }
    out.push_str("$EndElements\n");
}
