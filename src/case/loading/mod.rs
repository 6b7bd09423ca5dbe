//! The load history of a case: its named time functions, the loads and imposed
//! displacements with their functions (`Loading`), the step ends and the output times.
//!
//! | file | what |
//! |---|---|
//! | `mod.rs` | time functions, loads and imposed displacements, step ends, output times |
//! | `rigid_motions.rs` | the rigid surfaces' reference points: dofs imposed, driven or held |

mod rigid_motions;

use super::schema::CaseFile;
use crate::assembly::loads::{edge_points, EdgePoint};
use crate::error::{Error, Result};
use crate::expr::{Compiled, Value};
use crate::mesh::Mesh;
use crate::solver::history::{
    rigid_displacement, step_ends, Imposed, Loading, Place, TimeExpr, TimeFunction, TimedForce,
};
use rigid_motions::rigid_motions;
use std::collections::BTreeMap;

/// The named functions of `[[function]]`.
pub fn functions(case: &CaseFile) -> Result<BTreeMap<String, TimeFunction>> {
    let mut out = BTreeMap::new();
    for f in &case.function {
        let what = format!("[[function]] '{}'", f.name);
        let table = TimeFunction::table(f.table.iter().map(|p| (p[0], p[1])).collect(), &what)?;
        if out.insert(f.name.clone(), table).is_some() {
            return Err(Error::model(format!("{what} is defined twice")));
        }
    }
    Ok(out)
}

fn lookup(
    funcs: &BTreeMap<String, TimeFunction>,
    name: &Option<String>,
    what: &str,
) -> Result<TimeFunction> {
    let Some(name) = name else {
        return Ok(TimeFunction::Ramp);
    };
    funcs.get(name).cloned().ok_or_else(|| {
        let known: Vec<&str> = funcs.keys().map(String::as_str).collect();
        Error::model(format!(
            "{what}: function '{name}' is not defined (functions: {})",
            if known.is_empty() {
                "none; define it with [[function]] name = ..., table = [[t, v], ...]".to_string()
            } else {
                known.join(", ")
            }
        ))
    })
}

/// The force vector of time function `f` in `forces`, added (zero) if new.
fn slot(forces: &mut Vec<(Vec<f64>, TimeFunction)>, f: TimeFunction, ndof: usize) -> &mut [f64] {
    let i = match forces.iter().position(|(_, g)| *g == f) {
        Some(i) => i,
        None => {
            forces.push((vec![0.0; ndof], f));
            forces.len() - 1
        }
    };
    &mut forces[i].0
}

/// The variables of a load or an imposed displacement.
const XYT: [&str; 3] = ["x", "y", "t"];

/// Compiles one component; an expression of t is the value at time t and takes no
/// `function`.
fn compile(v: &Value, what: &str, function: &Option<String>) -> Result<Compiled> {
    let c = v.compile(&XYT, what)?;
    if let (true, Some(f)) = (c.uses_t(), function) {
        return Err(Error::model(format!(
            "{what} = {v} is an expression of t, which gives the value at time t itself: it \
             cannot also be scaled by function '{f}'; write the time dependence into the \
             expression, or drop t from it"
        )));
    }
    Ok(c)
}

/// The value of a component without t at `x`, which must be finite.
fn value_at(c: &Compiled, what: &str, x: [f64; 2], place: Place) -> Result<f64> {
    let v = c.at(x, 0.0);
    match (v.is_finite(), c) {
        (true, _) => Ok(v),
        (false, Compiled::Expr(e)) => Err(Error::model(format!(
            "{what} = \"{}\" is {v} at {place} (x = {}, y = {}): it must be finite there",
            e.text(),
            x[0],
            x[1]
        ))),
        (false, Compiled::Number(_)) => Err(Error::model(format!(
            "{what} must be a finite number, got {v}"
        ))),
    }
}

/// The expression of an entry, for time-dependent values.
fn time_expr(c: Compiled, what: &str) -> TimeExpr {
    match c {
        Compiled::Expr(expr) => TimeExpr {
            expr,
            what: what.to_string(),
        },
        Compiled::Number(_) => unreachable!("a number does not depend on t"),
    }
}

