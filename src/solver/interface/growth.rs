//! A contact pattern that grew beyond the analysis, taken as long as its new entries are
//! zero. The pattern grows when contact points come within reach of master cells they
//! were not paired with, and Newton then takes in at once what it predicts for the
//! loading's end (`Nonlinear::anticipate`); the couplings it brings are those of points
//! not (yet) in contact, zero in the tangent. The analysis at hand then still factorises
//! the matrix exactly: the blocks' factorisations stand, and so the active-set re-solve
//! that follows keeps them (SSNP154 D point-to-segment at 93k unknowns: the first step's
//! first re-solve, 21 088 new entries all zero, a second analysis and factorisation of
//! the bodies avoided). The analysis is made anew when one of these entries is no longer
//! zero, or when the bodies are factorised anyway (a full Newton correction: the new
//! analysis then costs its own time alone, and holds the whole pattern from there on).

use super::{gamma_entries, InterfaceSolver, NONE};
use crate::assembly::matrix::SparseMatrix;
use rayon::prelude::*;

impl InterfaceSolver {
    /// Takes `a`, whose pattern grew beyond this analysis's (`in_gamma` its interface, as
    /// `interface_of` finds it), when every entry of it that the analysis does not hold is
    /// zero and the blocks' values are those factorised: true when taken. Entries between
    /// interface unknowns are held whatever their pattern (the interface matrix is
    /// dense); the blocks' entries must be symmetric (only their lower triangles are
    /// read), which the unknowns that joined the interface are checked for. False leaves
    /// the solver unusable (its caller analyses `a` anew).
    pub fn rebind_grown(&mut self, a: &SparseMatrix, in_gamma_now: &[bool]) -> bool {
        if a.n != self.n {
            return false;
        }
        let mut in_gamma = vec![false; a.n];
        for &g in &self.gamma {
            in_gamma[g] = true;
        }
        if self.gamma.iter().any(|&g| !in_gamma_now[g]) {
            return false;
        }
        // An unknown joins the interface by an entry with a multiplier or by one whose
        // transpose differs: the latter must not be in a block.
        let joined: Vec<usize> = (0..a.n)
            .filter(|&u| in_gamma_now[u] && !in_gamma[u])
            .collect();
        if !symmetric(a, &joined) {
            return false;
        }
        // the block each interior unknown belongs to
        let mut owner = vec![NONE; a.n];
        for (ib, b) in self.blocks.iter().enumerate() {
            for &u in &b.unknowns[..b.interior] {
                owner[u] = ib;
            }
        }
        let positions: Vec<Vec<usize>> = self.blocks.par_iter().map(|b| b.positions(a.n)).collect();
        let blocks = &self.blocks;
        // the positions of the entries not held (None: one of them is not zero)
        let ignored = (0..a.n)
            .into_par_iter()
            .with_min_len(1 << 12)
            .try_fold(Vec::new, |mut out, c| {
                for p in a.col_ptr[c]..a.col_ptr[c + 1] {
                    let r = a.row_idx[p];
                    if in_gamma[r] && in_gamma[c] {
                        continue;
                    }
                    // (one of the two is interior to a block)
                    let ib = if owner[r] != NONE { owner[r] } else { owner[c] };
                    let (i, j) = (positions[ib][r], positions[ib][c]);
                    let held = i != NONE && j != NONE && blocks[ib].holds(i, j);
                    if !held {
                        if a.values[p] != 0.0 {
                            return None;
                        }
                        out.push(p);
                    }
                }
                Some(out)
            })
            .try_reduce(Vec::new, |mut x, y| {
                x.extend(y);
                Some(x)
            });
        let Some(ignored) = ignored else {
            return false;
        };
        let rebound = self
            .blocks
            .par_iter_mut()
            .zip(&positions)
            .map(|(b, at)| b.rebind(a, at, true) && b.values_unchanged(a))
            .collect::<Vec<bool>>();
        if rebound.contains(&false) {
            return false;
        }
        self.ignored = ignored;
        self.joined = joined;
        self.take_interface_entries(a);
        true
    }

    /// Whether this analysis is to factorise `a` (a matrix of the pattern it was last
    /// given): it holds every nonzero entry of `a`, the unknowns that joined the interface
    /// since it was made have symmetric entries, and, if it took a grown pattern, the
    /// bodies' factorisations stand (else a new analysis costs its own time alone).
    pub fn stands(&self, a: &SparseMatrix) -> bool {
        self.ignored.is_empty()
            || (self.ignored.iter().all(|&p| a.values[p] == 0.0)
                && symmetric(a, &self.joined)
                && self.blocks.iter().all(|b| b.values_unchanged(a)))
    }

    /// After a rebind: the entries of A in Γ × Γ at their new positions, the LU's values
    /// labelled by them.
    pub(super) fn take_interface_entries(&mut self, a: &SparseMatrix) {
        let entries = gamma_entries(a, &self.gamma);
        let old = std::mem::replace(&mut self.gamma_entries, entries);
        self.relabel_factorised(&old);
        if let Some(r) = &mut self.base.reduction {
            // (its values are by the old entries)
            r.values.clear();
        }
        self.update = None;
    }
}

/// Whether the entries of `a` in the columns of `unknowns` equal their transposes.
fn symmetric(a: &SparseMatrix, unknowns: &[usize]) -> bool {
    unknowns.iter().all(|&u| {
        (a.col_ptr[u]..a.col_ptr[u + 1]).all(|p| {
            let r = a.row_idx[p];
            a.position(u, r).is_some_and(|t| a.values[t] == a.values[p])
        })
    })
}
