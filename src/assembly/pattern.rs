//! The assembler's matrix pattern over the free unknowns and, per cell, the position of
//! every local entry in the value array. Built by counting and merging (one flat row
//! array, no vector per column, no search per entry), the columns and the cells split
//! between the cores.

use super::dofs::{DofMap, Role};
use super::matrix::{group_by_key, new_pattern_stamp, SparseMatrix};
use super::{LINKED, NONE};
use crate::mesh::Mesh;
use rayon::prelude::*;

/// Column ranges (and cell ranges) handed to one task: a few per core.
const CHUNKS: usize = 8;

pub struct Pattern {
    pub matrix: SparseMatrix,
    /// Cell i's local entry (a, b) of its nd × nd matrix is at `scatter_start[i] + a nd + b`.
    pub scatter_start: Vec<usize>,
    /// Position in the matrix values, NONE (a fixed dof, or above the diagonal with
    /// `lower_only`) or LINKED (involves a linked dof: the slow path).
    pub scatter: Vec<u32>,
}

/// The pattern of the cells' couplings (the free unknowns each touches, linked dofs
/// expanded); with `lower_only` only rows ≥ column are kept.
pub fn build(mesh: &Mesh, cells: &[usize], dofs: &DofMap, lower_only: bool) -> Pattern {
    let nf = dofs.num_free;
    // Free unknowns touched by each cell, sorted and unique.
    let (mut tmp, mut set) = (vec![], vec![]);
    let mut touched_start = vec![0usize];
    let mut touched = vec![];
    for &c in cells {
        set.clear();
        for &n in mesh.cell_nodes(c) {
            for comp in 0..2 {
                dofs.expand_dof(2 * n + comp, &mut tmp);
                set.extend(tmp.iter().map(|t| t.0));
            }
        }
        set.sort_unstable();
        set.dedup();
        touched.extend_from_slice(&set);
        touched_start.push(touched.len());
    }
    let cell_touched = |i: usize| &touched[touched_start[i]..touched_start[i + 1]];
    // free unknown → cells touching it
    let (count, cells_of) = group_by_key(
        nf,
        (0..cells.len()).flat_map(|i| cell_touched(i).iter().map(move |&j| (j, i))),
    );
    // Each column: the union of its cells' touched unknowns, sorted. Column ranges in
    // parallel, each into its own flat arrays, then concatenated.
    let ranges: Vec<(usize, usize)> = (0..CHUNKS)
        .map(|k| (k * nf / CHUNKS, (k + 1) * nf / CHUNKS))
        .collect();
    let parts: Vec<(Vec<usize>, Vec<usize>)> = ranges
        .par_iter()
        .map(|&(j0, j1)| {
            let mut mark = vec![usize::MAX; nf];
            let mut lens = Vec::with_capacity(j1 - j0);
            let mut rows = vec![];
            for j in j0..j1 {
                let first = rows.len();
                for &i in &cells_of[count[j]..count[j + 1]] {
                    for &k in cell_touched(i) {
                        if mark[k] != j && (!lower_only || k >= j) {
                            mark[k] = j;
                            rows.push(k);
                        }
                    }
                }
                if rows.len() == first {
                    rows.push(j);
                }
                rows[first..].sort_unstable();
                lens.push(rows.len() - first);
            }
            (lens, rows)
        })
        .collect();
    let mut col_ptr = Vec::with_capacity(nf + 1);
    col_ptr.push(0);
    let mut row_idx = Vec::with_capacity(parts.iter().map(|p| p.1.len()).sum());
    for (lens, rows) in parts {
        for l in lens {
            col_ptr.push(col_ptr.last().unwrap() + l);
        }
        row_idx.extend_from_slice(&rows);
    }
    let nnz = row_idx.len();
    let matrix = SparseMatrix {
        n: nf,
        col_ptr,
        row_idx,
        values: vec![0.0; nnz],
        pattern_stamp: new_pattern_stamp(),
    };
    let scatter_start: Vec<usize> = std::iter::once(0)
        .chain(cells.iter().scan(0, |end, &c| {
            let nd = 2 * mesh.cell_nodes(c).len();
            *end += nd * nd;
            Some(*end)
        }))
        .collect();
    let mut scatter = vec![NONE; *scatter_start.last().unwrap()];
    // Per cell, its slice of `scatter`: cell ranges in parallel.
    let mut slices: Vec<&mut [u32]> = Vec::with_capacity(cells.len());
    let mut rest = scatter.as_mut_slice();
    for i in 0..cells.len() {
        let (head, tail) = rest.split_at_mut(scatter_start[i + 1] - scatter_start[i]);
        slices.push(head);
        rest = tail;
    }
    let m = &matrix;
    let per_task = cells.len().div_ceil(CHUNKS).max(1);
    slices
        .par_chunks_mut(per_task)
        .enumerate()
        .for_each(|(k, chunk)| {
            let mut roles = vec![];
            let mut free = vec![];
            for (o, out) in chunk.iter_mut().enumerate() {
                let c = cells[k * per_task + o];
                cell_positions(
                    m,
                    mesh.cell_nodes(c),
                    dofs,
                    lower_only,
                    &mut roles,
                    &mut free,
                    out,
                );
            }
        });
    Pattern {
        matrix,
        scatter_start,
        scatter,
    }
}

/// One cell's scatter positions (`out`, nd × nd, NONE on entry). Its free local dofs sorted
/// by unknown; each free column is walked once alongside them.
fn cell_positions(
    m: &SparseMatrix,
    nodes: &[usize],
    dofs: &DofMap,
    lower_only: bool,
    roles: &mut Vec<Role>,
    free: &mut Vec<(usize, usize)>,
    out: &mut [u32],
) {
    let nd = 2 * nodes.len();
    roles.clear();
    roles.extend((0..nd).map(|a| dofs.roles[2 * nodes[a / 2] + a % 2]));
    free.clear();
    for (a, role) in roles.iter().enumerate() {
        if let Role::Free(i) = role {
            free.push((*i, a));
        }
    }
    free.sort_unstable();
    for a in 0..nd {
        for b in 0..nd {
            let linked = !matches!(
                (roles[a], roles[b]),
                (Role::Fixed, _) | (_, Role::Fixed) | (Role::Free(_), Role::Free(_))
            );
            if linked {
                out[a * nd + b] = LINKED;
            }
        }
    }
    for &(j, b) in free.iter() {
        let mut q = m.col_ptr[j];
        for &(i, a) in free.iter() {
            if lower_only && i < j {
                continue;
            }
            // every free unknown of the cell is a row of its free columns (≥ j if lower)
            while m.row_idx[q] < i {
                q += 1;
            }
            debug_assert_eq!(m.row_idx[q], i);
            out[a * nd + b] = q as u32;
        }
    }
}
