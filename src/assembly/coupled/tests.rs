//! Tests of the combined matrix: against fresh combinations, through rebuilds, with
//! fixed and linked dofs.

use super::*;

#[test]
fn clique_union_sends_each_entry_once() {
    let sets = vec![vec![0, 2, 5], vec![2, 5, 7], vec![9], vec![5, 0]];
    let mut t = Triplets::default();
    t.add_clique_union(&sets);
    let mut got: Vec<(usize, usize)> = t.entries.iter().map(|e| (e.0, e.1)).collect();
    assert!(t.entries.iter().all(|e| e.2 == 0.0));
    let n = got.len();
    got.sort_unstable();
    got.dedup();
    assert_eq!(got.len(), n, "no entry twice");
    let mut expected: Vec<(usize, usize)> = sets
        .iter()
        .flat_map(|s| s.iter().flat_map(move |&r| s.iter().map(move |&c| (r, c))))
        .collect();
    expected.sort_unstable();
    expected.dedup();
    assert_eq!(got, expected);
}

#[test]
fn sorted_unique_columns_equals_sort_and_dedup() {
    let pairs: Vec<(usize, usize)> = (0..500u64)
        .map(|i| {
            let h = i.wrapping_mul(2654435761) ^ (i >> 3);
            ((h % 37) as usize, ((h / 37) % 41) as usize)
        })
        .collect();
    let mut expected = pairs.clone();
    expected.sort_unstable();
    expected.dedup();
    assert!(
        expected.len() < pairs.len(),
        "the sample has repeated pairs"
    );
    let (ptr, rows) = rebuild::sorted_unique_columns(41, pairs.iter().copied());
    let got: Vec<(usize, usize)> = (0..41)
        .flat_map(|c| rows[ptr[c]..ptr[c + 1]].iter().map(move |&r| (c, r)))
        .collect();
    assert_eq!(got, expected);
}

/// A tridiagonal solid matrix over 6 free dofs (3 nodes), as assembled (`scale` on its
/// values), and a cell scatter naming each of its entries once.
fn solid(scale: f64) -> (SparseMatrix, Vec<u32>) {
    let mut entries = vec![];
    for i in 0..6 {
        entries.push((i, i, (4.0 + i as f64 * 0.1) * scale));
        if i > 0 {
            let v = (-1.0 - i as f64 * 0.01) * scale;
            entries.push((i, i - 1, v));
            entries.push((i - 1, i, v));
        }
    }
    let m = SparseMatrix::from_entries(6, &entries);
    let scatter = (0..m.nnz() as u32).chain([RESERVED]).collect();
    (m, scatter)
}

const RESERVED: u32 = u32::MAX - 1;

fn target<'a>(m: &'a mut SparseMatrix, cells: &'a mut [u32], generation: u64) -> SolidTarget<'a> {
    SolidTarget {
        matrix: m,
        generation,
        cell_scatter: cells,
        reserved: RESERVED,
    }
}

/// The combined matrix of `solid(scale)` and the triplets, built in one update.
fn fresh(history: &[fn(&mut Triplets)], scale: f64) -> SparseMatrix {
    let dofs = DofMap::new(&[true; 6], &[], &[]).unwrap();
    let (mut m, mut cells) = solid(scale);
    let mut c = CoupledMatrix::default();
    let mut t = Triplets::default();
    for (g, fill) in history.iter().enumerate() {
        t.clear();
        fill(&mut t);
        if g > 0 {
            // a new assembly: every value zeroed, the solid ones written again
            let (s, _) = solid(scale);
            m.values.iter_mut().for_each(|v| *v = 0.0);
            for (k, &q) in cells.iter().enumerate().take(s.nnz()) {
                m.values[q as usize] = s.values[k];
            }
        }
        c.update(target(&mut m, &mut cells, g as u64), &dofs, 1, &t)
            .unwrap();
    }
    m
}

fn first(t: &mut Triplets) {
    t.add(1, 6, 1.0);
    t.add(6, 1, 1.0);
    t.add(4, 6, -0.5);
    t.add(6, 4, -0.5);
    t.add(1, 4, 0.3);
}
/// The same entries with other values.
fn second(t: &mut Triplets) {
    t.add(1, 6, 0.7);
    t.add(6, 1, 0.7);
    t.add(4, 6, 0.0);
    t.add(6, 4, 0.0);
    t.add(1, 4, -0.2);
}
/// Another set inside the same pattern.
fn third(t: &mut Triplets) {
    t.add(6, 6, 2.5);
    t.add(1, 4, 0.9);
}
/// An entry outside it (a rebuild).
fn fourth(t: &mut Triplets) {
    t.add(0, 6, 0.4);
    t.add(6, 0, 0.4);
    t.add(5, 2, 0.1);
}

