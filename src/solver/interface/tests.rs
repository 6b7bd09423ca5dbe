//! Tests of the interface solve: exactness on a non-symmetric saddle point, storage
//! reuse, rebinding a changed pattern.

use super::*;
use crate::solver::linear::transpose_positions;

/// Two chains of springs (bodies) of `len` unknowns each; the second is held only
/// through two multipliers tying its first unknowns to the first chain's last ones,
/// with a non-symmetric friction-like term between the tied unknowns; a third
/// multiplier is decoupled (an open point).
fn two_bodies(len: usize) -> SparseMatrix {
    SparseMatrix::from_entries(2 * len + 3, &two_bodies_entries(len))
}

fn two_bodies_entries(len: usize) -> Vec<(usize, usize, f64)> {
    let mut e: Vec<(usize, usize, f64)> = vec![];
    for body in 0..2 {
        let o = body * len;
        for i in 0..len {
            let support = if body == 0 && i == 0 { 1.0 } else { 0.0 };
            let ends = if i == 0 || i + 1 == len { 1.0 } else { 2.0 };
            e.push((o + i, o + i, ends + support + 0.01 * i as f64));
            if i + 1 < len {
                e.push((o + i, o + i + 1, -1.0));
                e.push((o + i + 1, o + i, -1.0));
            }
        }
    }
    let m = 2 * len;
    for k in 0..2 {
        let (a, b) = (len - 1 - k, len + k); // tied pair
        e.push((m + k, a, 1.0));
        e.push((a, m + k, 1.0));
        e.push((m + k, b, -1.0));
        e.push((b, m + k, -1.0));
        e.push((m + k, m + k, 0.0));
        e.push((a, b, 0.3)); // non-symmetric coupling
        e.push((b, a, -0.2));
    }
    e.push((m + 2, m + 2, 2.0)); // an open contact point: decoupled multiplier
    e
}

#[test]
fn interface_solve_is_exact_on_a_nonsymmetric_saddle_point_system() {
    let len = 30;
    let a = two_bodies(len);
    let t = transpose_positions(&a);
    let in_gamma = interface_of(&a, 2 * len, &t).expect("small interface");
    let mut s = InterfaceSolver::new(&a, in_gamma, Storage::default()).unwrap();
    assert_eq!(s.blocks.len(), 2, "the chains are two blocks");
    assert_eq!(
        s.gamma.len(),
        4 + 3,
        "four tied unknowns and three multipliers"
    );
    s.factor(&a).unwrap();
    assert_eq!(
        s.base.at.iter().filter(|&&p| p == NONE).count(),
        1,
        "the open point's multiplier is solved alone"
    );
    let x: Vec<f64> = (0..a.n).map(|i| (0.37 * i as f64).sin() + 0.5).collect();
    let mut b = vec![0.0; a.n];
    a.mul_vec(&x, &mut b);
    s.solve(&mut b);
    let err = b
        .iter()
        .zip(&x)
        .fold(0.0f64, |m, (u, v)| m.max((u - v).abs()));
    assert!(err < 1e-12, "max error {err}");

    // An active-set re-solve: new interface values (a multiplier's row), a right-hand
    // side changed in the interface rows only. The blocks' factorisations and forward
    // passes are reused; the result still solves the new system.
    let mut a2 = a.clone();
    let m = 2 * len;
    let p = a2.position(m + 2, m + 2).unwrap();
    a2.values[p] = 5.0;
    let mut b2 = vec![0.0; a.n];
    a.mul_vec(&x, &mut b2);
    for &g in &s.gamma {
        b2[g] += 0.25 * (g as f64).cos();
    }
    s.factor(&a2).unwrap();
    let res = solve_residual(&mut s, &a2, &b2);
    assert!(s.blocks.iter().all(|blk| blk.last_forward.is_some()));
    assert!(res < 1e-12, "max residual {res}");
}

