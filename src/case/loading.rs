//! The load history of a case: its named time functions, the loads and imposed
//! displacements with their functions (`Loading`), the step ends and the output times.

use super::schema::CaseFile;
use crate::assembly::loads::{add_edge_load, add_nodal_force, EdgeLoad};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::solver::history::{rigid_displacement, step_ends, Imposed, Loading, TimeFunction};
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

/// The imposed dofs (dof, value at f = 1) for the dof map, and the loading.
pub fn build(case: &CaseFile, mesh: &Mesh) -> Result<(Vec<(usize, f64)>, Loading)> {
    let funcs = functions(case)?;
    let m = &case.model;
    let ndof = 2 * mesh.num_nodes();
    let mut fixed = vec![];
    let mut imposed = vec![];
    // which entry imposes each dof, with its value and function: a dof imposed twice must
    // be imposed alike
    let mut by: std::collections::HashMap<usize, (String, f64, Option<String>)> =
        std::collections::HashMap::new();
    for spec in &case.displacement {
        let what = format!("[[displacement]] on '{}'", spec.group);
        let function = lookup(&funcs, &spec.function, &what)?;
        let nodes = mesh
            .node_group(&spec.group)
            .map_err(|e| Error::model(format!("[[displacement]]: {e}")))?;
        let mut dofs = vec![];
        for &n in &nodes {
            if let Some(v) = spec.dx {
                dofs.push((2 * n, v));
            }
            if let Some(v) = spec.dy {
                dofs.push((2 * n + 1, v));
            }
        }
        for &(d, v) in &dofs {
            let entry = (what.clone(), v, spec.function.clone());
            if let Some(prev) = by.get(&d) {
                if prev.1 != v || prev.2 != spec.function {
                    return Err(Error::model(format!(
                        "{what}: node {} {} = {v} is also imposed by {} as {}{}",
                        d / 2 + 1,
                        ["dx", "dy"][d % 2],
                        prev.0,
                        prev.1,
                        if prev.2 != spec.function {
                            " with another function"
                        } else {
                            ""
                        }
                    )));
                }
            }
            by.insert(d, entry);
        }
        fixed.extend_from_slice(&dofs);
        imposed.push(Imposed::Scaled { dofs, function });
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
    // One force vector per distinct time function.
    let mut forces: Vec<(Vec<f64>, TimeFunction)> = vec![];
    let (lo, hi) = crate::mesh::quality::bounding_box(mesh);
    let on_axis_tol = 1e-9 * (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    for spec in &case.force {
        let what = format!("[[force]] on '{}'", spec.group);
        let f = slot(&mut forces, lookup(&funcs, &spec.function, &what)?, ndof);
        let nodes = mesh
            .node_group(&spec.group)
            .map_err(|e| Error::model(format!("[[force]]: {e}")))?;
        // a node on the axis is a point of the axis: it has no radial direction
        let radial = spec.fx.is_some_and(|fx| fx != 0.0);
        if m.modelisation == crate::fem::material::Modelisation::Axisymmetric && radial {
            if let Some(&n) = nodes
                .iter()
                .find(|&&n| mesh.coords[n][0].abs() <= on_axis_tol)
            {
                return Err(Error::model(format!(
                    "{what}: node {} is on the axis (r = 0) of the axisymmetric model, where a \
                     radial force fx means nothing (the axis does not move radially)",
                    n + 1
                )));
            }
        }
        add_nodal_force(f, &nodes, [spec.fx.unwrap_or(0.0), spec.fy.unwrap_or(0.0)]);
    }
    for spec in &case.pressure {
        let what = format!("[[pressure]] on '{}'", spec.group);
        let f = slot(&mut forces, lookup(&funcs, &spec.function, &what)?, ndof);
        let load = EdgeLoad::Pressure(spec.p);
        add_edge_load(mesh, &spec.group, load, m.modelisation, m.thickness, f)
            .map_err(|e| Error::model(format!("[[pressure]]: {e}")))?;
    }
    for spec in &case.traction {
        let what = format!("[[traction]] on '{}'", spec.group);
        let f = slot(&mut forces, lookup(&funcs, &spec.function, &what)?, ndof);
        let load = EdgeLoad::Traction([spec.tx.unwrap_or(0.0), spec.ty.unwrap_or(0.0)]);
        add_edge_load(mesh, &spec.group, load, m.modelisation, m.thickness, f)
            .map_err(|e| Error::model(format!("[[traction]]: {e}")))?;
    }
    let mut relation_functions = vec![];
    for (i, r) in case.relation.iter().enumerate() {
        let what = format!("[[relation]] {}", i + 1);
        relation_functions.push(lookup(&funcs, &r.function, &what)?);
    }
    super::checks::check_functions_used(case)?;
    Ok((
        fixed,
        Loading {
            forces,
            imposed,
            relation_functions,
        },
    ))
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
    Ok((step_ends(end, case.solver.steps, &extra), outputs))
}
