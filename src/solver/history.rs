//! Load histories: time functions (piecewise-linear tables) that scale each load and each
//! imposed displacement, rigid motions (rotation and translation of a node set), values
//! given by expressions of (x, y, t) (total values at t, evaluated at each time), and the
//! evaluation of the external forces and imposed values at a time t.
//!
//! Without a history every load follows the ramp f(t) = t, so that t plays the part of the
//! classic load factor (t = 1: the full load).

use crate::assembly::dofs::DofMap;
use crate::error::{Error, Result};
use crate::expr::Expr;

/// A scalar function of time.
#[derive(Clone, Debug, PartialEq)]
pub enum TimeFunction {
    /// f(t) = t.
    Ramp,
    /// Linear between the (time, value) points, constant before the first and after the last.
    Table(Vec<(f64, f64)>),
}

impl TimeFunction {
    /// A table; its times must increase strictly. `what` names it in errors.
    pub fn table(points: Vec<(f64, f64)>, what: &str) -> Result<TimeFunction> {
        if points.is_empty() {
            return Err(Error::model(format!("{what}: the table has no points")));
        }
        if let Some((t, v)) = points
            .iter()
            .find(|(t, v)| !t.is_finite() || !v.is_finite())
        {
            return Err(Error::model(format!(
                "{what}: point ({t}, {v}) is not finite"
            )));
        }
        if let Some(w) = points.windows(2).find(|w| w[1].0 <= w[0].0) {
            return Err(Error::model(format!(
                "{what}: times must increase strictly, but {} follows {}",
                w[1].0, w[0].0
            )));
        }
        Ok(TimeFunction::Table(points))
    }

    pub fn value(&self, t: f64) -> f64 {
        let pts = match self {
            TimeFunction::Ramp => return t,
            TimeFunction::Table(p) => p,
        };
        let (first, last) = (pts[0], pts[pts.len() - 1]);
        if t <= first.0 {
            return first.1;
        }
        if t >= last.0 {
            return last.1;
        }
        let k = pts.partition_point(|p| p.0 <= t); // pts[k-1].0 <= t < pts[k].0
        let ((t0, v0), (t1, v1)) = (pts[k - 1], pts[k]);
        v0 + (v1 - v0) * (t - t0) / (t1 - t0)
    }

    /// The times where the slope changes (a load step should end there).
    pub fn breakpoints(&self) -> Vec<f64> {
        match self {
            TimeFunction::Ramp => vec![],
            TimeFunction::Table(p) => p.iter().map(|q| q.0).collect(),
        }
    }
}

/// Where an expression is evaluated, for errors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Place {
    Node(usize),
    /// An integration point of an edge cell.
    Edge(usize),
}

impl std::fmt::Display for Place {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Place::Node(n) => write!(f, "node {}", n + 1),
            Place::Edge(c) => write!(f, "an integration point of edge cell {}", c + 1),
        }
    }
}

/// An expression of time (and position) with the entry that gave it, e.g.
/// `[[displacement]] 2 on 'Inner': dx`.
#[derive(Clone, Debug)]
pub struct TimeExpr {
    pub expr: Expr,
    pub what: String,
}

impl TimeExpr {
    fn error(&self, v: f64, at: Option<(Place, [f64; 2])>, t: f64) -> Error {
        let place = match at {
            Some((p, x)) => format!(" at {p} (x = {}, y = {})", x[0], x[1]),
            None => String::new(),
        };
        Error::model(format!(
            "{} = \"{}\" is {v}{place} at t = {t}: it must be finite there",
            self.what,
            self.expr.text()
        ))
    }
}

/// Forces given by an expression of t (and x, y): f[dof] += coef · e(x_p, t) for each
/// (point p, dof, coef).
#[derive(Clone, Debug)]
pub struct TimedForce {
    pub source: TimeExpr,
    pub points: Vec<([f64; 2], Place)>,
    pub terms: Vec<(usize, usize, f64)>,
}

