//! `MeshBuilder`: the one way to make a `Mesh`. Readers and generators push nodes, cells
//! and groups; `finish` checks node indices, reorders clockwise cells and rejects
//! degenerate or tangled ones, naming the cell, and puts 2D cells in no group into the
//! default group `ungrouped` (so every reader does).

use super::{CellKind, Mesh, DEFAULT_GROUP};
use crate::error::{Error, Result};
use crate::fem::element::{jacobian_det, reference_nodes};

#[derive(Default)]
pub struct MeshBuilder {
    mesh: Mesh,
    /// Label of each cell for error messages (e.g. the element tag in the file).
    labels: Vec<u64>,
    /// Where the mesh comes from, for error messages.
    source: String,
}

impl MeshBuilder {
    pub fn new(source: impl Into<String>) -> Self {
        let mut b = MeshBuilder {
            source: source.into(),
            ..Default::default()
        };
        b.mesh.offsets.push(0);
        b
    }

    pub fn add_node(&mut self, x: [f64; 2]) -> usize {
        self.mesh.coords.push(x);
        self.mesh.coords.len() - 1
    }

    pub fn num_nodes(&self) -> usize {
        self.mesh.coords.len()
    }

    pub fn num_cells(&self) -> usize {
        self.mesh.num_cells()
    }

    /// Kind and nodes of a cell added so far.
    pub fn cell(&self, c: usize) -> (CellKind, &[usize]) {
        (self.mesh.kind(c), self.mesh.cell_nodes(c))
    }

    pub fn coords(&self) -> &[[f64; 2]] {
        &self.mesh.coords
    }

    /// Adds a cell; `label` is the identifier the user knows it by (file tag or index).
    pub fn add_cell(&mut self, kind: CellKind, nodes: &[usize], label: u64) -> usize {
        debug_assert_eq!(nodes.len(), kind.num_nodes());
        self.mesh.kinds.push(kind);
        self.mesh.conn.extend_from_slice(nodes);
        self.mesh.offsets.push(self.mesh.conn.len());
        self.labels.push(label);
        self.mesh.kinds.len() - 1
    }

    pub fn add_to_cell_group(&mut self, group: &str, cell: usize) {
        // no String allocated per cell once the group exists
        match self.mesh.cell_groups.get_mut(group) {
            Some(cells) => cells.push(cell),
            None => {
                self.mesh.cell_groups.insert(group.to_string(), vec![cell]);
            }
        }
    }

    pub fn add_to_node_group(&mut self, group: &str, node: usize) {
        self.mesh
            .node_groups
            .entry(group.to_string())
            .or_default()
            .push(node);
    }

    /// Appends a whole mesh (another body), renaming its groups with `rename`.
    pub fn append(&mut self, mesh: &Mesh, rename: impl Fn(&str) -> String) {
        let base = self.num_nodes();
        for &x in &mesh.coords {
            self.add_node(x);
        }
        let first = self.mesh.num_cells();
        for c in 0..mesh.num_cells() {
            let nodes: Vec<usize> = mesh.cell_nodes(c).iter().map(|n| n + base).collect();
            self.add_cell(mesh.kind(c), &nodes, (first + c + 1) as u64);
        }
        for (name, cells) in &mesh.cell_groups {
            for &c in cells {
                self.add_to_cell_group(&rename(name), first + c);
            }
        }
        for (name, nodes) in &mesh.node_groups {
            for &n in nodes {
                self.add_to_node_group(&rename(name), base + n);
            }
        }
    }

