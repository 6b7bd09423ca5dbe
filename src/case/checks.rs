//! Checks of a case before any work: every number finite and in its range, every entry
//! meaningful for the chosen options, names that are safe as file names and CSV columns,
//! sizes within bounds. Each error names the entry and what was expected. (Checks that need
//! the mesh, such as a cell in two material groups or one dof imposed twice with different
//! values, are made where the mesh is read: `build_problem` and `loading::build`.)

use super::schema::{CaseFile, MeshSpec};
use crate::error::{Error, Result};
use crate::expr::Value;
use crate::fem::material::Modelisation;

/// Most load steps a history may have (a million steps of a small model is hours of work;
/// more is a typo).
pub const MAX_STEPS: usize = 1_000_000;
/// Most Newton iterations per step.
pub const MAX_ITERATIONS: usize = 10_000;
/// Largest accepted relative residual tolerance: above it a "converged" step may be far
/// from equilibrium (a residual of 2 % called converged).
pub const MAX_TOLERANCE: f64 = 1e-2;
/// Most cells a generator may make (≈ 10 GB of solver memory).
pub const MAX_GENERATED_CELLS: usize = 20_000_000;

/// "[solver] end_time", "[[force]] 2 on 'Top': fx".
fn key_of(what: &str, key: &str) -> String {
    if what.starts_with('[') && what.ends_with(']') && !what.contains(' ') {
        format!("{what} {key}")
    } else {
        format!("{what}: {key}")
    }
}

fn finite(v: f64, what: &str, key: &str) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(Error::model(format!(
            "{} must be a finite number, got {v}",
            key_of(what, key)
        )))
    }
}

fn positive(v: f64, what: &str, key: &str) -> Result<()> {
    finite(v, what, key)?;
    if v > 0.0 {
        Ok(())
    } else {
        Err(Error::model(format!(
            "{} must be positive, got {v}",
            key_of(what, key)
        )))
    }
}

/// A name used in a file name or a CSV column: letters, digits, `_`, `-`, `.`, not
/// starting with `.` (no path separator, no `..`, no comma, quote or line break).
fn safe_name(name: &str, what: &str) -> Result<()> {
    let ok = !name.is_empty()
        && name.len() <= 100
        && !name.starts_with('.')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
    if ok {
        Ok(())
    } else {
        Err(Error::model(format!(
            "{what}: name '{}' must be made of letters, digits, '_', '-' and '.', at most 100 \
             of them, and not start with '.' (it names an output file or column)",
            name.escape_debug()
        )))
    }
}

/// A number (finite) or an expression of x, y and t that compiles.
fn value(v: &Value, what: &str, key: &str) -> Result<()> {
    v.compile(&["x", "y", "t"], &key_of(what, key)).map(|_| ())
}

/// The two components of a load: at least one given, each finite or an expression.
fn components(what: &str, given: [(&str, &Option<Value>); 2]) -> Result<()> {
    if given.iter().all(|(_, v)| v.is_none()) {
        return Err(Error::model(format!(
            "{what} imposes nothing: give {}, {} or both",
            given[0].0, given[1].0
        )));
    }
    for (k, v) in given {
        if let Some(v) = v {
            value(v, what, k)?;
        }
    }
    Ok(())
}

/// Every [[function]] scales some load, imposed motion or relation (one that scales
/// nothing is a typo in a `function` key, or left over). Checked after the functions and
/// the loads' references to them.
pub(super) fn check_functions_used(case: &CaseFile) -> Result<()> {
    let used: Vec<&String> = case
        .displacement
        .iter()
        .filter_map(|d| d.function.as_ref())
        .chain(case.rotation.iter().filter_map(|r| r.function.as_ref()))
        .chain(case.force.iter().filter_map(|f| f.function.as_ref()))
        .chain(case.pressure.iter().filter_map(|p| p.function.as_ref()))
        .chain(case.traction.iter().filter_map(|t| t.function.as_ref()))
        .chain(case.relation.iter().filter_map(|r| r.function.as_ref()))
        .chain(case.rigid.iter().filter_map(|r| r.function.as_ref()))
        .collect();
    // (a name with no [[function]] is reported where the loads are built)
    if used
        .iter()
        .any(|u| case.function.iter().all(|f| &&f.name != u))
    {
        return Ok(());
    }
    for (i, f) in case.function.iter().enumerate() {
        if !used.contains(&&f.name) {
            return Err(Error::model(format!(
                "[[function]] {} ('{}') is used by no load, imposed motion or relation: name \
                 it in a function key, or remove it (to set the end of the history, give \
                 [solver] end_time)",
                i + 1,
                f.name
            )));
        }
    }
    Ok(())
}