/// Displacements imposed on dofs, as functions of time.
#[derive(Clone, Debug)]
pub enum Imposed {
    /// u_d = value · f(t) for each (dof, value).
    Scaled {
        dofs: Vec<(usize, f64)>,
        function: TimeFunction,
    },
    /// A rigid motion of nodes: rotation by angle · f(t) (radians, counter-clockwise) about
    /// `center`, then translation by `translation` · f(t). Each entry is (node, position).
    Rigid {
        nodes: Vec<(usize, [f64; 2])>,
        center: [f64; 2],
        angle: f64,
        translation: [f64; 2],
        function: TimeFunction,
    },
    /// u_d = e(x, t) for each (dof, initial position of its node): the total value at t.
    Field {
        dofs: Vec<(usize, [f64; 2])>,
        source: TimeExpr,
    },
    /// The rotation part of a rigid surface's motion, (R(θ) − I)(X − center) at each
    /// (node, X), θ being the imposed value of dof `angle` at t (so this entry comes after
    /// the one imposing it); the translation is linked to the reference point's dofs.
    Follow {
        nodes: Vec<(usize, [f64; 2])>,
        center: [f64; 2],
        angle: usize,
    },
}

/// The displacement of the point `x` under a rotation by `angle` (radians,
/// counter-clockwise) about `center` followed by a translation.
pub fn rigid_displacement(
    x: [f64; 2],
    center: [f64; 2],
    angle: f64,
    translation: [f64; 2],
) -> [f64; 2] {
    let (sin, cos) = angle.sin_cos();
    let (rx, ry) = (x[0] - center[0], x[1] - center[1]);
    [
        center[0] + cos * rx - sin * ry + translation[0] - x[0],
        center[1] + sin * rx + cos * ry + translation[1] - x[1],
    ]
}

/// All time-dependent data of a problem.
#[derive(Clone, Debug)]
pub struct Loading {
    /// External force vectors (full dofs) at f = 1 with their time functions.
    pub forces: Vec<(Vec<f64>, TimeFunction)>,
    /// Imposed displacements; a dof in several entries takes the last one's value. Imposed
    /// dofs in no entry stay at 0.
    pub imposed: Vec<Imposed>,
    /// Time function of each relation's right-hand side (Ramp when missing).
    pub relation_functions: Vec<TimeFunction>,
    /// Forces given by expressions of t (those without t are in `forces`).
    pub timed_forces: Vec<TimedForce>,
    /// Per relation, an expression of t giving its right-hand side at t (instead of
    /// rhs · f(t)).
    pub relation_exprs: Vec<Option<TimeExpr>>,
}

impl Loading {
    /// Everything proportional to t: the forces `fext` and the DofMap's imposed values and
    /// relation right-hand sides at t = 1.
    pub fn proportional(fext: Vec<f64>, dofs: &DofMap) -> Loading {
        let imposed = dofs
            .prescribed
            .iter()
            .enumerate()
            .filter(|(_, v)| **v != 0.0)
            .map(|(d, &v)| (d, v))
            .collect();
        Loading {
            forces: vec![(fext, TimeFunction::Ramp)],
            imposed: vec![Imposed::Scaled {
                dofs: imposed,
                function: TimeFunction::Ramp,
            }],
            relation_functions: vec![],
            timed_forces: vec![],
            relation_exprs: vec![],
        }
    }

    /// External forces at time t (full dofs).
    pub fn forces_at(&self, t: f64, out: &mut [f64]) {
        out.fill(0.0);
        for (f, func) in &self.forces {
            let s = func.value(t);
            if s != 0.0 {
                for (o, v) in out.iter_mut().zip(f) {
                    *o += s * v;
                }
            }
        }
        for f in &self.timed_forces {
            let values = eval_many(&f.source.expr, &f.points, |p| p.0, t);
            for &(p, d, c) in &f.terms {
                out[d] += c * values[p];
            }
        }
    }

    /// Errors if an expression of t is not finite at some point at one of `times` (an
    /// expression without t was checked where it was evaluated).
    pub fn check_finite(&self, times: &[f64]) -> Result<()> {
        for &t in times {
            for f in &self.timed_forces {
                for &(x, place) in &f.points {
                    let v = f.source.expr.eval(x, t);
                    if !v.is_finite() {
                        return Err(f.source.error(v, Some((place, x)), t));
                    }
                }
            }
            for entry in &self.imposed {
                if let Imposed::Field { dofs, source } = entry {
                    for &(d, x) in dofs {
                        let v = source.expr.eval(x, t);
                        if !v.is_finite() {
                            return Err(source.error(v, Some((Place::Node(d / 2), x)), t));
                        }
                    }
                }
            }
            for r in self.relation_exprs.iter().flatten() {
                let v = r.expr.eval([0.0; 2], t);
                if !v.is_finite() {
                    return Err(r.error(v, None, t));
                }
            }
        }
        Ok(())
    }

