//! Coulomb's law as a pure function on one contact point (contact.md §1.8), in the
//! reference code's semi-multiplier form: Λ is the tangential traction divided by μ|λ|
//! (so |Λ| ≤ 1), Δw the slip along the master tangent since the start of the load step,
//! and t = Λ + ρ_f Δw the augmented trial value. |t| ≤ 1 sticks, otherwise the point slips
//! with Λ = sign(t): a return map onto the Coulomb cone. (A tangential penalty's return
//! map, on forces, is `point_segment::penalty_friction`.)

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum State {
    Stick,
    /// slipping in the direction of this sign of the tangent
    Slip(f64),
}

/// The augmented value t and the state it decides.
pub fn state(semi_multiplier: f64, slip: f64, rho_f: f64) -> (f64, State) {
    let t = semi_multiplier + rho_f * slip;
    if t.abs() <= 1.0 {
        (t, State::Stick)
    } else {
        (t, State::Slip(t.signum()))
    }
}

/// Tangential force per unit area on the slave side along the master tangent, for the
/// normal multiplier λ (< 0 in compression): μ λ t when sticking, μ λ sign(t) when slipping.
/// It opposes the trial slip and never exceeds μ|λ| in magnitude.
pub fn traction(mu: f64, lambda: f64, t: f64, state: State) -> f64 {
    match state {
        State::Stick => mu * lambda * t,
        State::Slip(s) => mu * lambda * s,
    }
}

/// The share of the bodies' stiffness over the cell size, E/h, that a point's trial
/// stiffness is raised to. In t = Λ + ρ_f Δw the semi-multiplier Λ is the traction over
/// μ p, so a sticking point's trial traction grows by μ p ρ_f per unit of slip: with one
/// ρ_f for the pair that stiffness falls with the pressure, and toward the ends of a
/// contact zone, where the slip zones are, the trial sees stick where the bodies slip. The
/// stick zone then shrinks by a node or two per Newton iteration, more iterations the finer
/// the mesh (SSNP154 D point-to-segment with the reference's ρ_f = 100: 29, 53, 49 and 51
/// iterations at 34k, 82k, 93k and 266k unknowns; ρ_f = 30 did not converge at 93k).
/// Mortar's trial, t + c Δw with c = E/h, has this scale already. Every share from 0.03
/// to 1 helped; a tenth did best on both SSNP154 D (82k and 93k unknowns: 39 and 33
/// iterations, against 46 / 41, 47 / 37, 41 / 40 at 0.03, 0.3, 1) and the Cattaneo–Mindlin
/// tests (node-to-segment, four meshes: 159 iterations, against 165, 164, 171; measured
/// before `PRESSURE_FLOOR`, which leaves D's counts as they were, 160 here). The
/// converged state does not depend on ρ_f (stick: Δw = 0; slip: Λ = sign Δw), only the
/// path.
pub const TRIAL_STIFFNESS: f64 = 0.1;

/// The pressure, as a share of the pair's peak, below which a point's ρ_f is raised no
/// further: at a point of almost no pressure an unbounded ρ_f leaves a slip window 2/ρ_f
/// far below the slips, and the point swings between the two slip directions (as with a
/// far too large ρ_f: `SWITCHES_BEFORE_SMALLER_TRIAL`). SSNP154 D point-to-segment at
/// 960k unknowns diverged in its second load step without this floor (hundreds of
/// statuses swinging from one iteration to the next).
pub const PRESSURE_FLOOR: f64 = 0.1;

/// A point's ρ_f: the pair's `rho_f`, raised where needed so that its trial stiffness
/// μ p ρ_f is at least `TRIAL_STIFFNESS` × `stiffness` (E/h), p being the point's
/// `pressure` (> 0 in compression) but no less than `PRESSURE_FLOOR` × `peak` (none, or
/// no friction: the pair's).
pub fn balanced_rho_f(rho_f: f64, stiffness: f64, mu: f64, pressure: f64, peak: f64) -> f64 {
    if pressure > 0.0 && mu > 0.0 {
        let p = pressure.max(PRESSURE_FLOOR * peak);
        rho_f.max(TRIAL_STIFFNESS * stiffness / (mu * p))
    } else {
        rho_f
    }
}