/// The checks of a case that need no mesh.
pub fn check(case: &CaseFile) -> Result<()> {
    check_mesh_spec(&case.mesh)?;
    let m = &case.model;
    positive(m.thickness, "[model]", "thickness")?;
    if m.modelisation == Modelisation::Axisymmetric && m.thickness != 1.0 {
        return Err(Error::model(format!(
            "[model] thickness = {} does nothing in an axisymmetric model (loads are per full \
             ring); remove it",
            m.thickness
        )));
    }
    for (i, a) in case.material.iter().enumerate() {
        let Some(group) = &a.group else {
            if case.material.len() > 1 {
                return Err(Error::model(format!(
                    "[[material]] {} has no group: a material without a group covers the whole \
                     mesh, so it must be the only one; give each of the {} materials its group",
                    i + 1,
                    case.material.len()
                )));
            }
            continue;
        };
        if let Some(j) = case.material[..i]
            .iter()
            .position(|b| b.group.as_ref() == Some(group))
        {
            return Err(Error::model(format!(
                "[[material]] {} and {} are both for group '{group}': give one material per group",
                j + 1,
                i + 1,
            )));
        }
    }
    for (i, f) in case.function.iter().enumerate() {
        let what = format!("[[function]] {} ('{}')", i + 1, f.name);
        if f.name.is_empty() {
            return Err(Error::model(format!("{what}: the name is empty")));
        }
        for p in &f.table {
            finite(p[0], &what, "table time")?;
            finite(p[1], &what, "table value")?;
        }
    }
    for (i, d) in case.displacement.iter().enumerate() {
        let what = format!("[[displacement]] {} on '{}'", i + 1, d.group);
        if d.dx.is_none() && d.dy.is_none() {
            return Err(Error::model(format!(
                "{what} imposes nothing: give dx, dy or both"
            )));
        }
        for (k, v) in [("dx", &d.dx), ("dy", &d.dy)] {
            if let Some(v) = v {
                value(v, &what, k)?;
            }
        }
    }
    for (i, f) in case.force.iter().enumerate() {
        let what = format!("[[force]] {} on '{}'", i + 1, f.group);
        components(&what, [("fx", &f.fx), ("fy", &f.fy)])?;
    }
    for (i, p) in case.pressure.iter().enumerate() {
        value(
            &p.p,
            &format!("[[pressure]] {} on '{}'", i + 1, p.group),
            "p",
        )?;
    }
    for (i, t) in case.traction.iter().enumerate() {
        let what = format!("[[traction]] {} on '{}'", i + 1, t.group);
        components(&what, [("tx", &t.tx), ("ty", &t.ty)])?;
    }
    for (i, r) in case.relation.iter().enumerate() {
        let what = format!("[[relation]] {} ('{}')", i + 1, r.name);
        r.rhs.compile(&["t"], &key_of(&what, "rhs"))?;
        if r.terms.is_empty() {
            return Err(Error::model(format!("{what} has no terms")));
        }
        for t in &r.terms {
            finite(t.coef, &what, &format!("coef of {} {}", t.group, t.dof))?;
        }
        if r.terms.iter().all(|t| t.coef == 0.0) {
            return Err(Error::model(format!(
                "{what}: every coefficient is zero, the relation says nothing"
            )));
        }
        if !r.name.is_empty() {
            if let Some(j) = case.relation[..i].iter().position(|q| q.name == r.name) {
                return Err(Error::model(format!(
                    "{what}: relation {} has the same name",
                    j + 1
                )));
            }
        }
    }
    check_contacts(case)?;
    check_solver_and_output(case)
}