    /// The imposed values at time t as `DofMap::expand` takes them: one per dof (imposed
    /// dofs), then one per relation (its right-hand side).
    pub fn imposed_at(&self, t: f64, dofs: &DofMap, out: &mut Vec<f64>) {
        out.clear();
        out.resize(dofs.num_dofs() + dofs.rhs.len(), 0.0);
        for entry in &self.imposed {
            match entry {
                Imposed::Scaled { dofs, function } => {
                    let s = function.value(t);
                    for &(d, v) in dofs {
                        out[d] = s * v;
                    }
                }
                Imposed::Rigid {
                    nodes,
                    center,
                    angle,
                    translation,
                    function,
                } => {
                    let s = function.value(t);
                    for &(n, x) in nodes {
                        let u = rigid_displacement(
                            x,
                            *center,
                            s * angle,
                            [s * translation[0], s * translation[1]],
                        );
                        out[2 * n] = u[0];
                        out[2 * n + 1] = u[1];
                    }
                }
                Imposed::Field { dofs, source } => {
                    let values = eval_many(&source.expr, dofs, |p| p.1, t);
                    for (&(d, _), v) in dofs.iter().zip(values) {
                        out[d] = v;
                    }
                }
                Imposed::Follow {
                    nodes,
                    center,
                    angle,
                } => {
                    let theta = out[*angle];
                    for &(n, x) in nodes {
                        let u = rigid_displacement(x, *center, theta, [0.0; 2]);
                        out[2 * n] = u[0];
                        out[2 * n + 1] = u[1];
                    }
                }
            }
        }
        let base = dofs.num_dofs();
        for (r, &rhs) in dofs.rhs.iter().enumerate() {
            let f = self
                .relation_functions
                .get(r)
                .unwrap_or(&TimeFunction::Ramp);
            out[base + r] = match self.relation_exprs.get(r) {
                Some(Some(e)) => e.expr.eval([0.0; 2], t),
                _ => rhs * f.value(t),
            };
        }
    }

    /// Times in (0, end) where some time function has a kink.
    pub fn breakpoints(&self, end: f64) -> Vec<f64> {
        let mut out: Vec<f64> = self
            .forces
            .iter()
            .map(|f| &f.1)
            .chain(self.imposed.iter().filter_map(|i| match i {
                Imposed::Scaled { function, .. } | Imposed::Rigid { function, .. } => {
                    Some(function)
                }
                Imposed::Field { .. } | Imposed::Follow { .. } => None,
            }))
            .chain(&self.relation_functions)
            .flat_map(|f| f.breakpoints())
            .filter(|&t| t > 0.0 && t < end)
            .collect();
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }
}

/// The values of `e` at the points `at(item)` of `items` and time t; long lists in parallel
/// (a million nodes: 0.07 s per component alone).
fn eval_many<T: Sync>(
    e: &Expr,
    items: &[T],
    at: impl Fn(&T) -> [f64; 2] + Sync,
    t: f64,
) -> Vec<f64> {
    use rayon::prelude::*;
    if items.len() < 20_000 {
        return items.iter().map(|i| e.eval(at(i), t)).collect();
    }
    items.par_iter().map(|i| e.eval(at(i), t)).collect()
}