/// The largest entry of a2 x − b, x solved by `s` (factorised already).
fn solve_residual(s: &mut InterfaceSolver, a: &SparseMatrix, b: &[f64]) -> f64 {
    let mut x = b.to_vec();
    s.solve(&mut x);
    let mut r = vec![0.0; a.n];
    a.mul_vec(&x, &mut r);
    r.iter()
        .zip(b)
        .fold(0.0f64, |m, (u, v)| m.max((u - v).abs()))
}

/// The largest error of a solve of `a` by `s` (factorised here) with a known solution.
fn solve_error(s: &mut InterfaceSolver, a: &SparseMatrix) -> f64 {
    s.factor(a).unwrap();
    let x: Vec<f64> = (0..a.n).map(|i| (0.61 * i as f64).cos() - 0.2).collect();
    let mut b = vec![0.0; a.n];
    a.mul_vec(&x, &mut b);
    s.solve(&mut b);
    b.iter()
        .zip(&x)
        .fold(0.0f64, |m, (u, v)| m.max((u - v).abs()))
}

#[test]
fn an_analysis_in_the_storage_of_another_solves_exactly() {
    // the blocks' factors of a larger analysis serve a smaller one, then the other way
    // round (they grow)
    let mut storage = Storage::default();
    for len in [40, 20, 50] {
        let a = two_bodies(len);
        let t = transpose_positions(&a);
        let in_gamma = interface_of(&a, 2 * len, &t).expect("small interface");
        let mut s = InterfaceSolver::new(&a, in_gamma, storage).unwrap();
        let err = solve_error(&mut s, &a);
        assert!(err < 1e-12, "{len} unknowns per body: max error {err}");
        storage = s.into_storage();
        assert_eq!(storage.factors.len(), 2, "each block's factor is kept");
    }
}

#[test]
fn the_interface_matrix_follows_the_coupled_unknowns() {
    // A tied point that opens (its multiplier's couplings zero, its row λ = 0) and closes
    // again: the interface matrix is built for the coupled unknowns only, so it shrinks,
    // then grows past its storage; each solve stays exact.
    let len = 25;
    let a = two_bodies(len);
    let m = 2 * len;
    let mut open = a.clone();
    for (r, c) in [(m, len - 1), (len - 1, m), (m, len), (len, m)] {
        let p = open.position(r, c).unwrap();
        open.values[p] = 0.0;
    }
    let p = open.position(m, m).unwrap();
    open.values[p] = 3.0;
    let t = transpose_positions(&a);
    let in_gamma = interface_of(&a, 2 * len, &t).expect("small interface");
    let mut s = InterfaceSolver::new(&a, in_gamma, Storage::default()).unwrap();
    for (matrix, decoupled) in [(&open, 2), (&a, 1), (&open, 2)] {
        let err = solve_error(&mut s, matrix);
        assert_eq!(s.base.at.iter().filter(|&&p| p == NONE).count(), decoupled);
        assert_eq!(s.base.kept.len() + decoupled, s.gamma.len());
        assert!(err < 1e-12, "{decoupled} decoupled: max error {err}");
    }
}

#[test]
fn too_large_an_interface_is_declined() {
    // every unknown coupled to a multiplier: nothing to condense
    let len = 3;
    let a = two_bodies(len);
    let t = transpose_positions(&a);
    assert!(interface_of(&a, 2 * len, &t).is_none());
}

