//! The elimination tree of a factor's supernodes, with each subtree's size, first
//! supernode and entries: what the parallel passes (`passes.rs`) and the factorisation by
//! the tree (`numeric.rs`) are cut along.

/// Supernode s's parent (None: a root) is the supernode of its first row below its
/// diagonal block; a parent comes after its children.
pub(super) struct Forest {
    /// The supernode of each column.
    pub(super) node_of: Vec<usize>,
    pub(super) parent: Vec<Option<usize>>,
    /// Each supernode's children, ascending.
    pub(super) children: Vec<Vec<usize>>,
    /// Of each subtree: its first supernode, its number of supernodes, its entries.
    pub(super) first: Vec<usize>,
    pub(super) size: Vec<usize>,
    pub(super) work: Vec<usize>,
}

impl Forest {
    /// From the supernodes' column ranges (`begin[s]..end[s]`, increasing), their rows
    /// below the diagonal block (`rows(s)`) and their numbers of entries.
    pub(super) fn new<'r>(
        begin: &[usize],
        end: &[usize],
        rows: impl Fn(usize) -> &'r [usize],
        entries: &[usize],
    ) -> Forest {
        let ns = begin.len();
        let n = end.last().copied().unwrap_or(0);
        let mut node_of = vec![0; n];
        for s in 0..ns {
            node_of[begin[s]..end[s]].fill(s);
        }
        let parent: Vec<Option<usize>> = (0..ns)
            .map(|s| rows(s).iter().min().map(|&r| node_of[r]))
            .collect();
        let mut work = entries.to_vec();
        let mut size = vec![1usize; ns];
        let mut first = (0..ns).collect::<Vec<_>>();
        let mut children = vec![vec![]; ns];
        for s in 0..ns {
            if let Some(p) = parent[s] {
                debug_assert!(p > s, "a supernode's parent comes after it");
                work[p] += work[s];
                size[p] += size[s];
                first[p] = first[p].min(first[s]);
                children[p].push(s);
            }
        }
        Forest {
            node_of,
            parent,
            children,
            first,
            size,
            work,
        }
    }

    /// Whether the subtree of s is the range of supernodes from its first to s (in a
    /// postorder, every subtree is).
    pub(super) fn contiguous(&self, s: usize) -> bool {
        s + 1 - self.first[s] == self.size[s]
    }
}