/// The ends of the load steps: `steps` equal steps over (0, end], plus every time in
/// `extra` (output times, kinks of the time functions) inside (0, end). Times closer than
/// 1e-9 · end merge.
pub fn step_ends(end: f64, steps: usize, extra: &[f64]) -> Vec<f64> {
    let steps = steps.max(1);
    let mut t: Vec<f64> = (1..=steps).map(|k| end * k as f64 / steps as f64).collect();
    t.extend(extra.iter().copied().filter(|&x| x > 0.0 && x < end));
    t.sort_by(f64::total_cmp);
    let eps = 1e-9 * end.abs();
    let mut out: Vec<f64> = vec![];
    for x in t {
        match out.last_mut() {
            Some(l) if (x - *l).abs() <= eps => *l = l.max(x),
            _ => out.push(x),
        }
    }
    if let Some(l) = out.last_mut() {
        *l = end;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_interpolates_linearly_and_holds_its_end_values() {
        let f = TimeFunction::table(vec![(0.0, 0.0), (1.0, 2.0), (3.0, -2.0)], "f").unwrap();
        for (t, v) in [
            (-1.0, 0.0),
            (0.0, 0.0),
            (0.25, 0.5),
            (1.0, 2.0),
            (2.0, 0.0),
            (2.5, -1.0),
            (3.0, -2.0),
            (9.0, -2.0),
        ] {
            assert!(
                (f.value(t) - v).abs() < 1e-15,
                "f({t}) = {} not {v}",
                f.value(t)
            );
        }
        assert_eq!(TimeFunction::Ramp.value(1.7), 1.7);
    }

    #[test]
    fn non_increasing_times_are_an_error() {
        let e = TimeFunction::table(vec![(0.0, 0.0), (1.0, 1.0), (1.0, 2.0)], "function 'f'")
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "function 'f': times must increase strictly, but 1 follows 1"
        );
        assert!(TimeFunction::table(vec![], "g").is_err());
        assert!(TimeFunction::table(vec![(0.0, f64::NAN)], "g").is_err());
    }

    #[test]
    fn step_ends_merge_the_grid_and_the_extra_times() {
        let t = step_ends(2.0, 4, &[0.5, 0.75, 1.0 + 1e-12, 3.0, 0.0]);
        assert_eq!(t, vec![0.5, 0.75, 1.0 + 1e-12, 1.5, 2.0]);
        assert_eq!(step_ends(1.0, 1, &[]), vec![1.0]);
    }

    #[test]
    fn a_million_node_expression_is_imposed_quickly() {
        // issue 21: a 1M-node expression BC under 0.1 s per step (both components here)
        let n = 1_000_000;
        let expr = |s: &str| TimeExpr {
            expr: Expr::parse(s, &["x", "y", "t"], "test").unwrap(),
            what: "test".into(),
        };
        let x = |i: usize| {
            let a = i as f64 * std::f64::consts::TAU / n as f64;
            [a.cos(), a.sin()]
        };
        let used = vec![true; 2 * n];
        let dofs = DofMap::new(&used, &[], &[]).unwrap();
        let loading = Loading {
            forces: vec![],
            imposed: ["t*1e-3*x/sqrt(x^2+y^2)", "t*1e-3*y/sqrt(x^2+y^2)"]
                .iter()
                .enumerate()
                .map(|(c, s)| Imposed::Field {
                    dofs: (0..n).map(|i| (2 * i + c, x(i))).collect(),
                    source: expr(s),
                })
                .collect(),
            relation_functions: vec![],
            timed_forces: vec![],
            relation_exprs: vec![],
        };
        let mut g = vec![];
        loading.imposed_at(0.5, &dofs, &mut g);
        let start = std::time::Instant::now();
        loading.imposed_at(1.0, &dofs, &mut g);
        let dt = start.elapsed().as_secs_f64();
        eprintln!("1M-node radial displacement (dx and dy) at one time: {dt:.3} s");
        assert!((g[2 * 7] - 1e-3 * x(7)[0]).abs() < 1e-18);
        assert!((g[2 * 7 + 1] - 1e-3 * x(7)[1]).abs() < 1e-18);
        // measured ≈ 0.08 s on the 2-core machine; generous for a loaded one
        assert!(dt < 0.5, "{dt} s");
    }

    #[test]
    fn rigid_motion_rotates_about_the_center() {
        let used = [true; 4];
        let dofs = DofMap::new(&used, &[(0, 0.0), (1, 0.0), (2, 0.0), (3, 0.0)], &[]).unwrap();
        let loading = Loading {
            forces: vec![],
            imposed: vec![Imposed::Rigid {
                nodes: vec![(0, [2.0, 1.0]), (1, [1.0, 1.0])],
                center: [1.0, 1.0],
                angle: std::f64::consts::FRAC_PI_2,
                translation: [0.5, 0.0],
                function: TimeFunction::table(vec![(0.0, 0.0), (2.0, 1.0)], "f").unwrap(),
            }],
            relation_functions: vec![],
            timed_forces: vec![],
            relation_exprs: vec![],
        };
        let mut g = vec![];
        loading.imposed_at(2.0, &dofs, &mut g);
        // (2, 1) turns a quarter about (1, 1) to (1, 2), then moves by (0.5, 0)
        let want = [-0.5, 1.0, 0.5, 0.0];
        for (a, b) in g.iter().zip(want) {
            assert!((a - b).abs() < 1e-15, "{g:?}");
        }
        loading.imposed_at(1.0, &dofs, &mut g);
        let (s, c) = (std::f64::consts::FRAC_PI_4).sin_cos();
        assert!((g[0] - (1.0 + c - 2.0 + 0.25)).abs() < 1e-15);
        assert!((g[1] - (1.0 + s - 1.0)).abs() < 1e-15);
    }
}