#[test]
fn a_pattern_changed_between_interface_unknowns_keeps_the_analysis() {
    let len = 30;
    let m = 2 * len;
    let a = two_bodies(len);
    let t = transpose_positions(&a);
    let in_gamma = interface_of(&a, m, &t).expect("small interface");
    let mut s = InterfaceSolver::new(&a, in_gamma, Storage::default()).unwrap();
    assert!(solve_error(&mut s, &a) < 1e-12);
    let with = |extra: &[(usize, usize, f64)], body_scale: f64| {
        let mut e = two_bodies_entries(len);
        for entry in e.iter_mut().filter(|(r, c, _)| *r < m && *c < m) {
            entry.2 *= body_scale;
        }
        e.extend_from_slice(extra);
        SparseMatrix::from_entries(m + 3, &e)
    };
    // the open point closes on the first chain's last unknown (both in the interface):
    // a new pattern, the same blocks, their values unchanged
    let closing = [(m + 2, len - 1, 1.0), (len - 1, m + 2, 1.0)];
    let a2 = with(&closing, 1.0);
    assert_ne!(a2.row_idx, a.row_idx, "the pattern changed");
    assert!(s.rebind(&a2, &interface_searched(&a2, m).unwrap()));
    s.factor(&a2).unwrap();
    assert!(
        s.blocks.iter().all(|b| b.last_forward.is_some()),
        "the blocks' factorisations are kept"
    );
    let b: Vec<f64> = (0..a2.n).map(|i| (0.3 * i as f64).sin()).collect();
    let res = solve_residual(&mut s, &a2, &b);
    assert!(res < 1e-12, "max residual {res}");
    // the same pattern change with the bodies' values changed: refactorised, exact
    let a3 = with(&closing, 1.5);
    let mut s3 =
        InterfaceSolver::new(&a, interface_searched(&a, m).unwrap(), Storage::default()).unwrap();
    assert!(solve_error(&mut s3, &a) < 1e-12);
    assert!(s3.rebind(&a3, &interface_searched(&a3, m).unwrap()));
    let err = solve_error(&mut s3, &a3);
    assert!(err < 1e-12, "max error {err}");
    // a new entry inside a body: its block's pattern changed, a new analysis is needed
    let a4 = with(&[(2, 5, -0.1), (5, 2, -0.1)], 1.0);
    let mut s4 =
        InterfaceSolver::new(&a, interface_searched(&a, m).unwrap(), Storage::default()).unwrap();
    assert!(!s4.rebind(&a4, &interface_searched(&a4, m).unwrap()));
    // an interface that grew (a body unknown coupled to a multiplier): the same
    let a5 = with(&[(m + 2, 7, 1.0), (7, m + 2, 1.0)], 1.0);
    let mut s5 =
        InterfaceSolver::new(&a, interface_searched(&a, m).unwrap(), Storage::default()).unwrap();
    assert!(!s5.rebind(&a5, &interface_searched(&a5, m).unwrap()));
}