    /// Checks and orients the mesh. Clockwise 2D cells are reordered counter-clockwise
    /// (counted in `Mesh::reoriented`); cells with a zero or sign-changing Jacobian are errors.
    pub fn finish(mut self) -> Result<Mesh> {
        let n_nodes = self.mesh.coords.len();
        for (i, x) in self.mesh.coords.iter().enumerate() {
            if !x[0].is_finite() || !x[1].is_finite() {
                return Err(Error::model(format!(
                    "{}: node {} has a non-finite coordinate",
                    self.source,
                    i + 1
                )));
            }
        }
        // a length below 1e-12 of the mesh's extent is zero
        let (lo, hi) =
            self.mesh
                .coords
                .iter()
                .fold(([f64::MAX; 2], [f64::MIN; 2]), |(lo, hi), x| {
                    (
                        [lo[0].min(x[0]), lo[1].min(x[1])],
                        [hi[0].max(x[0]), hi[1].max(x[1])],
                    )
                });
        let tol = 1e-12 * (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
        for c in 0..self.mesh.num_cells() {
            if let Some(&bad) = self.mesh.cell_nodes(c).iter().find(|&&n| n >= n_nodes) {
                return Err(Error::model(format!(
                    "{}: cell {} ({}) refers to node {} but the mesh has {} nodes",
                    self.source,
                    self.labels[c],
                    self.mesh.kinds[c],
                    bad + 1,
                    n_nodes
                )));
            }
            let kind = self.mesh.kinds[c];
            let nodes = self.mesh.cell_nodes(c);
            if let Some(a) = (1..nodes.len()).find(|&a| nodes[..a].contains(&nodes[a])) {
                return Err(Error::model(format!(
                    "{}: cell {} ({}) lists node {} twice",
                    self.source,
                    self.labels[c],
                    kind,
                    nodes[a] + 1
                )));
            }
            if kind.dim() == 1 && self.zero_length(c, tol) {
                return Err(Error::model(format!(
                    "{}: cell {} ({}) is of zero length",
                    self.source, self.labels[c], kind
                )));
            }
            if kind.dim() != 2 {
                continue;
            }
            let signs = self.jacobian_signs(c);
            match signs {
                Orientation::Positive => {}
                Orientation::Negative => {
                    let perm = kind.reverse_permutation();
                    let range = self.mesh.offsets[c]..self.mesh.offsets[c + 1];
                    let old: Vec<usize> = self.mesh.conn[range.clone()].to_vec();
                    for (i, slot) in self.mesh.conn[range].iter_mut().enumerate() {
                        *slot = old[perm[i]];
                    }
                    self.mesh.reoriented += 1;
                }
                Orientation::Degenerate(what) => {
                    return Err(Error::model(format!(
                        "{}: cell {} ({}) is {}",
                        self.source, self.labels[c], kind, what
                    )));
                }
            }
        }
        for cells in self.mesh.cell_groups.values_mut() {
            cells.sort_unstable();
            cells.dedup();
        }
        for nodes in self.mesh.node_groups.values_mut() {
            nodes.sort_unstable();
            nodes.dedup();
        }
        self.default_group()?;
        Ok(self.mesh)
    }

    /// Two nodes of a 1D cell at one place (relative to the mesh's extent): a contact
    /// or load edge without a direction.
    fn zero_length(&self, c: usize, tol: f64) -> bool {
        let (x, n) = self.mesh.cell_coords(c);
        (0..n).any(|a| (0..a).any(|b| (x[a][0] - x[b][0]).hypot(x[a][1] - x[b][1]) <= tol))
    }

    /// Puts the 2D cells that are in no group into the group `DEFAULT_GROUP` (MED files
    /// often leave the bodies' cells without a group; `mesh convert` writes them so).
    fn default_group(&mut self) -> Result<()> {
        let mut grouped = vec![false; self.mesh.num_cells()];
        for cells in self.mesh.cell_groups.values() {
            for &c in cells {
                grouped[c] = true;
            }
        }
        let free: Vec<usize> = self.mesh.cells_of_dim(2).filter(|&c| !grouped[c]).collect();
        if free.is_empty() {
            return Ok(());
        }
        if self.mesh.cell_groups.contains_key(DEFAULT_GROUP)
            || self.mesh.node_groups.contains_key(DEFAULT_GROUP)
        {
            return Err(Error::model(format!(
                "{}: {} 2D cells (cell {} first) are in no group and would form the default \
                 group '{DEFAULT_GROUP}', but the mesh already has a group named \
                 '{DEFAULT_GROUP}'; put those cells in a group or rename that group",
                self.source,
                free.len(),
                self.labels[free[0]]
            )));
        }
        self.mesh
            .cell_groups
            .insert(DEFAULT_GROUP.to_string(), free);
        Ok(())
    }

    /// Sign of det J at the reference nodes and the centre of a 2D cell.
    fn jacobian_signs(&self, c: usize) -> Orientation {
        let kind = self.mesh.kinds[c];
        let (x, _) = self.mesh.cell_coords(c);
        let centre = if kind.num_corners() == 3 {
            [1.0 / 3.0, 1.0 / 3.0]
        } else {
            [0.0, 0.0]
        };
        let size2 = {
            let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
            for xa in &x[..kind.num_nodes()] {
                for d in 0..2 {
                    lo[d] = lo[d].min(xa[d]);
                    hi[d] = hi[d].max(xa[d]);
                }
            }
            ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2)).max(f64::MIN_POSITIVE)
        };
        // Relative threshold: |det J| below 1e-12 of the squared cell size counts as zero.
        let eps = 1e-12 * size2;
        let (mut pos, mut neg, mut zero) = (0, 0, 0);
        for xi in reference_nodes(kind)
            .iter()
            .take(kind.num_corners())
            .copied()
            .chain(std::iter::once(centre))
        {
            let d = jacobian_det(kind, &x, xi);
            if d > eps {
                pos += 1;
            } else if d < -eps {
                neg += 1;
            } else {
                zero += 1;
            }
        }
        if pos > 0 && neg == 0 && zero == 0 {
            Orientation::Positive
        } else if neg > 0 && pos == 0 && zero == 0 {
            Orientation::Negative
        } else if pos == 0 && neg == 0 {
            Orientation::Degenerate("of zero area")
        } else {
            Orientation::Degenerate("inverted or tangled (its Jacobian changes sign or vanishes)")
        }
    }
}