/// A point where a load is evaluated: (position, place, [(dof, coefficient)]).
type LoadPoint = ([f64; 2], Place, Vec<(usize, f64)>);

/// Forces `dir(point)` · value on edge points (or nodes): into the force vector of the
/// time function, or, for an expression of t, as a timed force.
struct Forces<'a> {
    forces: &'a mut Vec<(Vec<f64>, TimeFunction)>,
    timed: &'a mut Vec<TimedForce>,
    ndof: usize,
}

impl Forces<'_> {
    fn add(
        &mut self,
        c: Compiled,
        what: &str,
        function: TimeFunction,
        points: Vec<LoadPoint>,
    ) -> Result<()> {
        if c.uses_t() {
            let mut terms = vec![];
            for (k, p) in points.iter().enumerate() {
                terms.extend(p.2.iter().map(|&(d, coef)| (k, d, coef)));
            }
            self.timed.push(TimedForce {
                source: time_expr(c, what),
                points: points.iter().map(|p| (p.0, p.1)).collect(),
                terms,
            });
            return Ok(());
        }
        let f = slot(self.forces, function, self.ndof);
        for (x, place, terms) in points {
            let v = value_at(&c, what, x, place)?;
            for (d, coef) in terms {
                f[d] += coef * v;
            }
        }
        Ok(())
    }
}

/// What the loads and imposed motions give: the imposed dofs (dof, value at f = 1, or at
/// t = 1 for an expression of t) for the dof map, each relation's right-hand side (the
/// same way), and the loading.
pub struct Built {
    pub fixed: Vec<(usize, f64)>,
    pub rhs: Vec<f64>,
    pub loading: Loading,
}

/// How an entry imposes a dof, to compare two entries imposing the same dof: numbers
/// with the same function, or else the same values at half the history and at its end
/// (to round-off: `sin(PI)` is not 0).
enum Imposes {
    /// value at f = 1, function, values at the two times
    Scaled(f64, Option<String>, [f64; 2]),
    /// an expression of t, values at the two times
    Field(String, [f64; 2]),
}

impl Imposes {
    fn values(&self) -> [f64; 2] {
        match self {
            Imposes::Scaled(.., v) | Imposes::Field(_, v) => *v,
        }
    }

    /// Whether two entries impose alike; `scale`: the largest value of either entry.
    fn alike(&self, other: &Imposes, scale: f64) -> bool {
        match (self, other) {
            (Imposes::Scaled(a, f, _), Imposes::Scaled(b, g, _)) => {
                f == g && (a - b).abs() <= 1e-12 * scale
            }
            _ => {
                let (a, b) = (self.values(), other.values());
                (0..2).all(|k| (a[k] - b[k]).abs() <= 1e-12 * scale)
            }
        }
    }
}

impl std::fmt::Display for Imposes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Imposes::Scaled(v, ..) => write!(f, "{v}"),
            Imposes::Field(s, _) => write!(f, "\"{s}\""),
        }
    }
}