/// A contact point (or node) that switched this many times in one load step has its
/// trial's augmentation cut, by `SMALLER_TRIAL` at most (mortar: by that, down to
/// `SMALLEST_TRIAL` of the chosen one). Semi-smooth Newton cycles where the augmentation is
/// large for the local tangential compliance: in the semi-multiplier form a slipping point
/// must reverse its slip by less than 2/ρ_f to stick, and otherwise slips the other way.
/// What counts as a switch is the formulation's (point-to-segment: a reversal of the slip
/// direction; mortar: any change of branch). The converged solution does not depend on the
/// augmentation (stick: Δw = 0; slip: Λ = sign Δw), only the path.
pub const SWITCHES_BEFORE_SMALLER_TRIAL: u32 = 3;
pub const SMALLER_TRIAL: f64 = 0.1;
pub const SMALLEST_TRIAL: f64 = 1e-4;

/// Counts one branch change of a point with `switches` changes so far in this step and
/// the trial factor `scale` (1 at first); cuts the factor after
/// `SWITCHES_BEFORE_SMALLER_TRIAL` changes and starts counting again.
pub fn count_switch(switches: &mut u32, scale: &mut f64) {
    *switches += 1;
    if *switches >= SWITCHES_BEFORE_SMALLER_TRIAL {
        *scale = (SMALLER_TRIAL * *scale).max(SMALLEST_TRIAL);
        *switches = 0;
    }
}