enum Orientation {
    Positive,
    Negative,
    Degenerate(&'static str),
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(b: &mut MeshBuilder, pts: [[f64; 2]; 4]) -> Vec<usize> {
        pts.iter().map(|&p| b.add_node(p)).collect()
    }

    #[test]
    fn clockwise_cells_are_reoriented() {
        let mut b = MeshBuilder::new("t.msh");
        let n = square(&mut b, [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        b.add_cell(CellKind::Quad4, &[n[0], n[3], n[2], n[1]], 7);
        b.add_cell(CellKind::Tri3, &[n[0], n[1], n[2]], 8);
        let m = b.finish().unwrap();
        assert_eq!(m.reoriented, 1);
        assert_eq!(m.cell_nodes(0), &[n[0], n[1], n[2], n[3]]);
    }

    #[test]
    fn zero_area_cell_is_an_error_naming_it() {
        let mut b = MeshBuilder::new("t.msh");
        let n = square(&mut b, [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]]);
        b.add_cell(CellKind::Tri3, &[n[0], n[1], n[2]], 42);
        let e = b.finish().unwrap_err().to_string();
        assert_eq!(e, "t.msh: cell 42 (Tri3) is of zero area");
    }

    #[test]
    fn tangled_cell_is_an_error_naming_it() {
        let mut b = MeshBuilder::new("t.msh");
        // bow-tie quadrilateral
        let n = square(&mut b, [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]);
        b.add_cell(CellKind::Quad4, &n, 5);
        let e = b.finish().unwrap_err().to_string();
        assert_eq!(
            e,
            "t.msh: cell 5 (Quad4) is inverted or tangled (its Jacobian changes sign or vanishes)"
        );
    }

    #[test]
    fn out_of_range_node_is_an_error() {
        let mut b = MeshBuilder::new("t.msh");
        b.add_node([0.0, 0.0]);
        b.add_cell(CellKind::Seg2, &[0, 3], 1);
        let e = b.finish().unwrap_err().to_string();
        assert_eq!(
            e,
            "t.msh: cell 1 (Seg2) refers to node 4 but the mesh has 1 nodes"
        );
    }
}
