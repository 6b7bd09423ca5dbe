//! MSH 2.2 (ASCII): `$Nodes` and `$Elements` (element tags: the first is the physical group).

use super::{Block, Parser};
use crate::error::Result;

impl<'a> Parser<'a> {
    pub(super) fn nodes22(&mut self) -> Result<()> {
        let (n, _) = self.ascii_num::<u64>("number of nodes")?;
        self.nodes.expect(self.cap(n, 8));
        for _ in 0..n {
            let (tag, tag_pos) = self.ascii_num::<u64>("node number")?;
            let (x, px) = self.ascii_num::<f64>("x coordinate")?;
            let (y, _) = self.ascii_num::<f64>("y coordinate")?;
            let (z, pz) = self.ascii_num::<f64>("z coordinate")?;
            self.add_node(tag, tag_pos, [x, y, z], px, pz)?;
        }
        Ok(())
    }

    pub(super) fn elements22(&mut self) -> Result<()> {
        let (n, _) = self.ascii_num::<u64>("number of elements")?;
        for _ in 0..n {
            let (label, pl) = self.ascii_num::<u64>("element number")?;
            let (gmsh_type, pt) = self.ascii_num::<i64>("element type")?;
            let kind = self.element_kind(gmsh_type, pt)?;
            let (ntags, _) = self.ascii_num::<u64>("number of tags")?;
            let mut physical = 0;
            for i in 0..ntags {
                let (t, _) = self.ascii_num::<i64>("element tag")?;
                if i == 0 {
                    physical = t;
                }
            }
            let conn_start = self.conn.len();
            self.element_nodes(kind.num_nodes(), label, pl)?;
            let dim = kind.dim() as i64;
            match self.blocks.last_mut() {
                Some(b) if b.kind == kind && b.key == physical => b.count += 1,
                _ => self.blocks.push(Block {
                    kind,
                    dim,
                    key: physical,
                    conn_start,
                    label_start: self.labels.len(),
                    count: 1,
                }),
            }
            self.labels.push(label);
        }
        Ok(())
    }
}