/// The imposed dofs, the relations' right-hand sides and the loading of a case.
pub fn build(case: &CaseFile, mesh: &Mesh) -> Result<Built> {
    let funcs = functions(case)?;
    let m = &case.model;
    let ndof = 2 * mesh.num_nodes();
    let mut fixed = vec![];
    let mut imposed = vec![];
    // which entry imposes each dof, and how: a dof imposed twice must be imposed alike
    let mut by: std::collections::HashMap<usize, (String, Imposes, f64)> =
        std::collections::HashMap::new();
    let end = end_time(case)?;
    let times = [0.5 * end, end];
    for (i, spec) in case.displacement.iter().enumerate() {
        let what = format!("[[displacement]] {} on '{}'", i + 1, spec.group);
        let function = lookup(&funcs, &spec.function, &what)?;
        let nodes = mesh
            .node_group(&spec.group)
            .map_err(|e| Error::model(format!("[[displacement]]: {e}")))?;
        let mut scaled = vec![];
        let mut entries = vec![];
        for (c, key, v) in [(0, "dx", &spec.dx), (1, "dy", &spec.dy)] {
            let Some(v) = v else { continue };
            let key_what = format!("{what}: {key}");
            let value = compile(v, &key_what, &spec.function)?;
            if value.uses_t() {
                let source = time_expr(value, &key_what);
                let dofs: Vec<(usize, [f64; 2])> =
                    nodes.iter().map(|&n| (2 * n + c, mesh.coords[n])).collect();
                for &(d, x) in &dofs {
                    let at_1 = source.expr.eval(x, 1.0);
                    fixed.push((d, if at_1.is_finite() { at_1 } else { 0.0 }));
                    let at = times.map(|t| source.expr.eval(x, t));
                    entries.push((d, Imposes::Field(source.expr.text().to_string(), at)));
                }
                imposed.push(Imposed::Field { dofs, source });
            } else {
                for &n in &nodes {
                    let x = mesh.coords[n];
                    let u = value_at(&value, &key_what, x, Place::Node(n))?;
                    scaled.push((2 * n + c, u));
                    let at = times.map(|t| u * function.value(t));
                    let how = Imposes::Scaled(u, spec.function.clone(), at);
                    entries.push((2 * n + c, how));
                }
            }
        }
        let scale = entries
            .iter()
            .flat_map(|e| e.1.values())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        for (d, how) in entries {
            if let Some(prev) = by.get(&d) {
                if !prev.1.alike(&how, scale.max(prev.2)) {
                    let other_function = match (&prev.1, &how) {
                        (Imposes::Scaled(_, f, _), Imposes::Scaled(_, g, _)) if f != g => {
                            " with another function"
                        }
                        _ => "",
                    };
                    return Err(Error::model(format!(
                        "{what}: node {} {} = {how} is also imposed by {} as {}{other_function}",
                        d / 2 + 1,
                        ["dx", "dy"][d % 2],
                        prev.0,
                        prev.1,
                    )));
                }
            }
            by.insert(d, (what.clone(), how, scale));
        }
        fixed.extend_from_slice(&scaled);
        // (even empty: its function's kinks still end steps, as before expressions)
        imposed.push(Imposed::Scaled {
            dofs: scaled,
            function,
        });
    }
    let mut by_displacement = vec![false; ndof];
    for &(d, _) in &fixed {
        by_displacement[d] = true;
    }
    // the [[rotation]] that moves each node: a node moved twice must be moved alike
    let mut rotated: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    for (i, spec) in case.rotation.iter().enumerate() {
        let what = format!("[[rotation]] on '{}'", spec.group);
        let function = lookup(&funcs, &spec.function, &what)?;
        let nodes = mesh
            .node_group(&spec.group)
            .map_err(|e| Error::model(format!("{what}: {e}")))?;
        if ![spec.angle, spec.dx, spec.dy, spec.center[0], spec.center[1]]
            .iter()
            .all(|v| v.is_finite())
        {
            return Err(Error::model(format!(
                "{what}: angle, center, dx and dy must be finite numbers"
            )));
        }
        if let Some(&n) = nodes
            .iter()
            .find(|&&n| by_displacement[2 * n] || by_displacement[2 * n + 1])
        {
            return Err(Error::model(format!(
                "{what}: node {} also has a [[displacement]]; a node's motion is imposed once",
                n + 1
            )));
        }
        for &n in &nodes {
            let Some(&j) = rotated.get(&n) else {
                rotated.insert(n, i);
                continue;
            };
            let other = &case.rotation[j];
            let same = (
                other.center,
                other.angle,
                other.dx,
                other.dy,
                &other.function,
            ) == (spec.center, spec.angle, spec.dx, spec.dy, &spec.function);
            if !same {
                return Err(Error::model(format!(
                    "{what} (angle {}): node {} is also moved by [[rotation]] {} on '{}' \
                     (angle {}) differently; a node's motion is imposed once",
                    spec.angle,
                    n + 1,
                    j + 1,
                    other.group,
                    other.angle
                )));
            }
        }
        let entry = Imposed::Rigid {
            nodes: nodes.iter().map(|&n| (n, mesh.coords[n])).collect(),
            center: spec.center,
            angle: spec.angle.to_radians(),
            translation: [spec.dx, spec.dy],
            function,
        };
        // the values at f = 1, for the dof map's checks of the relations
        for &n in &nodes {
            let u = rigid_displacement(
                mesh.coords[n],
                spec.center,
                spec.angle.to_radians(),
                [spec.dx, spec.dy],
            );
            fixed.push((2 * n, u[0]));
            fixed.push((2 * n + 1, u[1]));
        }
        imposed.push(entry);
    }
    // One force vector per distinct time function, and the forces of expressions of t.
    let mut forces: Vec<(Vec<f64>, TimeFunction)> = vec![];
    let mut timed_forces = vec![];
    let mut out = Forces {
        forces: &mut forces,
        timed: &mut timed_forces,
        ndof,
    };
    let (lo, hi) = crate::mesh::quality::bounding_box(mesh);
    let on_axis_tol = 1e-9 * (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let axisymmetric = m.modelisation == crate::fem::material::Modelisation::Axisymmetric;
    for (i, spec) in case.force.iter().enumerate() {
        let what = format!("[[force]] {} on '{}'", i + 1, spec.group);
        let function = lookup(&funcs, &spec.function, &what)?;
        let nodes = mesh
            .node_group(&spec.group)
            .map_err(|e| Error::model(format!("[[force]]: {e}")))?;
        for (c, key, v) in [(0, "fx", &spec.fx), (1, "fy", &spec.fy)] {
            let Some(v) = v else { continue };
            let key_what = format!("{what}: {key}");
            let value = compile(v, &key_what, &spec.function)?;
            // a node on the axis is a point of the axis: it has no radial direction
            if axisymmetric && c == 0 {
                for &n in &nodes {
                    let x = mesh.coords[n];
                    let radial = value.uses_t() || value.at(x, 0.0) != 0.0;
                    if x[0].abs() <= on_axis_tol && radial {
                        return Err(Error::model(format!(
                            "{what}: node {} is on the axis (r = 0) of the axisymmetric model, \
                             where a radial force fx means nothing (the axis does not move \
                             radially)",
                            n + 1
                        )));
                    }
                }
            }
            let points = nodes
                .iter()
                .map(|&n| (mesh.coords[n], Place::Node(n), vec![(2 * n + c, 1.0)]))
                .collect();
            out.add(value, &key_what, function.clone(), points)?;
        }
    }
    let edge = |group: &str, what: &str| {
        edge_points(mesh, group, m.modelisation, m.thickness)
            .map_err(|e| Error::model(format!("{what}: {e}")))
    };
    let spread = |points: &[EdgePoint], dir: &dyn Fn(&EdgePoint) -> [f64; 2]| {
        points
            .iter()
            .map(|p| (p.x, Place::Edge(p.cell), p.terms(dir(p)).collect()))
            .collect()
    };
    for (i, spec) in case.pressure.iter().enumerate() {
        let what = format!("[[pressure]] {} on '{}'", i + 1, spec.group);
        let function = lookup(&funcs, &spec.function, &what)?;
        let value = compile(&spec.p, &format!("{what}: p"), &spec.function)?;
        let points = edge(&spec.group, "[[pressure]]")?;
        let dir = |p: &EdgePoint| [-p.normal_w[0], -p.normal_w[1]];
        out.add(
            value,
            &format!("{what}: p"),
            function,
            spread(&points, &dir),
        )?;
    }
    for (i, spec) in case.traction.iter().enumerate() {
        let what = format!("[[traction]] {} on '{}'", i + 1, spec.group);
        let function = lookup(&funcs, &spec.function, &what)?;
        let points = edge(&spec.group, "[[traction]]")?;
        for (c, key, v) in [(0, "tx", &spec.tx), (1, "ty", &spec.ty)] {
            let Some(v) = v else { continue };
            let key_what = format!("{what}: {key}");
            let value = compile(v, &key_what, &spec.function)?;
            let dir = |p: &EdgePoint| {
                let mut d = [0.0; 2];
                d[c] = p.ds_w;
                d
            };
            out.add(value, &key_what, function.clone(), spread(&points, &dir))?;
        }
    }
    rigid_motions(case, mesh, &funcs, &mut fixed, &mut imposed, &mut out)?;
    let mut relation_functions = vec![];
    let mut relation_exprs = vec![];
    let mut rhs = vec![];
    for (i, r) in case.relation.iter().enumerate() {
        let what = format!("[[relation]] {}", i + 1);
        relation_functions.push(lookup(&funcs, &r.function, &what)?);
        let key_what = format!("{what}: rhs");
        let value = r.rhs.compile(&["t"], &key_what)?;
        let value = compile_relation(value, &key_what, &r.function)?;
        if value.uses_t() {
            let source = time_expr(value, &key_what);
            let at_1 = source.expr.eval([0.0; 2], 1.0);
            rhs.push(if at_1.is_finite() { at_1 } else { 0.0 });
            relation_exprs.push(Some(source));
        } else {
            let v = value.at([0.0; 2], 0.0);
            if !v.is_finite() {
                return Err(Error::model(format!(
                    "{key_what} = {} is {v}: it must be finite",
                    r.rhs
                )));
            }
            rhs.push(v);
            relation_exprs.push(None);
        }
    }
    super::checks::check_functions_used(case)?;
    Ok(Built {
        fixed,
        rhs,
        loading: Loading {
            forces,
            imposed,
            relation_functions,
            timed_forces,
            relation_exprs,
        },
    })
}

/// A relation's right-hand side: as `compile`, with t as its only variable.
fn compile_relation(c: Compiled, what: &str, function: &Option<String>) -> Result<Compiled> {
    if let (Compiled::Expr(e), Some(f)) = (&c, function) {
        if e.uses_t() {
            return Err(Error::model(format!(
                "{what} = \"{}\" is an expression of t, which gives the value at time t \
                 itself: it cannot also be scaled by function '{f}'",
                e.text()
            )));
        }
    }
    Ok(c)
}

/// The end of the history: `[solver] end_time`, else the last time of the function tables
/// (if there are functions), else 1.
pub fn end_time(case: &CaseFile) -> Result<f64> {
    let end = match case.solver.end_time {
        Some(t) => t,
        None if !case.function.is_empty() => case
            .function
            .iter()
            .filter_map(|f| f.table.last().map(|p| p[0]))
            .fold(f64::NEG_INFINITY, f64::max),
        None => 1.0,
    };
    if !end.is_finite() || end <= 0.0 {
        return Err(Error::model(format!(
            "[solver] end_time must be positive, got {end}{}",
            if case.solver.end_time.is_none() {
                " (the last time of the function tables); give end_time"
            } else {
                ""
            }
        )));
    }
    Ok(end)
}

/// The step ends of the solve and the output times (None: every step).
pub fn schedule(case: &CaseFile, loading: &Loading) -> Result<(Vec<f64>, Option<Vec<f64>>)> {
    let end = end_time(case)?;
    if case.solver.steps == 0 {
        return Err(Error::model("[solver] steps must be at least 1"));
    }
    let outputs = match &case.output.times {
        None => None,
        Some(t) => {
            if let Some(&x) = t.iter().find(|&&x| !(x > 0.0 && x <= end)) {
                return Err(Error::model(format!(
                    "[output] times: {x} is outside the history (0, {end}]; the end time is \
                     [solver] end_time or the last time of the function tables"
                )));
            }
            if let Some(w) = t.windows(2).find(|w| w[1] <= w[0]) {
                return Err(Error::model(format!(
                    "[output] times must increase strictly, but {} follows {}",
                    w[1], w[0]
                )));
            }
            Some(t.clone())
        }
    };
    let mut extra = loading.breakpoints(end);
    extra.extend(outputs.iter().flatten());
    let times = step_ends(end, case.solver.steps, &extra);
    loading.check_finite(&times)?;
    Ok((times, outputs))
}