#[test]
fn a_grown_pattern_with_zero_new_entries_keeps_the_analysis_while_they_stay_zero() {
    let len = 30;
    let m = 2 * len;
    let a = two_bodies(len);
    let analysed = || {
        let mut s =
            InterfaceSolver::new(&a, interface_searched(&a, m).unwrap(), Storage::default())
                .unwrap();
        assert!(solve_error(&mut s, &a) < 1e-12);
        s
    };
    let with = |extra: &[(usize, usize, f64)]| {
        let mut e = two_bodies_entries(len);
        e.extend_from_slice(extra);
        SparseMatrix::from_entries(m + 3, &e)
    };
    // the open point comes within reach of two unknowns inside the first chain, and of
    // one inside the second (couplings in the pattern, zero: not in contact), and the
    // contact tangent couples two body unknowns not coupled before (zero too)
    let reach = [
        (m + 2, 7, 0.0),
        (7, m + 2, 0.0),
        (m + 2, 8, 0.0),
        (8, m + 2, 0.0),
        (m + 2, len + 9, 0.0),
        (len + 9, m + 2, 0.0),
        (7, 12, 0.0),
        (12, 7, 0.0),
    ];
    let grown = with(&reach);
    let in_gamma = interface_searched(&grown, m).unwrap();
    assert!(in_gamma[7] && in_gamma[len + 9], "the interface grew");
    let mut s = analysed();
    assert!(!s.rebind(&grown, &in_gamma), "not the same blocks");
    let mut s = analysed();
    assert!(s.rebind_grown(&grown, &in_gamma));
    assert!(s.stands(&grown));
    s.factor(&grown).unwrap();
    assert!(
        s.blocks.iter().all(|b| b.last_forward.is_some()),
        "the blocks' factorisations are kept"
    );
    let b: Vec<f64> = (0..grown.n).map(|i| (0.3 * i as f64).sin()).collect();
    let res = solve_residual(&mut s, &grown, &b);
    assert!(res < 1e-12, "max residual {res}");
    // the open point's multiplier changes (an interface entry): the analysis stands
    let mut again = grown.clone();
    again.values[grown.position(m + 2, m + 2).unwrap()] = 3.0;
    assert!(s.stands(&again));
    let err = solve_error(&mut s, &again);
    assert!(err < 1e-12, "max error {err}");
    // any of the new entries no longer zero, or a joined unknown's entry no longer
    // symmetric (either of the pair): a new analysis is needed
    for (r, c) in [
        (m + 2, 8),
        (8, m + 2),
        (len + 9, m + 2),
        (12, 7),
        (7, 6),
        (6, 7),
    ] {
        let mut closing = again.clone();
        closing.values[grown.position(r, c).unwrap()] = 0.5;
        assert!(!s.stands(&closing), "entry ({r}, {c})");
    }
    // the bodies to be factorised anyway: a new analysis (it costs no more then)
    let mut loaded = again.clone();
    loaded.values[grown.position(3, 3).unwrap()] *= 1.5;
    assert!(!s.stands(&loaded));
    // a new entry not zero, or one against the bodies' last values: not taken
    let mut closed = grown.clone();
    closed.values[grown.position(m + 2, 7).unwrap()] = 1.0;
    closed.values[grown.position(7, m + 2).unwrap()] = 1.0;
    assert!(!analysed().rebind_grown(&closed, &in_gamma));
    let mut moved = grown.clone();
    moved.values[grown.position(3, 3).unwrap()] *= 1.5;
    assert!(!analysed().rebind_grown(&moved, &in_gamma));
}

#[test]
fn the_searched_interface_is_the_one_from_transpose_positions() {
    let a = two_bodies(30);
    let t = transpose_positions(&a);
    assert_eq!(interface_of(&a, 60, &t), interface_searched(&a, 60));
}

/// The entries of the two chains of `two_bodies` alone (no ties).
fn two_chains_entries(len: usize) -> Vec<(usize, usize, f64)> {
    two_bodies_entries(len)
        .into_iter()
        .filter(|&(r, c, _)| r < 2 * len && c < 2 * len)
        .filter(|&(r, c, _)| r == c || (r < len) == (c < len))
        .collect()
}

/// Two chains of `len` springs tied at `ties` pairs of unknowns by multipliers (each with
/// a non-symmetric friction-like coupling): an interface of 3 × `ties` unknowns. The ties
/// in `open` are open: their multiplier's couplings zero, its row λ = 0.
fn tied_chains(len: usize, ties: usize, open: &[usize]) -> SparseMatrix {
    SparseMatrix::from_entries(2 * len + ties, &tied_chains_entries(len, ties, open))
}

fn tied_chains_entries(len: usize, ties: usize, open: &[usize]) -> Vec<(usize, usize, f64)> {
    let mut e = two_chains_entries(len);
    let m = 2 * len;
    for k in 0..ties {
        let (a, b) = (len - 1 - k, len + k);
        let w = if open.contains(&k) { 0.0 } else { 1.0 };
        e.extend([(m + k, a, w), (a, m + k, w), (m + k, b, -w), (b, m + k, -w)]);
        e.push((m + k, m + k, 3.0 * (1.0 - w)));
        e.extend([(a, b, 0.3 * w), (b, a, -0.2 * w)]);
    }
    e
}

