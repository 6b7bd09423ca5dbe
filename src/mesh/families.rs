//! Families: entities (cells or nodes) partitioned by the set of groups they belong to.
//! MED stores groups this way, and a Gmsh entity carries one set of physical groups, so
//! both writers start from here.

use super::Mesh;
use std::collections::BTreeMap;

pub struct Families {
    /// Group-name sets; `sets[0]` is the empty set (entities in no group).
    pub sets: Vec<Vec<String>>,
    /// Index into `sets` for each entity.
    pub of: Vec<usize>,
}

fn partition(count: usize, groups: &BTreeMap<String, Vec<usize>>) -> Families {
    let mut member: Vec<Vec<String>> = vec![vec![]; count];
    for (name, items) in groups {
        for &i in items {
            member[i].push(name.clone());
        }
    }
    let mut index: BTreeMap<Vec<String>, usize> = BTreeMap::new();
    let mut sets = vec![vec![]];
    index.insert(vec![], 0);
    let of = member
        .into_iter()
        .map(|m| {
            *index.entry(m.clone()).or_insert_with(|| {
                sets.push(m);
                sets.len() - 1
            })
        })
        .collect();
    Families { sets, of }
}

/// Families of the cells, from the cell groups.
pub fn cell_families(mesh: &Mesh) -> Families {
    partition(mesh.num_cells(), &mesh.cell_groups)
}

/// Families of the nodes, from the explicit node groups.
pub fn node_families(mesh: &Mesh) -> Families {
    partition(mesh.num_nodes(), &mesh.node_groups)
}
