//! Graded, conforming quad-dominant meshes from a 2:1-balanced quadtree over a mapped
//! parameter domain. Leaves become Quad4/Quad8 cells; a leaf with a finer neighbour
//! (one hanging mid-side node per side at most, thanks to the balance) becomes a fan of
//! right-isosceles triangles around its centre, so every cell keeps angles of 45° or more
//! in the parameter plane. Used by the SSNP154 generator.
//!
//! The tree is an arena of cells with child links, so finding the leaf over a point is a
//! descent of array lookups (a hash set of leaves made the 525k-node SSNP154 mesh spend
//! 36 % of its time in `balance` and 17 % hashing). `balance` visits leaves once, finest
//! level first: splits then only make coarser leaves, still to be visited.

/// Lattice resolution: parameter coordinates are integers in units of root / 2^DEPTH.
const DEPTH: u32 = 26;

/// A cell: (level, i, j), the square [i, i + 1] × [j, j + 1] × root / 2^level.
pub type Leaf = (u32, u64, u64);

const NO_KIDS: usize = usize::MAX;

struct Node {
    cell: Leaf,
    /// Index of the first of the four children (i + 2 j order), NO_KIDS for a leaf.
    kids: usize,
}

pub struct Quadtree {
    /// Number of root cells in each direction and the root cell size (parameter units).
    pub nx: u64,
    pub ny: u64,
    pub root: f64,
    /// Roots first (root (i, j) at i·ny + j), then children four at a time.
    nodes: Vec<Node>,
}

impl Quadtree {
    pub fn new(nx: u64, ny: u64, root: f64) -> Self {
        let mut nodes = vec![];
        for i in 0..nx {
            for j in 0..ny {
                nodes.push(Node {
                    cell: (0, i, j),
                    kids: NO_KIDS,
                });
            }
        }
        Quadtree {
            nx,
            ny,
            root,
            nodes,
        }
    }

    /// Parameter-space box of a leaf: (x0, y0, size).
    pub fn bbox(&self, (l, i, j): Leaf) -> (f64, f64, f64) {
        let s = self.root / (1u64 << l) as f64;
        (i as f64 * s, j as f64 * s, s)
    }

