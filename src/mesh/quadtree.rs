//! Graded, conforming quad-dominant meshes from a 2:1-balanced quadtree over a mapped
//! parameter domain. Leaves become Quad4/Quad8 cells; a leaf with a finer neighbour
//! (one hanging mid-side node per side at most, thanks to the balance) becomes a fan of
//! right-isosceles triangles around its centre, so every cell keeps angles of 45° or more
//! in the parameter plane. Used by the SSNP154 generator.

use std::collections::{HashMap, HashSet};

/// Lattice resolution: parameter coordinates are integers in units of root / 2^DEPTH.
const DEPTH: u32 = 26;

pub type Leaf = (u32, u64, u64);

pub struct Quadtree {
    /// Number of root cells in each direction and the root cell size (parameter units).
    pub nx: u64,
    pub ny: u64,
    pub root: f64,
    pub leaves: HashSet<Leaf>,
}

impl Quadtree {
    pub fn new(nx: u64, ny: u64, root: f64) -> Self {
        let mut leaves = HashSet::new();
        for i in 0..nx {
            for j in 0..ny {
                leaves.insert((0, i, j));
            }
        }
        Quadtree {
            nx,
            ny,
            root,
            leaves,
        }
    }

    /// Parameter-space box of a leaf: (x0, y0, size).
    pub fn bbox(&self, (l, i, j): Leaf) -> (f64, f64, f64) {
        let s = self.root / (1u64 << l) as f64;
        (i as f64 * s, j as f64 * s, s)
    }

    /// Splits leaves while `split(leaf)` says so (at most `max_level`).
    pub fn refine(&mut self, max_level: u32, split: &dyn Fn(&Quadtree, Leaf) -> bool) {
        let mut todo: Vec<Leaf> = self.leaves.iter().copied().collect();
        while let Some(leaf) = todo.pop() {
            if leaf.0 < max_level && self.leaves.contains(&leaf) && split(self, leaf) {
                todo.extend(self.split(leaf));
            }
        }
    }

    pub fn split(&mut self, (l, i, j): Leaf) -> [Leaf; 4] {
        self.leaves.remove(&(l, i, j));
        let kids = [
            (l + 1, 2 * i, 2 * j),
            (l + 1, 2 * i + 1, 2 * j),
            (l + 1, 2 * i + 1, 2 * j + 1),
            (l + 1, 2 * i, 2 * j + 1),
        ];
        for k in kids {
            self.leaves.insert(k);
        }
        kids
    }

    /// The leaf that contains the same-level cell (l, i, j), if it is that cell or coarser;
    /// None if the cell is outside the domain or subdivided further.
    pub fn covering(&self, l: u32, i: i64, j: i64) -> Option<Leaf> {
        if i < 0 || j < 0 || (i as u64) >= self.nx << l || (j as u64) >= self.ny << l {
            return None;
        }
        (0..=l)
            .rev()
            .map(|lc| (lc, (i as u64) >> (l - lc), (j as u64) >> (l - lc)))
            .find(|c| self.leaves.contains(c))
    }

    /// Whether the same-level neighbour cell across a side is subdivided (finer leaves).
    fn finer_across(&self, (l, i, j): Leaf, di: i64, dj: i64) -> bool {
        let (ni, nj) = (i as i64 + di, j as i64 + dj);
        if ni < 0 || nj < 0 || (ni as u64) >= self.nx << l || (nj as u64) >= self.ny << l {
            return false;
        }
        self.covering(l, ni, nj).is_none()
    }

    /// Splits leaves until neighbours differ by at most one level.
    pub fn balance(&mut self) {
        loop {
            let mut to_split = HashSet::new();
            for &(l, i, j) in &self.leaves {
                if l < 2 {
                    continue;
                }
                for (di, dj) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                    if let Some(n) = self.covering(l, i as i64 + di, j as i64 + dj) {
                        if n.0 + 1 < l {
                            to_split.insert(n);
                        }
                    }
                }
            }
            if to_split.is_empty() {
                return;
            }
            for leaf in to_split {
                if self.leaves.contains(&leaf) {
                    self.split(leaf);
                }
            }
        }
    }

    /// Conforming cells as lattice corner lists (counter-clockwise in the parameter plane):
    /// 4 corners for a quadrilateral, 3 for a triangle. Lattice points are (x, y) integers
    /// in units of root / 2^DEPTH.
    pub fn cells(&self) -> Vec<Vec<(u64, u64)>> {
        let mut out = vec![];
        let mut leaves: Vec<Leaf> = self.leaves.iter().copied().collect();
        leaves.sort_unstable();
        for leaf in leaves {
            let (l, i, j) = leaf;
            let s = 1u64 << (DEPTH - l);
            let (x0, y0) = (i * s, j * s);
            let h = s / 2;
            let c = [(x0, y0), (x0 + s, y0), (x0 + s, y0 + s), (x0, y0 + s)];
            let mids = [
                self.finer_across(leaf, 0, -1).then_some((x0 + h, y0)),
                self.finer_across(leaf, 1, 0).then_some((x0 + s, y0 + h)),
                self.finer_across(leaf, 0, 1).then_some((x0 + h, y0 + s)),
                self.finer_across(leaf, -1, 0).then_some((x0, y0 + h)),
            ];
            if mids.iter().all(|m| m.is_none()) {
                out.push(c.to_vec());
                continue;
            }
            let centre = (x0 + h, y0 + h);
            let hanging: Vec<usize> = (0..4).filter(|&k| mids[k].is_some()).collect();
            if let [k] = hanging[..] {
                // one hanging side (k): two quadrilaterals and one right triangle
                let (a, m, b) = (c[k], mids[k].unwrap(), c[(k + 1) % 4]);
                let (cc, d) = (c[(k + 2) % 4], c[(k + 3) % 4]);
                out.push(vec![a, m, centre, d]);
                out.push(vec![m, b, cc, centre]);
                out.push(vec![cc, d, centre]);
                continue;
            }
            let mut ring = vec![];
            for k in 0..4 {
                ring.push(c[k]);
                if let Some(m) = mids[k] {
                    ring.push(m);
                }
            }
            for k in 0..ring.len() {
                out.push(vec![ring[k], ring[(k + 1) % ring.len()], centre]);
            }
        }
        out
    }

    /// Parameter coordinates of a lattice point.
    pub fn param(&self, p: (u64, u64)) -> [f64; 2] {
        let unit = self.root / (1u64 << DEPTH) as f64;
        [p.0 as f64 * unit, p.1 as f64 * unit]
    }
}

/// Node numbering by lattice point, shared by the cells of one body.
#[derive(Default)]
pub struct LatticeNodes {
    pub index: HashMap<(u64, u64), usize>,
}