/// A re-solve with the ties `open` changed since the first LU: as exact as a new LU, and
/// by an update of the first one exactly when some tie changed.
fn check_update(s: &InterfaceSolver, err: f64, open: &[usize]) {
    assert!(err < 1e-11, "open {open:?}: max error {err}");
    assert_eq!(
        s.update.is_some(),
        !open.is_empty(),
        "open {open:?}: the first LU serves with an update"
    );
}

#[test]
fn a_re_solve_updates_the_interface_lu_and_stays_exact() {
    // Ties open and close between factorisations with the same blocks (active-set
    // re-solves): the LU of the first matrix and a low-rank change solve each of the
    // others, as exactly as a new factorisation would.
    let (len, ties) = (200, 20);
    let first = tied_chains(len, ties, &[]);
    let t = transpose_positions(&first);
    let in_gamma = interface_of(&first, 2 * len, &t).expect("small interface");
    let mut s = InterfaceSolver::new(&first, in_gamma, Storage::default()).unwrap();
    let err = solve_error(&mut s, &first);
    assert!(err < 1e-12, "first factorisation: max error {err}");
    assert!(s.update.is_none());
    for open in [vec![3], vec![3, 11], vec![11], vec![]] {
        let a = tied_chains(len, ties, &open);
        let err = solve_error(&mut s, &a);
        check_update(&s, err, &open);
    }
    // too many rows changed: a new LU
    let many: Vec<usize> = (0..ties).step_by(2).collect();
    let a = tied_chains(len, ties, &many);
    let err = solve_error(&mut s, &a);
    assert!(err < 1e-12, "many open: max error {err}");
    assert!(s.update.is_none(), "many open: a new LU");
}

/// As `tied_chains`, but an open tie's multiplier couplings are out of the pattern (a
/// contact pattern change between interface unknowns: the tied unknowns stay in the
/// interface through their friction-like coupling).
fn tied_chains_sparse(len: usize, ties: usize, open: &[usize]) -> SparseMatrix {
    let mut e = two_chains_entries(len);
    let m = 2 * len;
    for k in 0..ties {
        let (a, b) = (len - 1 - k, len + k);
        if open.contains(&k) {
            e.push((m + k, m + k, 3.0));
        } else {
            e.extend([(m + k, a, 1.0), (a, m + k, 1.0), (m + k, b, -1.0)]);
            e.extend([(b, m + k, -1.0), (m + k, m + k, 0.0)]);
        }
        e.extend([(a, b, 0.3), (b, a, -0.2)]);
    }
    SparseMatrix::from_entries(2 * len + ties, &e)
}

#[test]
fn a_re_solve_across_a_contact_pattern_change_updates_the_interface_lu() {
    // Ties open (their couplings leave the pattern) and close again between
    // factorisations with the same blocks: after each rebind the first LU and a low-rank
    // change, entries gone from the pattern included, solve as exactly as a new LU.
    let (len, ties) = (200, 20);
    let first = tied_chains_sparse(len, ties, &[]);
    let in_gamma = interface_searched(&first, 2 * len).expect("small interface");
    let mut s = InterfaceSolver::new(&first, in_gamma, Storage::default()).unwrap();
    assert!(solve_error(&mut s, &first) < 1e-12);
    for open in [vec![3], vec![3, 11], vec![11], vec![]] {
        let a = tied_chains_sparse(len, ties, &open);
        assert_eq!(a.nnz() == first.nnz(), open.is_empty(), "a pattern change");
        let in_gamma = interface_searched(&a, 2 * len).expect("small interface");
        assert!(s.rebind(&a, &in_gamma), "open {open:?}: the same blocks");
        let err = solve_error(&mut s, &a);
        check_update(&s, err, &open);
    }
}

