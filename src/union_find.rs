//! Disjoint sets over 0..n (union by link, path halving): the connected components of the
//! mesh's bodies and of the interface's passive unknowns. Hand-written: a dozen lines,
//! where a crate would bring its own numbering of the sets.

pub struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    /// n singletons.
    pub fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    /// The representative of i's set.
    pub fn root(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    /// Joins the sets of a and b (b's representative under a's).
    pub fn join(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.root(a), self.root(b));
        self.parent[rb] = ra;
    }
}

#[cfg(test)]
mod tests {
    use super::UnionFind;

    #[test]
    fn joined_elements_share_a_root_and_others_do_not() {
        let mut u = UnionFind::new(6);
        u.join(0, 3);
        u.join(4, 1);
        u.join(3, 4);
        let r = u.root(0);
        assert!([1, 3, 4].iter().all(|&i| u.root(i) == r));
        assert!(u.root(2) != r && u.root(5) != r && u.root(2) != u.root(5));
    }
}