fn check_contacts(case: &CaseFile) -> Result<()> {
    for (i, c) in case.contact.iter().enumerate() {
        let what = format!("[[contact]] {} ({} on {})", i + 1, c.slave, c.master);
        if let Some(r) = c.rho {
            positive(r, &what, "rho")?;
        }
        if let Some(r) = c.rho_f {
            positive(r, &what, "rho_f")?;
        }
        finite(c.friction, &what, "friction")?;
        if let Some(g) = c.initial_gap {
            finite(g, &what, "initial_gap")?;
        }
        if let Some(k) = c.penalty {
            positive(k, &what, "penalty")?;
        }
        if let Some(k) = c.tangential_penalty {
            positive(k, &what, "tangential_penalty")?;
        }
        if let Some(a) = c.adjust {
            finite(a, &what, "adjust")?;
        }
        if c.friction == 0.0 && c.rho_f.is_some() {
            return Err(Error::model(format!(
                "{what}: rho_f does nothing without friction"
            )));
        }
        if c.friction == 0.0 && !c.friction_exclude.is_empty() {
            return Err(Error::model(format!(
                "{what}: friction_exclude does nothing without friction"
            )));
        }
        if c.formulation == "mortar" {
            let idle = [
                ("rho", c.rho.is_some()),
                ("rho_f", c.rho_f.is_some()),
                ("integration", c.integration != "gauss"),
                ("master_normal", c.master_normal.is_some()),
            ];
            if let Some((key, _)) = idle.iter().find(|k| k.1) {
                return Err(Error::model(format!(
                    "{what}: {key} does nothing with mortar (its complementarity parameter \
                     comes from the bodies' stiffness and cell size; it integrates the overlap \
                     segments itself)"
                )));
            }
        }
        if c.formulation == "mortar" && c.gauss_points != 3 {
            return Err(Error::model(format!(
                "{what}: gauss_points does nothing with mortar (it integrates every overlap \
                 segment exactly enough by itself)"
            )));
        }
        if c.integration == "nodal" && c.gauss_points != 3 {
            return Err(Error::model(format!(
                "{what}: gauss_points does nothing with integration = \"nodal\""
            )));
        }
        for (j, d) in case.contact[..i].iter().enumerate() {
            let same = (d.slave == c.slave && d.master == c.master)
                || (d.slave == c.master && d.master == c.slave);
            if same {
                return Err(Error::model(format!(
                    "{what}: [[contact]] {} is between the same two surfaces",
                    j + 1
                )));
            }
        }
    }
    Ok(())
}

fn check_solver_and_output(case: &CaseFile) -> Result<()> {
    let s = &case.solver;
    if s.steps == 0 || s.steps > MAX_STEPS {
        return Err(Error::model(format!(
            "[solver] steps must lie in 1..={MAX_STEPS}, got {}",
            s.steps
        )));
    }
    if s.max_iterations == 0 || s.max_iterations > MAX_ITERATIONS {
        return Err(Error::model(format!(
            "[solver] max_iterations must lie in 1..={MAX_ITERATIONS}, got {}",
            s.max_iterations
        )));
    }
    if !(s.tolerance.is_finite() && s.tolerance > 0.0 && s.tolerance <= MAX_TOLERANCE) {
        return Err(Error::model(format!(
            "[solver] tolerance (relative residual) must lie in (0, {MAX_TOLERANCE}], got {}",
            s.tolerance
        )));
    }
    if let Some(t) = s.end_time {
        positive(t, "[solver]", "end_time")?;
    }
    let o = &case.output;
    if let Some(t) = &o.times {
        if t.is_empty() {
            return Err(Error::model(
                "[output] times is empty: give output times, or remove the key for every step",
            ));
        }
        for &x in t {
            finite(x, "[output]", "times")?;
        }
    }
    if let Some(h) = &o.hertz {
        positive(h.a, "[output] hertz", "a")?;
        positive(h.p0, "[output] hertz", "p0")?;
        if case.contact.is_empty() {
            return Err(Error::model(
                "[output] hertz does nothing without a [[contact]] (it plots the contact \
                 pressure against Hertz's)",
            ));
        }
    }
    for (i, p) in o.probe.iter().enumerate() {
        let what = format!("[[output.probe]] {}", i + 1);
        safe_name(&p.name, &what)?;
        if let Some(j) = o.probe[..i].iter().position(|q| q.name == p.name) {
            return Err(Error::model(format!(
                "{what}: [[output.probe]] {} has the same name '{}'",
                j + 1,
                p.name
            )));
        }
        if p.name.starts_with("rx_") || p.name.starts_with("ry_") {
            return Err(Error::model(format!(
                "{what}: name '{}' would clash with a reaction column of history.csv \
                 (rx_GROUP, ry_GROUP)",
                p.name
            )));
        }
        if p.name.starts_with("contact") && p.name[7..].starts_with(|c: char| c.is_ascii_digit()) {
            return Err(Error::model(format!(
                "{what}: name '{}' would clash with a contact column of history.csv \
                 (contactN_QUANTITY)",
                p.name
            )));
        }
        for (key, v) in [("at", p.at), ("center", p.center)] {
            if let Some(a) = v {
                finite(a[0], &what, key)?;
                finite(a[1], &what, key)?;
            }
        }
        // with `at`, stress_group also picks the cells whose nodes are searched
        if p.stress_group.is_some() && p.at.is_none() && matches!(p.field.as_str(), "dx" | "dy") {
            return Err(Error::model(format!(
                "{what}: stress_group does nothing on a displacement probe (field = {}) over \
                 a group: it selects the cells whose stresses are averaged",
                p.field
            )));
        }
    }
    for (i, c) in o.curve.iter().enumerate() {
        let what = format!("[[output.curve]] {}", i + 1);
        safe_name(&c.name, &what)?;
        if let Some(a) = c.center {
            finite(a[0], &what, "center")?;
            finite(a[1], &what, "center")?;
        }
        if let Some(j) = o.curve[..i].iter().position(|q| q.name == c.name) {
            return Err(Error::model(format!(
                "{what}: [[output.curve]] {} has the same name '{}'",
                j + 1,
                c.name
            )));
        }
    }
    Ok(())
}