#[test]
fn a_change_in_rows_of_unlike_sizes_still_updates_the_interface_lu() {
    // The multiplier rows of half the ties in other units (a factor 1e9: a constraint
    // row scaled by a stiffness): C's rows then differ in size as much, which says
    // nothing of its conditioning; the update serves and stays exact.
    let (len, ties) = (200, 20);
    let scaled = |open: &[usize]| {
        let mut a = tied_chains(len, ties, open);
        for c in 0..a.n {
            for p in a.col_ptr[c]..a.col_ptr[c + 1] {
                let r = a.row_idx[p];
                if r >= 2 * len && (r - 2 * len).is_multiple_of(2) {
                    a.values[p] *= 1e9;
                }
            }
        }
        a
    };
    let first = scaled(&[]);
    let t = transpose_positions(&first);
    let in_gamma = interface_of(&first, 2 * len, &t).expect("small interface");
    let mut s = InterfaceSolver::new(&first, in_gamma, Storage::default()).unwrap();
    assert!(solve_error(&mut s, &first) < 1e-12);
    let a = scaled(&[2, 3]);
    let err = solve_error(&mut s, &a);
    assert!(err < 1e-11, "max error {err}");
    assert!(s.update.is_some(), "the first LU serves with an update");
}

/// An interface solver of `a` (primal unknowns before `np`) that knows its multipliers,
/// as after `lus` LUs with the bodies kept (the reduction pays only where such follow).
fn knowing_multipliers(a: &SparseMatrix, np: usize, lus: usize) -> InterfaceSolver {
    let t = transpose_positions(a);
    let in_gamma = interface_of(a, np, &t).expect("small interface");
    let mut s = InterfaceSolver::new(a, in_gamma, Storage::default())
        .unwrap()
        .with_multipliers_from(np);
    s.lus_with_bodies_kept = lus;
    s
}

#[test]
fn the_interface_matrix_reduced_onto_its_live_unknowns_solves_exactly() {
    // Most ties open: their tied unknowns carry no contact term and are reduced away;
    // a later matrix that changes the live rows only (ties that close or open next to
    // the closed ones) is a new LU of the live part; one that closes ties among the
    // passive unknowns is a new reduction. Every solve as exact as a dense LU.
    let (len, ties) = (400, 40);
    let open: Vec<usize> = (0..36).collect();
    let first = tied_chains(len, ties, &open);
    // (a first factorisation is reduced only after LUs with the bodies kept)
    let mut s = knowing_multipliers(&first, 2 * len, 0);
    assert!(solve_error(&mut s, &first) < 1e-12);
    assert!(s.base.reduction.is_none(), "no LU with the bodies kept yet");
    let mut s = knowing_multipliers(&first, 2 * len, 1);
    let err = solve_error(&mut s, &first);
    assert!(err < 1e-12, "first factorisation: max error {err}");
    let red = s.base.reduction.as_ref().expect("reduced");
    assert!(
        red.passive_cholesky(),
        "the bodies' terms alone on the passive part"
    );
    // live: the tied unknowns and multipliers of ties 35–39 (35 next to 36); the other
    // open ties' multipliers are solved on their own
    assert_eq!(red.num_live(), 3 * 5);
    let reduced_at = red.values.clone();
    // ties 35 and 37 swap: live rows only
    let swapped: Vec<usize> = (0..35).chain([37]).collect();
    let a = tied_chains(len, ties, &swapped);
    let err = solve_error(&mut s, &a);
    assert!(err < 1e-12, "live change: max error {err}");
    assert!(
        s.update.is_none(),
        "a new LU of the live part, no low-rank update"
    );
    assert_eq!(s.base.reduction.as_ref().unwrap().values, reduced_at);
    // ties 5 and 6 closed among the passive unknowns: a new reduction
    let closed: Vec<usize> = (0..35)
        .filter(|k| ![5, 6].contains(k))
        .chain([37])
        .collect();
    let a = tied_chains(len, ties, &closed);
    let err = solve_error(&mut s, &a);
    assert!(err < 1e-12, "passive changes: max error {err}");
    assert!(s.update.is_none());
    assert_ne!(s.base.reduction.as_ref().unwrap().values, reduced_at);
    // without the multipliers known, never reduced
    let t = transpose_positions(&first);
    let in_gamma = interface_of(&first, 2 * len, &t).unwrap();
    let mut whole = InterfaceSolver::new(&first, in_gamma, Storage::default()).unwrap();
    assert!(solve_error(&mut whole, &first) < 1e-12);
    assert!(whole.base.reduction.is_none());
    // fewer than a quarter passive: not reduced
    let mostly_closed = tied_chains(len, ties, &[0, 1, 2, 3, 4, 5]);
    let mut s = knowing_multipliers(&mostly_closed, 2 * len, 1);
    assert!(solve_error(&mut s, &mostly_closed) < 1e-12);
    assert!(s.base.reduction.is_none());
}