/// Re-combining the same solid values with other triplets (an active-set re-solve),
/// with or without a rebuild, gives exactly the values of a fresh combination, and the
/// assembler's scatter follows the solid entries into the extended pattern.
#[test]
fn update_with_unchanged_solid_equals_fresh_combination() {
    let dofs = DofMap::new(&[true; 6], &[], &[]).unwrap();
    let (mut m, mut cells) = solid(1.0);
    let (solid0, _) = solid(1.0);
    let mut reused = CoupledMatrix::default();
    let mut t = Triplets::default();
    let mut history: Vec<fn(&mut Triplets)> = vec![first];
    first(&mut t);
    reused
        .update(target(&mut m, &mut cells, 7), &dofs, 1, &t)
        .unwrap();
    for fill in [second as fn(&mut Triplets), third, fourth] {
        t.clear();
        fill(&mut t);
        reused
            .update(target(&mut m, &mut cells, 7), &dofs, 1, &t)
            .unwrap();
        history.push(fill);
        // the fresh one sees the same pattern history, each with a new assembly
        let fresh = fresh(&history, 1.0);
        assert_eq!(m.col_ptr, fresh.col_ptr);
        assert_eq!(m.row_idx, fresh.row_idx);
        assert_eq!(m.values, fresh.values);
        // each cell entry lands where its solid entry now is
        for (k, &q) in cells.iter().enumerate().take(solid0.nnz()) {
            let (c, r) = (0..6)
                .flat_map(|c| (solid0.col_ptr[c]..solid0.col_ptr[c + 1]).map(move |p| (c, p)))
                .find(|&(_, p)| p == k)
                .map(|(c, p)| (c, solid0.row_idx[p]))
                .unwrap();
            assert_eq!(Some(q as usize), m.position(r, c));
        }
        assert_eq!(cells.last(), Some(&RESERVED), "a reserved value stays");
    }
    assert_eq!(
        reused.rebuilds, 2,
        "the fourth set alone leaves the pattern"
    );
}

/// New solid values (a new assembly) in the extended matrix: the contact terms are
/// added to them, not to the old ones.
#[test]
fn a_new_assembly_in_the_extended_matrix_takes_the_new_solid_values() {
    let history: [fn(&mut Triplets); 2] = [first, second];
    let reassembled = fresh(&history, 2.0);
    let dofs = DofMap::new(&[true; 6], &[], &[]).unwrap();
    let (mut m, mut cells) = solid(2.0);
    let mut c = CoupledMatrix::default();
    let mut t = Triplets::default();
    second(&mut t);
    c.update(target(&mut m, &mut cells, 0), &dofs, 1, &t)
        .unwrap();
    // same pattern (the first triplets' entries are the second's)
    assert_eq!(m.row_idx, reassembled.row_idx);
    assert_eq!(m.values, reassembled.values);
}

/// Triplets on a fixed dof (no target) and on a linked one (a target per term, with
/// its coefficient) land as an explicit expansion puts them.
#[test]
fn triplets_on_fixed_and_linked_dofs_expand_to_their_targets() {
    use crate::assembly::dofs::Relation;
    // 8 dofs: dof 6 fixed, 2 u7 − u4 − u5 = 0 (one of the three eliminated): 6 free
    let link = Relation {
        terms: vec![(7, 2.0), (4, -1.0), (5, -1.0)],
        rhs: 0.0,
        name: "mean".into(),
    };
    let dofs = DofMap::new(&[true; 8], &[(6, 0.0)], &[link]).unwrap();
    assert_eq!(dofs.num_free, 6);
    let (mut m, mut cells) = solid(1.0);
    let (solid0, _) = solid(1.0);
    let mut t = Triplets::default();
    // extended ids: dofs 0–7, the extra unknown 8
    for (r, c, v) in [
        (6, 8, 0.5),
        (8, 6, 0.5),
        (7, 8, 1.5),
        (8, 7, 1.5),
        (4, 7, 0.25),
    ] {
        t.add(r, c, v);
    }
    t.add(8, 8, -2.0);
    let mut c = CoupledMatrix::default();
    c.update(target(&mut m, &mut cells, 0), &dofs, 1, &t)
        .unwrap();
    assert!(!c.targets.ptr.is_empty(), "not one target per triplet");
    let mut expected = vec![vec![0.0; 7]; 7];
    for j in 0..6 {
        for p in solid0.col_ptr[j]..solid0.col_ptr[j + 1] {
            expected[solid0.row_idx[p]][j] = solid0.values[p];
        }
    }
    let expand = |id: usize| {
        let mut out = vec![];
        if id < 8 {
            dofs.expand_dof(id, &mut out);
        } else {
            out.push((6, 1.0));
        }
        out
    };
    for &(r, c, v) in &t.entries {
        for (i, ci) in expand(r) {
            for (j, cj) in expand(c) {
                expected[i][j] += ci * cj * v;
            }
        }
    }
    for (i, row) in expected.iter().enumerate() {
        for (j, &e) in row.iter().enumerate() {
            let got = m.position(i, j).map_or(0.0, |q| m.values[q]);
            assert_eq!(got, e, "entry ({i}, {j})");
        }
    }
}