    fn leaf_ids(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.nodes.len()).filter(|&n| self.nodes[n].kids == NO_KIDS)
    }

    pub fn num_leaves(&self) -> usize {
        // every split turns one leaf into four
        let roots = (self.nx * self.ny) as usize;
        roots + 3 * (self.nodes.len() - roots) / 4
    }

    /// The leaves, sorted.
    pub fn leaves(&self) -> Vec<Leaf> {
        let mut out: Vec<Leaf> = self.leaf_ids().map(|n| self.nodes[n].cell).collect();
        out.sort_unstable();
        out
    }

    /// Splits leaves while `split(leaf)` says so (at most `max_level`).
    pub fn refine(&mut self, max_level: u32, split: &dyn Fn(&Quadtree, Leaf) -> bool) {
        let mut todo: Vec<usize> = self.leaf_ids().collect();
        while let Some(n) = todo.pop() {
            let leaf = self.nodes[n].cell;
            if leaf.0 < max_level && split(self, leaf) {
                todo.extend(self.split_node(n));
            }
        }
    }

    fn split_node(&mut self, n: usize) -> [usize; 4] {
        debug_assert_eq!(self.nodes[n].kids, NO_KIDS);
        let (l, i, j) = self.nodes[n].cell;
        let first = self.nodes.len();
        self.nodes[n].kids = first;
        for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            self.nodes.push(Node {
                cell: (l + 1, 2 * i + di, 2 * j + dj),
                kids: NO_KIDS,
            });
        }
        [first, first + 1, first + 2, first + 3]
    }

    /// Splits a leaf in four (nothing if it is not a leaf).
    pub fn split(&mut self, (l, i, j): Leaf) {
        if let Some(n) = self.locate(l, i as i64, j as i64) {
            if self.nodes[n].cell.0 == l {
                self.split_node(n);
            }
        }
    }

    /// The node of the leaf that contains the same-level cell (l, i, j), if it is that cell
    /// or coarser; None if the cell is outside the domain or subdivided further.
    fn locate(&self, l: u32, i: i64, j: i64) -> Option<usize> {
        if i < 0 || j < 0 || (i as u64) >= self.nx << l || (j as u64) >= self.ny << l {
            return None;
        }
        let (i, j) = (i as u64, j as u64);
        let mut n = ((i >> l) * self.ny + (j >> l)) as usize;
        for shift in (0..l).rev() {
            let kids = self.nodes[n].kids;
            if kids == NO_KIDS {
                return Some(n);
            }
            n = kids + ((i >> shift) & 1) as usize + 2 * ((j >> shift) & 1) as usize;
        }
        (self.nodes[n].kids == NO_KIDS).then_some(n)
    }

    /// Whether the same-level neighbour cell across a side is subdivided (finer leaves).
    fn finer_across(&self, (l, i, j): Leaf, di: i64, dj: i64) -> bool {
        let (ni, nj) = (i as i64 + di, j as i64 + dj);
        if ni < 0 || nj < 0 || (ni as u64) >= self.nx << l || (nj as u64) >= self.ny << l {
            return false;
        }
        self.locate(l, ni, nj).is_none()
    }

    /// Splits leaves until side neighbours differ by at most one level: the least such
    /// refinement (every split is forced by a leaf two or more levels finer).
    pub fn balance(&mut self) {
        let mut by_level: Vec<Vec<usize>> = vec![];
        for n in self.leaf_ids() {
            let l = self.nodes[n].cell.0 as usize;
            if by_level.len() <= l {
                by_level.resize(l + 1, vec![]);
            }
            by_level[l].push(n);
        }
        // Finest first: a leaf of level l only splits coarser leaves (down to level l - 1),
        // which are visited later; leaves of level l - 1 or finer are never split after.
        for l in (2..by_level.len()).rev() {
            let mut k = 0;
            while k < by_level[l].len() {
                let (_, i, j) = self.nodes[by_level[l][k]].cell;
                k += 1;
                for (di, dj) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                    let (ni, nj) = (i as i64 + di, j as i64 + dj);
                    let Some(mut n) = self.locate(l as u32, ni, nj) else {
                        continue;
                    };
                    while (self.nodes[n].cell.0 as usize) + 1 < l {
                        let kids = self.split_node(n);
                        let lk = self.nodes[n].cell.0 as usize + 1;
                        for kid in kids {
                            by_level[lk].push(kid);
                        }
                        let shift = l - lk;
                        n = kids[((ni >> shift) & 1) as usize + 2 * ((nj >> shift) & 1) as usize];
                    }
                }
            }
        }
    }

    /// Conforming cells as lattice corner lists (counter-clockwise in the parameter plane),
    /// leaf by leaf in sorted order: 4 corners for a quadrilateral, 3 for a triangle.
    /// Lattice points are (x, y) integers in units of root / 2^DEPTH.
    pub fn for_each_cell(&self, mut f: impl FnMut(&[(u64, u64)])) {
        for leaf in self.leaves() {
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
            let hanging = mids.iter().filter(|m| m.is_some()).count();
            if hanging == 0 {
                f(&c);
                continue;
            }
            let centre = (x0 + h, y0 + h);
            if hanging == 1 {
                // one hanging side (k): two quadrilaterals and one right triangle
                let k = mids.iter().position(|m| m.is_some()).unwrap();
                let (a, m, b) = (c[k], mids[k].unwrap(), c[(k + 1) % 4]);
                let (cc, d) = (c[(k + 2) % 4], c[(k + 3) % 4]);
                f(&[a, m, centre, d]);
                f(&[m, b, cc, centre]);
                f(&[cc, d, centre]);
                continue;
            }
            let mut ring = [(0, 0); 8];
            let mut len = 0;
            for k in 0..4 {
                ring[len] = c[k];
                len += 1;
                if let Some(m) = mids[k] {
                    ring[len] = m;
                    len += 1;
                }
            }
            for k in 0..len {
                f(&[ring[k], ring[(k + 1) % len], centre]);
            }
        }
    }

    /// The cells of `for_each_cell`, collected.
    pub fn cells(&self) -> Vec<Vec<(u64, u64)>> {
        let mut out = vec![];
        self.for_each_cell(|c| out.push(c.to_vec()));
        out
    }

    /// Parameter coordinates of a lattice point.
    pub fn param(&self, p: (u64, u64)) -> [f64; 2] {
        let unit = self.root / (1u64 << DEPTH) as f64;
        [p.0 as f64 * unit, p.1 as f64 * unit]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    /// The balance by its definition: split any leaf with a side neighbour two or more
    /// levels finer, until none is left (a hash set of leaves, neighbours by lookup).
    fn balance_by_definition(nx: u64, ny: u64, mut leaves: HashSet<Leaf>) -> HashSet<Leaf> {
        let covering = |leaves: &HashSet<Leaf>, l: u32, i: i64, j: i64| {
            if i < 0 || j < 0 || i as u64 >= nx << l || j as u64 >= ny << l {
                return None;
            }
            (0..=l)
                .map(|lc| (lc, (i as u64) >> (l - lc), (j as u64) >> (l - lc)))
                .find(|c| leaves.contains(c))
        };
        loop {
            let mut split = HashSet::new();
            for &(l, i, j) in &leaves {
                for (di, dj) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                    if let Some(n) = covering(&leaves, l, i as i64 + di, j as i64 + dj) {
                        if n.0 + 1 < l {
                            split.insert(n);
                        }
                    }
                }
            }
            if split.is_empty() {
                return leaves;
            }
            for (l, i, j) in split {
                leaves.remove(&(l, i, j));
                for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    leaves.insert((l + 1, 2 * i + di, 2 * j + dj));
                }
            }
        }
    }

    #[test]
    fn balance_is_the_least_balanced_refinement() {
        // trees refined deep towards points next to the sides of root cells (the finest
        // leaves there touch a root: strongly unbalanced), 3 × 2 roots
        let targets: [&[(f64, f64)]; 3] = [
            &[(1.0001, 0.5)],
            &[(1.999, 1.3), (0.5, 1.001)],
            &[(0.0001, 1.999), (2.5, 0.999), (1.75, 1.5)],
        ];
        for pts in targets {
            let mut tree = Quadtree::new(3, 2, 1.0);
            tree.refine(9, &|t, leaf| {
                let (x0, y0, s) = t.bbox(leaf);
                pts.iter()
                    .any(|&(x, y)| x >= x0 && x <= x0 + s && y >= y0 && y <= y0 + s)
            });
            let before: HashSet<Leaf> = tree.leaves().into_iter().collect();
            tree.balance();
            let expect = balance_by_definition(3, 2, before.clone());
            let got: HashSet<Leaf> = tree.leaves().into_iter().collect();
            assert!(got.len() > before.len(), "the balance split nothing");
            assert_eq!(got, expect);
        }
    }

    #[test]
    fn hanging_sides_become_triangle_fans() {
        // one root split, then its lower-left child: the other three children have a
        // finer neighbour across one side each, or none
        let mut tree = Quadtree::new(1, 1, 1.0);
        tree.split((0, 0, 0));
        tree.split((1, 0, 0));
        assert_eq!(tree.num_leaves(), 7);
        assert_eq!(tree.num_leaves(), tree.leaves().len());
        let mut kinds = vec![];
        tree.for_each_cell(|c| kinds.push(c.len()));
        // 4 quads (level 2); (1,1,0) and (1,0,1): 2 quads + 1 triangle each; (1,1,1): quad
        assert_eq!(kinds.iter().filter(|&&n| n == 4).count(), 4 + 4 + 1);
        assert_eq!(kinds.iter().filter(|&&n| n == 3).count(), 2);
    }
}
