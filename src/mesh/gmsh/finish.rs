//! After the last section: whole-file checks (z = 0, physical names) and the mesh, each
//! element in the cell groups of its physical groups.

use super::{Mesh, Parser, Version};
use crate::error::{Error, Result};
use std::collections::HashMap;

impl<'a> Parser<'a> {
    // ---------------------------------------------------------------- the mesh

    pub(super) fn finish(self) -> Result<Mesh> {
        if !self.has_nodes {
            return Err(self.file_err("no $Nodes section"));
        }
        if !self.has_elements {
            return Err(self.file_err("no $Elements section"));
        }
        if let Some((z, tag, p)) = self.zmax {
            let diag = (0..3)
                .map(|d| (self.hi[d] - self.lo[d]).powi(2))
                .sum::<f64>()
                .sqrt();
            if z.abs() > 1e-12 * diag {
                return Err(self.err(
                    p,
                    format!(
                        "node {tag} has z = {z}: 3D meshes are not supported \
                         (all nodes must lie in the plane z = 0)"
                    ),
                ));
            }
        }
        let v41 = self.version == Version::V41;
        if v41 && self.entities.is_none() && !self.names.is_empty() {
            return Err(self.file_err(
                "$PhysicalNames but no $Entities section: \
                 the physical groups of the elements are unknown",
            ));
        }
        let has_physicals = !self.names.is_empty()
            || self
                .entities
                .as_ref()
                .is_some_and(|m| m.values().any(|p| !p.is_empty()))
            || (!v41 && self.blocks.iter().any(|b| b.key != 0));

        let Parser {
            source,
            mut builder,
            names,
            entities,
            conn,
            labels,
            blocks,
            ..
        } = self;
        let entities = entities.unwrap_or_default();
        let mut groups: Vec<&str> = Vec::new();
        let mut seen: HashMap<u64, usize> = HashMap::new();
        for b in &blocks {
            let physical: &[i64] = if v41 {
                entities.get(&(b.dim, b.key)).map_or(&[], |p| p.as_slice())
            } else if b.key != 0 {
                std::slice::from_ref(&b.key)
            } else {
                &[]
            };
            if physical.is_empty() && has_physicals {
                continue;
            }
            groups.clear();
            for &t in physical {
                match names.get(&(b.dim, t)) {
                    Some(name) => groups.push(name),
                    None => {
                        return Err(Error::parse(
                            source,
                            format!(
                                "physical group {t} (dim {}) of element {} has no name \
                                 in $PhysicalNames",
                                b.dim, labels[b.label_start]
                            ),
                        ))
                    }
                }
            }
            let n = b.kind.num_nodes();
            for i in 0..b.count {
                let s = b.conn_start + i * n;
                let label = labels[b.label_start + i];
                // MSH 2.2 repeats an element once per physical group, with one number.
                let c = match seen.get(&label) {
                    Some(&c) if !v41 => {
                        if builder.cell(c) != (b.kind, &conn[s..s + n]) {
                            return Err(Error::parse(
                                source,
                                format!("element {label} is defined twice with different nodes"),
                            ));
                        }
                        c
                    }
                    _ => {
                        let c = builder.add_cell(b.kind, &conn[s..s + n], label);
                        if !v41 {
                            seen.insert(label, c);
                        }
                        c
                    }
                };
                for g in &groups {
                    builder.add_to_cell_group(g, c);
                }
            }
        }
        builder.finish()
    }
}