/// Keyed groups (one per contact point) whose statuses come and go, change their
/// entries, move in the sequence, and leave the pattern: after every update the matrix
/// equals the one the same triplets give without groups, with plain and with linked dofs
/// (several targets per triplet); and a group's targets found before a rebuild are not
/// taken after it.
#[test]
fn grouped_triplets_give_the_values_of_ungrouped_ones() {
    use crate::assembly::dofs::Relation;
    type Group = (u64, Vec<(usize, usize, f64)>);
    let states: Vec<Vec<Group>> = vec![
        vec![
            (0, vec![(1, 6, 1.0), (6, 1, 1.0)]),
            (1, vec![(4, 6, -0.5), (6, 4, -0.5), (1, 4, 0.3)]),
        ],
        // point 0 off, point 1 the same entries with other values, point 2 on
        vec![
            (1, vec![(4, 6, 0.2), (6, 4, 0.2), (1, 4, -0.1)]),
            (2, vec![(6, 6, 2.5)]),
        ],
        // point 1 with fewer entries, point 0 back after it with other values
        vec![(1, vec![(1, 4, 0.9)]), (0, vec![(1, 6, 0.4), (6, 1, 0.4)])],
        // an entry outside the pattern: a rebuild moves every position
        vec![
            (0, vec![(1, 6, 1.0), (6, 1, 1.0), (0, 5, 0.7)]),
            (1, vec![(4, 6, -0.5), (6, 4, -0.5), (1, 4, 0.3)]),
        ],
        // point 2 back: its targets found before the rebuild no longer hold
        vec![
            (0, vec![(1, 6, 1.0), (6, 1, 1.0)]),
            (1, vec![(4, 6, -0.5), (6, 4, -0.5), (1, 4, 0.3)]),
            (2, vec![(6, 6, 1.5)]),
        ],
    ];
    let link = Relation {
        terms: vec![(7, 2.0), (4, -1.0), (5, -1.0)],
        rhs: 0.0,
        name: "mean".into(),
    };
    let plain = DofMap::new(&[true; 6], &[], &[]).unwrap();
    let linked = DofMap::new(&[true; 8], &[(6, 0.0)], &[link]).unwrap();
    for (dofs, extra) in [(&plain, 6), (&linked, 8)] {
        let (mut m, mut cells) = solid(1.0);
        let (mut m0, mut cells0) = solid(1.0);
        let (mut grouped, mut ungrouped) = (CoupledMatrix::default(), CoupledMatrix::default());
        let (mut t, mut t0) = (Triplets::default(), Triplets::default());
        for state in &states {
            t.clear();
            t0.clear();
            t.begin_pair(0);
            for (key, entries) in state {
                t.group(*key);
                // (the extra unknown's id is the dofs' count)
                let id = |i: usize| if i == 6 { extra } else { i };
                for &(r, c, v) in entries {
                    t.add(id(r), id(c), v);
                    t0.add(id(r), id(c), v);
                }
            }
            t.ungrouped();
            t.add(2, 2, 0.125);
            t0.add(2, 2, 0.125);
            grouped
                .update(target(&mut m, &mut cells, 3), dofs, 1, &t)
                .unwrap();
            ungrouped
                .update(target(&mut m0, &mut cells0, 3), dofs, 1, &t0)
                .unwrap();
            assert_eq!(m.col_ptr, m0.col_ptr);
            assert_eq!(m.row_idx, m0.row_idx);
            assert_eq!(m.values, m0.values);
        }
        assert_eq!(grouped.rebuilds, 2, "the first state and the fourth");
        // point 1 in the second state and the last, point 0 in the third
        assert_eq!(grouped.groups.reused, 3, "unchanged groups' targets kept");
    }
}
