//! The targets of keyed groups of triplets (`Triplets::group`), kept from one search to
//! the next while the matrix's pattern stands. Contact statuses that change at a few
//! points change the sequence of all triplets, so the whole sequence is not the one
//! searched last time; each point's own group mostly is (SSNP154 D point-to-segment at
//! 93k unknowns: 130k–330k triplets per evaluation, their search 10–20 ms of each light
//! Newton iteration). A hand-written map by key: the check that a group is unchanged is
//! a comparison of its (row, column) sequence, the same loop whatever the keys.

use super::{expand, Targets, Triplets};
use crate::assembly::dofs::DofMap;
use crate::assembly::matrix::SparseMatrix;
use std::collections::HashMap;

/// One group's triplets (row, column) and, per triplet, its number of targets, with the
/// targets' positions and coefficients.
struct Group {
    pairs: Vec<(u32, u32)>,
    counts: Vec<u32>,
    at: Vec<u32>,
    coefficients: Vec<f64>,
}

impl Group {
    fn holds(&self, entries: &[(usize, usize, f64)]) -> bool {
        self.pairs.len() == entries.len()
            && self
                .pairs
                .iter()
                .zip(entries)
                .all(|(p, e)| p.0 as usize == e.0 && p.1 as usize == e.1)
    }
}

#[derive(Default)]
pub(super) struct GroupTargets {
    /// The pattern stamp the targets were found in (none: nothing kept).
    stamp: Option<u64>,
    groups: HashMap<u64, Group>,
    /// Groups whose kept targets served (for tests).
    pub(super) reused: usize,
}

impl GroupTargets {
    /// Forgets every group unless the pattern is the one they were found in (a stamp of
    /// zero names no pattern: nothing is kept).
    pub(super) fn stand_for(&mut self, stamp: u64) {
        if self.stamp != Some(stamp) || stamp == 0 {
            self.groups.clear();
            self.stamp = (stamp != 0).then_some(stamp);
        }
    }

    /// The targets of `extra` in `m`'s pattern, the unchanged groups' as found last time
    /// and the rest searched (and kept, by key); none if one is not in the pattern.
    pub(super) fn targets(
        &mut self,
        m: &SparseMatrix,
        dofs: &DofMap,
        extra: &Triplets,
    ) -> Option<Targets> {
        let len = extra.entries.len();
        let mut ptr = Vec::with_capacity(len + 1);
        ptr.push(0usize);
        let mut at = Vec::with_capacity(len);
        let mut coefficients = Vec::with_capacity(len);
        for (key, range) in extra.segments() {
            let entries = &extra.entries[range];
            if let Some(g) = key.and_then(|k| self.groups.get(&k)) {
                if g.holds(entries) {
                    for &c in &g.counts {
                        ptr.push(ptr[ptr.len() - 1] + c as usize);
                    }
                    at.extend_from_slice(&g.at);
                    coefficients.extend_from_slice(&g.coefficients);
                    self.reused += 1;
                    continue;
                }
            }
            let (p, targets) = expand(dofs, entries);
            let start = at.len();
            for &(col, row, c) in &targets {
                at.push(m.position(row, col)? as u32);
                coefficients.push(c);
            }
            let counts: Vec<u32> = p.windows(2).map(|w| (w[1] - w[0]) as u32).collect();
            for &c in &counts {
                ptr.push(ptr[ptr.len() - 1] + c as usize);
            }
            let (Some(k), Some(pairs)) = (key, pairs_u32(entries)) else {
                continue;
            };
            self.groups.insert(
                k,
                Group {
                    pairs,
                    counts,
                    at: at[start..].to_vec(),
                    coefficients: coefficients[start..].to_vec(),
                },
            );
        }
        Some(Targets::new(ptr, at, coefficients))
    }
}

/// The (row, column) pairs in 32 bits, if they fit.
fn pairs_u32(entries: &[(usize, usize, f64)]) -> Option<Vec<(u32, u32)>> {
    entries
        .iter()
        .map(|e| Some((u32::try_from(e.0).ok()?, u32::try_from(e.1).ok()?)))
        .collect()
}