#[test]
fn a_reduction_with_unsymmetric_passive_terms_solves_exactly() {
    // T made unsymmetric among the passive unknowns (ties 3 and 4) and between passive and
    // live ones (ties 34 and 35), on one side only: the reduction keeps T_LP (the
    // symmetric form does without); the live part changes as above.
    let (len, ties) = (400, 40);
    let with_skew = |open: &[usize]| {
        let mut e = tied_chains_entries(len, ties, open);
        e.push((len - 4, len - 5, 0.05));
        e.push((len - 1 - 34, len - 1 - 35, 0.07)); // passive row (tie 34), live column (35)
        SparseMatrix::from_entries(2 * len + ties, &e)
    };
    let first = with_skew(&(0..36).collect::<Vec<_>>());
    let mut s = knowing_multipliers(&first, 2 * len, 1);
    let err = solve_error(&mut s, &first);
    assert!(err < 1e-12, "first factorisation: max error {err}");
    let red = s.base.reduction.as_ref().expect("reduced");
    assert!(!red.passive_cholesky(), "T_LP kept: LU");
    let a = with_skew(&(0..35).chain([37]).collect::<Vec<_>>());
    let err = solve_error(&mut s, &a);
    assert!(err < 1e-12, "live change: max error {err}");
    assert!(s.update.is_none());
    // and the chains alone are symmetric there: T_LP is not kept
    let b = tied_chains(len, ties, &(0..36).collect::<Vec<_>>());
    let mut s = knowing_multipliers(&b, 2 * len, 1);
    assert!(solve_error(&mut s, &b) < 1e-12);
    let red = s.base.reduction.as_ref().expect("reduced");
    assert!(red.passive_cholesky());
}

#[test]
fn a_decoupled_unknowns_diagonal_that_moves_keeps_the_reduction() {
    // An open tie's multiplier is decoupled (its diagonal alone in row and column: mortar's
    // open points, whose weight moves with the geometry). Its diagonal changing beside a
    // live change is still a new LU of the live part, the reduction kept, and exact.
    let (len, ties) = (400, 40);
    let open: Vec<usize> = (0..36).collect();
    let with_weight = |open: &[usize], extra: f64| {
        let mut e = tied_chains_entries(len, ties, open);
        e.push((2 * len + 10, 2 * len + 10, extra));
        SparseMatrix::from_entries(2 * len + ties, &e)
    };
    let first = with_weight(&open, 0.0);
    let mut s = knowing_multipliers(&first, 2 * len, 1);
    assert!(solve_error(&mut s, &first) < 1e-12);
    let reduced_at = s.base.reduction.as_ref().expect("reduced").values.clone();
    let swapped: Vec<usize> = (0..35).chain([37]).collect();
    for extra in [2.0, -1.5, 0.0] {
        let a = with_weight(&swapped, extra);
        let err = solve_error(&mut s, &a);
        assert!(err < 1e-12, "diagonal + {extra}: max error {err}");
        assert_eq!(
            s.base.reduction.as_ref().unwrap().values,
            reduced_at,
            "diagonal + {extra}: the reduction kept"
        );
    }
}