/// Counts one reversal of a point's slip direction, its slip now Δw = `slip` under the
/// augmentation `rho_f` × `scale`. After `SWITCHES_BEFORE_SMALLER_TRIAL` reversals the
/// factor becomes the one under which this slip would have stuck, ρ_f |Δw| ≤ 1 (the slip
/// scale of the problem, whatever its units and cells), cut by `SMALLER_TRIAL` at most: a
/// reversal early in a large step, of a slip far from the solution's, then cuts no more
/// than that (a floor at a fixed fraction instead let ρ_f = 100 go to 0.01 on SSNP154 D
/// in one step at 0.16 mm, which then failed).
pub fn count_reversal(switches: &mut u32, scale: &mut f64, rho_f: f64, slip: f64) {
    *switches += 1;
    if *switches >= SWITCHES_BEFORE_SMALLER_TRIAL {
        let stuck = 1.0 / (rho_f * slip.abs());
        *scale = stuck.min(*scale).max(SMALLER_TRIAL * *scale);
        *switches = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stick_inside_the_cone_and_slip_outside() {
        assert_eq!(state(0.2, 0.001, 100.0).1, State::Stick); // t = 0.3
        assert_eq!(state(0.5, 0.01, 100.0).1, State::Slip(1.0)); // t = 1.5
        assert_eq!(state(-0.5, -0.01, 100.0).1, State::Slip(-1.0));
        assert_eq!(state(1.0, 0.0, 100.0).1, State::Stick); // on the cone: stick
    }

    #[test]
    fn traction_never_exceeds_the_cone_and_opposes_the_slip() {
        let (mu, lambda) = (0.1, -2000.0); // compression
        let mut seed: u64 = 12345;
        for _ in 0..10_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let l = (seed % 2001) as f64 / 1000.0 - 1.0;
            let dw = ((seed >> 20) % 2001) as f64 / 1e5 - 0.01;
            let (t, st) = state(l, dw, 100.0);
            let q = traction(mu, lambda, t, st);
            assert!(q.abs() <= mu * lambda.abs() * (1.0 + 1e-15));
            if let State::Slip(s) = st {
                assert_eq!(q.abs(), mu * lambda.abs());
                // a positive trial slip (s > 0) gets a negative force on the slave
                assert!(q * s < 0.0);
            }
        }
    }

    #[test]
    fn a_point_that_keeps_switching_gets_a_smaller_trial_down_to_the_floor() {
        let (mut switches, mut scale) = (0, 1.0);
        for _ in 0..SWITCHES_BEFORE_SMALLER_TRIAL - 1 {
            count_switch(&mut switches, &mut scale);
        }
        assert_eq!(scale, 1.0);
        count_switch(&mut switches, &mut scale);
        assert_eq!((switches, scale), (0, SMALLER_TRIAL));
        for _ in 0..100 {
            count_switch(&mut switches, &mut scale);
        }
        assert_eq!(scale, SMALLEST_TRIAL);
    }

    #[test]
    fn a_reversing_point_gets_the_trial_under_which_its_slip_sticks() {
        let (mut switches, mut scale) = (0, 1.0);
        let rho_f = 1e4;
        // two reversals: nothing yet
        count_reversal(&mut switches, &mut scale, rho_f, 2e-4);
        count_reversal(&mut switches, &mut scale, rho_f, -2e-4);
        assert_eq!(scale, 1.0);
        // the third: ρ_f |Δw| = 1 (2e-4 → ρ_f 5000)
        count_reversal(&mut switches, &mut scale, rho_f, 2e-4);
        assert_eq!(switches, 0);
        assert!((rho_f * scale - 5000.0).abs() < 1e-9);
        let (t, law) = state(1.0, -2e-4, rho_f * scale);
        assert_eq!((t, law), (0.0, State::Stick));
        // a slip already inside the window leaves it; a large one cuts 10× at most
        for _ in 0..3 {
            count_reversal(&mut switches, &mut scale, rho_f, 1e-6);
        }
        assert!((rho_f * scale - 5000.0).abs() < 1e-9);
        for _ in 0..3 {
            count_reversal(&mut switches, &mut scale, rho_f, 1.0);
        }
        assert!((rho_f * scale - 500.0).abs() < 1e-9);
    }

    #[test]
    fn the_balanced_trial_stiffness_is_a_share_of_e_over_h_and_free_of_units() {
        // E = 2e5 MPa, h = 0.1 mm, μ = 0.1
        let (stiffness, mu) = (2e5 / 0.1, 0.1);
        let peak = 3000.0;
        for p in [300.0, 1000.0, 3000.0] {
            let rho_f = balanced_rho_f(10.0, stiffness, mu, p, peak);
            assert!(mu * p * rho_f >= TRIAL_STIFFNESS * stiffness * (1.0 - 1e-12));
            assert!(rho_f >= 10.0);
        }
        // below a tenth of the peak, raised no further than there
        let floor = balanced_rho_f(10.0, stiffness, mu, 300.0, peak);
        assert_eq!(balanced_rho_f(10.0, stiffness, mu, 1.0, peak), floor);
        // a high pressure keeps the pair's ρ_f; no pressure or no friction: the pair's
        assert_eq!(balanced_rho_f(1e4, stiffness, mu, 3000.0, peak), 1e4);
        assert_eq!(balanced_rho_f(10.0, stiffness, mu, 0.0, peak), 10.0);
        assert_eq!(balanced_rho_f(10.0, stiffness, 0.0, 1000.0, peak), 10.0);
        // N-m-Pa: E/h and p in Pa and m, ρ_f per m (1000 × per mm)
        let mm = balanced_rho_f(10.0, stiffness, mu, 1000.0, peak);
        let m = balanced_rho_f(1e4, 2e11 / 1e-4, mu, 1e9, 1e6 * peak);
        assert!((m - 1e3 * mm).abs() <= 1e-9 * m);
    }

    #[test]
    fn traction_is_continuous_across_the_cone() {
        let (mu, lambda) = (0.3, -10.0);
        let inside = traction(mu, lambda, 1.0 - 1e-12, State::Stick);
        let outside = traction(mu, lambda, 1.0 + 1e-12, State::Slip(1.0));
        assert!((inside - outside).abs() < 1e-10);
    }
}