/// The [mesh] keys: those of the chosen generator only, counts within bounds.
pub fn check_mesh_spec(spec: &MeshSpec) -> Result<()> {
    let given: Vec<(&str, bool)> = vec![
        ("size", spec.size.is_some()),
        ("stretch", spec.stretch.is_some()),
        ("radius", spec.radius.is_some()),
        ("cell", spec.cell.is_some()),
        ("origin", spec.origin.is_some()),
        ("width", spec.width.is_some()),
        ("height", spec.height.is_some()),
        ("nx", spec.nx.is_some()),
        ("ny", spec.ny.is_some()),
        ("distortion", spec.distortion != 0.0),
        ("r_in", spec.r_in.is_some()),
        ("r_out", spec.r_out.is_some()),
        ("n_r", spec.n_r.is_some()),
        ("n_theta", spec.n_theta.is_some()),
        ("angle", spec.angle.is_some()),
        ("quadratic", spec.quadratic),
    ];
    let allowed: &[&str] = match spec.generator.as_deref() {
        None => &[],
        Some("ssnp154") => &["size", "quadratic"],
        Some("disc_pair") => &["size", "stretch", "radius", "quadratic"],
        Some("rectangle") => &[
            "cell",
            "origin",
            "width",
            "height",
            "nx",
            "ny",
            "distortion",
        ],
        Some("ring") => &["cell", "r_in", "r_out", "n_r", "n_theta", "angle"],
        Some(_) => return Ok(()), // the unknown generator is reported by build_mesh
    };
    if let Some((key, _)) = given.iter().find(|(k, g)| *g && !allowed.contains(k)) {
        let source = match &spec.generator {
            Some(g) => format!("the '{g}' generator"),
            None => "a mesh file".to_string(),
        };
        return Err(Error::model(format!(
            "[mesh] {key} does nothing with {source}{}",
            if allowed.is_empty() {
                String::new()
            } else {
                format!(" (its keys: {})", allowed.join(", "))
            }
        )));
    }
    for (key, v) in [
        ("width", spec.width),
        ("height", spec.height),
        ("r_in", spec.r_in),
        ("r_out", spec.r_out),
        ("angle", spec.angle),
        ("size", spec.size),
        ("radius", spec.radius),
        ("stretch", spec.stretch),
    ] {
        if let Some(v) = v {
            finite(v, "[mesh]", key)?;
        }
    }
    if let Some(o) = spec.origin {
        finite(o[0], "[mesh]", "origin")?;
        finite(o[1], "[mesh]", "origin")?;
    }
    finite(spec.distortion, "[mesh]", "distortion")?;
    let cells = |a: Option<usize>, b: Option<usize>| {
        a.unwrap_or(1)
            .checked_mul(b.unwrap_or(1))
            .and_then(|n| n.checked_mul(2))
    };
    for (keys, n) in [
        ("nx × ny", cells(spec.nx, spec.ny)),
        ("n_r × n_theta", cells(spec.n_r, spec.n_theta)),
    ] {
        if n.is_none_or(|n| n > MAX_GENERATED_CELLS) {
            return Err(Error::model(format!(
                "[mesh] {keys} asks for more than {MAX_GENERATED_CELLS} cells"
            )));
        }
    }
    Ok(())
}
