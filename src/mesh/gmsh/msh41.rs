//! MSH 4.1: `$Entities` (the physical tags of each entity) and the entity blocks of
//! `$Nodes` and `$Elements`, in ASCII or binary.

use super::{Block, Parser, Pos};
use crate::error::Result;
use std::collections::HashMap;

impl<'a> Parser<'a> {
    fn entity_dim(&mut self) -> Result<i64> {
        let (dim, p) = self.int("entity dimension")?;
        if !(0..=3).contains(&dim) {
            return Err(self.err(
                p,
                format!("entity dimension must be 0, 1, 2 or 3, found {dim}"),
            ));
        }
        Ok(dim)
    }

    pub(super) fn entities41(&mut self, p: Pos) -> Result<()> {
        if self.entities.is_some() {
            return Err(self.duplicate(p, "$Entities"));
        }
        if self.binary {
            self.end_header_line()?;
        }
        let mut counts = [0u64; 4];
        for (c, what) in counts.iter_mut().zip([
            "number of points",
            "number of curves",
            "number of surfaces",
            "number of volumes",
        ]) {
            *c = self.size(what)?.0;
        }
        let mut map = HashMap::new();
        for (dim, &n) in counts.iter().enumerate() {
            for _ in 0..n {
                let (tag, _) = self.int("entity tag")?;
                let reals = if dim == 0 { 3 } else { 6 };
                for _ in 0..reals {
                    self.real("entity coordinate")?;
                }
                let (np, _) = self.size("number of physical tags")?;
                let mut phys = Vec::with_capacity(self.cap(np, self.min_number_bytes()));
                for _ in 0..np {
                    phys.push(self.int("physical tag")?.0);
                }
                if dim > 0 {
                    let (nb, _) = self.size("number of bounding entities")?;
                    for _ in 0..nb {
                        self.int("bounding entity tag")?;
                    }
                }
                map.insert((dim as i64, tag), phys);
            }
        }
        self.entities = Some(map);
        self.end_section("$EndEntities")
    }

    pub(super) fn nodes41(&mut self) -> Result<()> {
        if self.binary {
            self.end_header_line()?;
        }
        let (nblocks, _) = self.size("number of entity blocks")?;
        let (nnodes, pn) = self.size("number of nodes")?;
        self.size("smallest node tag")?;
        self.size("largest node tag")?;
        self.nodes
            .expect(self.cap(nnodes, 4 * self.min_number_bytes()));
        let mut total: u64 = 0;
        let mut tags: Vec<(u64, Pos)> = Vec::new();
        for _ in 0..nblocks {
            let dim = self.entity_dim()?;
            self.int("entity tag")?;
            let (param, pp) = self.int("parametric flag")?;
            if param != 0 && param != 1 {
                return Err(self.err(pp, format!("parametric flag must be 0 or 1, found {param}")));
            }
            let (count, _) = self.size("number of nodes in the block")?;
            total = total.saturating_add(count);
            tags.clear();
            tags.reserve(self.cap(count, self.min_number_bytes()));
            // Per block: all the tags first, then all the coordinates.
            for _ in 0..count {
                tags.push(self.size("node tag")?);
            }
            let extra = if param == 1 { dim } else { 0 };
            for &(tag, tag_pos) in &tags {
                let (x, px) = self.real("x coordinate")?;
                let (y, _) = self.real("y coordinate")?;
                let (z, pz) = self.real("z coordinate")?;
                for _ in 0..extra {
                    self.real("parametric coordinate")?;
                }
                self.add_node(tag, tag_pos, [x, y, z], px, pz)?;
            }
        }
        if total != nnodes {
            return Err(self.err(
                pn,
                format!("the $Nodes header announces {nnodes} nodes but its blocks hold {total}"),
            ));
        }
        Ok(())
    }

    pub(super) fn elements41(&mut self) -> Result<()> {
        if self.binary {
            self.end_header_line()?;
        }
        let (nblocks, _) = self.size("number of entity blocks")?;
        let (nelems, pn) = self.size("number of elements")?;
        self.size("smallest element tag")?;
        self.size("largest element tag")?;
        let mut total: u64 = 0;
        let mut element_tags = std::collections::HashSet::new();
        for _ in 0..nblocks {
            let dim = self.entity_dim()?;
            let (entity, pe) = self.int("entity tag")?;
            if self
                .entities
                .as_ref()
                .is_some_and(|m| !m.contains_key(&(dim, entity)))
            {
                return Err(self.err(
                    pe,
                    format!(
                        "element block of entity {entity} (dim {dim}): \
                         the entity is not in $Entities"
                    ),
                ));
            }
            let (gmsh_type, pt) = self.int("element type")?;
            let kind = self.element_kind(gmsh_type, pt)?;
            let (count, _) = self.size("number of elements in the block")?;
            total = total.saturating_add(count);
            let n = kind.num_nodes();
            let reserve = self.cap(count, (n + 1) * self.min_number_bytes());
            self.labels.reserve(reserve);
            self.conn.reserve(reserve * n);
            let mut block = Block {
                kind,
                dim,
                key: entity,
                conn_start: self.conn.len(),
                label_start: self.labels.len(),
                count: 0,
            };
            for _ in 0..count {
                let (label, pl) = self.size("element tag")?;
                if !element_tags.insert(label) {
                    return Err(self.err(
                        pl,
                        format!("element tag {label} appears twice in $Elements"),
                    ));
                }
                self.element_nodes(n, label, pl)?;
                self.labels.push(label);
            }
            block.count = self.labels.len() - block.label_start;
            self.blocks.push(block);
        }
        if total != nelems {
            return Err(self.err(
                pn,
                format!(
                    "the $Elements header announces {nelems} elements but its blocks hold {total}"
                ),
            ));
        }
        Ok(())
    }
}
