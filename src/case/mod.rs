//! Case files: load and check a TOML case, build the mesh and the discrete problem, run it.
//!
//! | file | what |
//! |---|---|
//! | `schema.rs` | serde structs of the TOML format (unknown keys rejected) |
//! | `checks.rs` | every value finite and in range, every key meaningful, before any work |
//! | `loading.rs` | time functions, loads and imposed motions, step ends, output times |
//! | `pairs.rs` | the contact pairs |
//! | `probe.rs` | probes: their nodes and values |
//! | `ssnp154.rs` | the built-in SSNP154 cases |

pub mod checks;
pub mod loading;
pub mod pairs;
pub mod probe;
pub mod schema;
pub mod ssnp154;

pub use pairs::build_pairs;
pub use probe::probe;
use probe::probe_nodes;

use crate::assembly::dofs::{DofMap, Relation};
use crate::assembly::Assembler;
use crate::contact::problem::ContactProblem;
use crate::contact::surface::Surface;
use crate::error::{Error, Result};
use crate::fem::material::{Elastic, Modelisation};
use crate::fem::solid::{Kinematics, SolidModel};
use crate::mesh::{generate, CellKind, Mesh};
use crate::post::stress::{cell_node_stresses, nodal_stresses};
use crate::solver::linear::Method;
use crate::solver::newton::{self, NewtonReport, NewtonSettings, Nonlinear};
use crate::solver::problem::SolidProblem;
use schema::CaseFile;
use std::path::{Path, PathBuf};

/// Reads a case file; syntax errors and unknown keys name the file, line and valid keys.
pub fn load(path: &Path) -> Result<(CaseFile, PathBuf)> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let case: CaseFile = toml::from_str(&text).map_err(|e| {
        Error::parse(
            path.display().to_string(),
            e.to_string().trim_end().to_string(),
        )
    })?;
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    Ok((case, dir))
}

fn need<T: Copy>(v: Option<T>, key: &str, generator: &str) -> Result<T> {
    v.ok_or_else(|| {
        Error::model(format!(
            "[mesh] generator '{generator}' needs the key '{key}'"
        ))
    })
}

/// Builds the mesh of a case: a file (relative to `dir`) or a generator.
pub fn build_mesh(spec: &schema::MeshSpec, dir: &Path) -> Result<Mesh> {
    checks::check_mesh_spec(spec)?;
    match (&spec.file, &spec.generator) {
        (Some(f), None) => {
            let p = dir.join(f);
            crate::mesh::read(&p)
        }
        (None, Some(g)) => {
            let cell = || -> Result<CellKind> {
                let name = spec.cell.as_deref().unwrap_or("Quad4");
                CellKind::from_name(name)
                    .filter(|k| k.dim() == 2)
                    .ok_or_else(|| {
                        Error::model(format!(
                            "[mesh] cell '{name}' is not one of Tri3, Tri6, Quad4, Quad8"
                        ))
                    })
            };
            match g.as_str() {
                "ssnp154" => generate::ssnp154(&generate::Ssnp154Options {
                    quadratic: spec.quadratic,
                    size: spec.size.unwrap_or(1.5),
                    ..Default::default()
                }),
                "disc_pair" => {
                    let size = need(spec.size, "size", g)?;
                    generate::disc_pair(&generate::DiscPairOptions {
                        quadratic: spec.quadratic,
                        radius: need(spec.radius, "radius", g)?,
                        size,
                        stretch: spec.stretch.unwrap_or(1.0),
                    })
                }
                "rectangle" => generate::rectangle(
                    spec.origin.unwrap_or([0.0, 0.0]),
                    need(spec.width, "width", g)?,
                    need(spec.height, "height", g)?,
                    need(spec.nx, "nx", g)?,
                    need(spec.ny, "ny", g)?,
                    cell()?,
                    spec.distortion,
                ),
                "ring" => generate::ring(
                    need(spec.r_in, "r_in", g)?,
                    need(spec.r_out, "r_out", g)?,
                    need(spec.n_r, "n_r", g)?,
                    need(spec.n_theta, "n_theta", g)?,
                    spec.angle.unwrap_or(90.0),
                    cell()?,
                ),
                other => Err(Error::model(format!(
                    "[mesh] unknown generator '{other}'; generators are: ssnp154, disc_pair, rectangle, ring"
                ))),
            }
        }
        _ => Err(Error::model(
            "[mesh] needs exactly one of 'file' or 'generator'",
        )),
    }
}

fn dof_index(node: usize, dof: &str, what: &str) -> Result<usize> {
    match dof {
        "dx" => Ok(2 * node),
        "dy" => Ok(2 * node + 1),
        other => Err(Error::model(format!(
            "{what}: dof '{other}' is not one of dx, dy"
        ))),
    }
}

/// The assembled problem of a case, ready to solve.
pub fn build_problem<'m>(case: &CaseFile, mesh: &'m Mesh) -> Result<SolidProblem<'m>> {
    checks::check(case)?;
    let m = &case.model;
    if m.modelisation == Modelisation::PlaneStress && m.kinematics == Kinematics::Large {
        return Err(Error::model(
            "[model] large kinematics is not available in plane stress; use plane_strain or axisymmetric",
        ));
    }
    if m.thickness.is_nan() || m.thickness <= 0.0 {
        return Err(Error::model(format!(
            "[model] thickness must be positive, got {}",
            m.thickness
        )));
    }
    if m.modelisation == Modelisation::Axisymmetric {
        if let Some((i, x)) = mesh.coords.iter().enumerate().find(|(_, x)| x[0] < -1e-9) {
            return Err(Error::model(format!(
                "axisymmetric model: node {} has a negative radius x = {}",
                i + 1,
                x[0]
            )));
        }
    }
    // Materials by group: every 2D cell needs exactly one.
    let mut material_of: Vec<Option<usize>> = vec![None; mesh.num_cells()];
    let mut materials = vec![];
    for (i, spec) in case.material.iter().enumerate() {
        let what = format!("[[material]] for group '{}'", spec.group);
        let cells = mesh
            .cell_group(&spec.group)
            .map_err(|e| Error::model(format!("[[material]]: {e}")))?;
        if mesh.group_dim(&spec.group) != Some(2) {
            return Err(Error::model(format!(
                "{what}: the group is not made of 2D cells"
            )));
        }
        materials.push(Elastic::new(spec.young, spec.nu, &what)?);
        for &c in cells {
            if let Some(j) = material_of[c] {
                return Err(Error::model(format!(
                    "{what}: cell {} is also in group '{}' of [[material]] {}: a cell has one \
                     material",
                    c + 1,
                    case.material[j].group,
                    j + 1
                )));
            }
            material_of[c] = Some(i);
        }
    }
    let mut cells = vec![];
    let mut models = vec![];
    let mut missing = 0;
    for c in mesh.cells_of_dim(2) {
        match material_of[c] {
            Some(i) => {
                cells.push(c);
                models.push(SolidModel {
                    model: m.modelisation,
                    kinematics: m.kinematics,
                    material: materials[i],
                    thickness: m.thickness,
                });
            }
            None => missing += 1,
        }
    }
    if missing > 0 {
        let groups2d: Vec<&String> = mesh
            .cell_groups
            .keys()
            .filter(|g| mesh.group_dim(g) == Some(2))
            .collect();
        return Err(Error::model(format!(
            "{missing} 2D cells have no material; give a [[material]] for each body (2D groups: {})",
            groups2d.iter().map(|s| s.as_str()).collect::<Vec<_>>().join(", ")
        )));
    }
    let ndof = 2 * mesh.num_nodes();
    let mut used = vec![false; ndof];
    for &c in &cells {
        for &n in mesh.cell_nodes(c) {
            used[2 * n] = true;
            used[2 * n + 1] = true;
        }
    }
    let (fixed, loading) = loading::build(case, mesh)?;
    let mut relations = vec![];
    for (i, spec) in case.relation.iter().enumerate() {
        let name = if spec.name.is_empty() {
            format!("relation {}", i + 1)
        } else {
            spec.name.clone()
        };
        let mut terms = vec![];
        for t in &spec.terms {
            let what = format!("[[relation]] '{name}'");
            let node = mesh
                .single_node(&t.group)
                .map_err(|e| Error::model(format!("{what}: {e}")))?;
            terms.push((dof_index(node, &t.dof, &what)?, t.coef));
        }
        // the same dof named twice: its coefficients add up (and may cancel)
        let mut sums: std::collections::BTreeMap<usize, (f64, f64)> = Default::default();
        for &(d, c) in &terms {
            let e = sums.entry(d).or_default();
            e.0 += c;
            e.1 = e.1.max(c.abs());
        }
        // (with a right-hand side it is a contradiction, which the dof map reports)
        let cancel = sums.values().all(|&(sum, size)| sum.abs() <= 1e-12 * size);
        if cancel && spec.rhs == 0.0 {
            return Err(Error::model(format!(
                "[[relation]] '{name}': its terms cancel (the coefficients of each dof add up \
                 to zero), the relation says nothing"
            )));
        }
        relations.push(Relation {
            terms,
            rhs: spec.rhs,
            name,
        });
    }
    let dofs = DofMap::new(&used, &fixed, &relations)?;
    // Without contact the matrix is SPD: Cholesky reads the lower triangle only.
    let asm = Assembler::new(mesh, cells, models, dofs, case.contact.is_empty())?;
    Ok(SolidProblem::with_loading(mesh, asm, loading))
}

/// What a run produces.
pub struct Outcome {
    pub report: NewtonReport,
    /// The state after each converged load step (when the case writes VTU files).
    pub steps: Vec<StepOutcome>,
    /// Per contact pair: (slave node, pressure) from the multipliers.
    pub contact_pressure: Vec<Vec<(usize, f64)>>,
    /// Per contact pair: (slave node, [normal, tangential] multiplier) as stored.
    pub contact_multipliers: Vec<Multipliers>,
    /// Per contact pair: (slave, master) surfaces.
    pub contact_surfaces: Vec<(Surface, Surface)>,
    /// Per contact pair: (slave node, tangential traction) with friction, and μ.
    pub contact_shear: Vec<(f64, Vec<(usize, f64)>)>,
    pub u: Vec<f64>,
    pub reactions: Vec<f64>,
    /// Nodal stresses averaged over all cells sharing a node.
    pub stress: Vec<[f64; 4]>,
    pub probes: Vec<(String, f64)>,
}

/// The fields of one converged load step.
pub struct StepOutcome {
    pub time: f64,
    pub probes: Vec<(String, f64)>,
    pub u: Vec<f64>,
    pub reactions: Vec<f64>,
    pub stress: Vec<[f64; 4]>,
    pub contact_pressure: Vec<Vec<(usize, f64)>>,
    pub contact_shear: Vec<(f64, Vec<(usize, f64)>)>,
    pub contact_multipliers: Vec<Multipliers>,
}

/// (slave node, [normal, tangential] multiplier) of one contact pair.
pub type Multipliers = Vec<(usize, [f64; 2])>;

fn step_outcome(
    case: &CaseFile,
    mesh: &Mesh,
    solid: &SolidProblem,
    time: f64,
    contact_pressure: Vec<Vec<(usize, f64)>>,
    contact_shear: Vec<(f64, Vec<(usize, f64)>)>,
) -> Result<StepOutcome> {
    let elno = cell_node_stresses(mesh, &solid.asm, &solid.u)?;
    let stress = nodal_stresses(mesh, &solid.asm, &elno, None)?;
    let mut probes = vec![];
    for p in &case.output.probe {
        probes.push((p.name.clone(), probe(solid, p, &elno, &stress)?));
    }
    Ok(StepOutcome {
        time,
        probes,
        u: solid.u.clone(),
        reactions: solid.reactions(),
        stress,
        contact_pressure,
        contact_shear,
        contact_multipliers: vec![],
    })
}

/// Per pair: nodal pressures, (μ, nodal shear) from the multipliers, and the raw
/// multipliers.
#[allow(clippy::type_complexity)]
fn contact_tractions(
    cp: &ContactProblem,
) -> Result<(
    Vec<Vec<(usize, f64)>>,
    Vec<(f64, Vec<(usize, f64)>)>,
    Vec<Multipliers>,
)> {
    let (mut pressures, mut shear, mut multipliers) = (vec![], vec![], vec![]);
    for (p, &b) in cp.pairs.iter().zip(&cp.mult_base) {
        let lam = &cp.lam[b..b + p.num_multipliers()];
        pressures.push(p.nodal_pressures(lam));
        shear.push((p.friction(), p.nodal_shear(lam)));
        multipliers.push(p.nodal_multipliers(lam));
    }
    // never a non-finite value in an output
    for (i, (p, s)) in pressures.iter().zip(&shear).enumerate() {
        if let Some(&(n, v)) = p.iter().chain(&s.1).find(|(_, v)| !v.is_finite()) {
            return Err(Error::Solve(format!(
                "[[contact]] {}: the contact traction at node {} is {v} (a degenerate \
                 contact there: a node with no share of the surface?)",
                i + 1,
                n + 1
            )));
        }
    }
    Ok((pressures, shear, multipliers))
}

/// The converged states at output times, and the final state (last, so that evaluating
/// them in order leaves the problem in its final state), each with whether it is an output.
fn output_states(
    mut states: Vec<(f64, Vec<f64>)>,
    is_output: impl Fn(f64) -> bool,
) -> Vec<(f64, Vec<f64>, bool)> {
    let last = states.pop();
    let mut out: Vec<(f64, Vec<f64>, bool)> = states
        .into_iter()
        .filter(|s| is_output(s.0))
        .map(|(t, x)| (t, x, true))
        .collect();
    if let Some((t, x)) = last {
        out.push((t, x, is_output(t)));
    }
    out
}

/// Solves a case on a mesh.
pub fn run(case: &CaseFile, mesh: &Mesh, verbose: bool) -> Result<Outcome> {
    let mut problem = build_problem(case, mesh)?;
    // Probes are checked before the (possibly long) solve.
    for c in &case.output.curve {
        crate::post::curve::chain(mesh, &c.group)
            .map_err(|e| Error::model(format!("[[output.curve]] '{}': {e}", c.name)))?;
    }
    for p in &case.output.probe {
        probe_nodes(mesh, p)?;
        if let Some(g) = &p.stress_group {
            mesh.cell_group(g)
                .map_err(|e| Error::model(format!("probe '{}': {e}", p.name)))?;
        }
    }
    let (times, output_times) = loading::schedule(case, &problem.loading)?;
    let settings = NewtonSettings {
        steps: case.solver.steps.max(1),
        times,
        tolerance: case.solver.tolerance,
        max_iterations: case.solver.max_iterations,
        verbose,
        keep_states: case.output.history,
        ..Default::default()
    };
    let end = *settings.times.last().unwrap_or(&1.0);
    // the converged states that are output times (all of them by default)
    let is_output = |t: f64| {
        output_times
            .as_ref()
            .is_none_or(|o| o.iter().any(|&x| (x - t).abs() <= 1e-9 * end))
    };
    let mut steps = vec![];
    let mut contact_multipliers = vec![];
    let (report, contact_pressure, contact_surfaces, contact_shear) = if case.contact.is_empty() {
        let mut report = newton::solve(&mut problem, &settings, Method::Cholesky)?;
        let states = output_states(std::mem::take(&mut report.states), is_output);
        let mut r = vec![0.0; problem.num_unknowns()];
        for (lf, x, output) in &states {
            problem.evaluate(x, *lf, &mut r, false)?;
            if *output {
                steps.push(step_outcome(case, mesh, &problem, *lf, vec![], vec![])?);
            }
        }
        (report, vec![], vec![], vec![])
    } else {
        let pairs = build_pairs(case, mesh)?;
        let mut cp = ContactProblem::new(problem, pairs);
        if let Some(e) = cp.initial_overlap() {
            return Err(Error::model(e));
        }
        // Contact tangents are saddle-point matrices, non-symmetric with friction and mortar
        // geometry terms: condensed on the contact interface (exact), or for a large
        // interface LDLᵀ of a symmetric approximation with GMRES on the exact matrix (LU if
        // that fails).
        let method = Method::SaddleLdlt;
        let mut report = newton::solve(&mut cp, &settings, method)?;
        // Outputs of each converged step; the last state is the final one, so the problem
        // is left where the solve left it.
        let states = output_states(std::mem::take(&mut report.states), is_output);
        let mut r = vec![0.0; cp.num_unknowns()];
        for (lf, x, output) in &states {
            cp.evaluate(x, *lf, &mut r, false)?;
            if !output {
                continue;
            }
            let (p, sh, m) = contact_tractions(&cp)?;
            let mut step = step_outcome(case, mesh, &cp.solid, *lf, p, sh)?;
            step.contact_multipliers = m;
            steps.push(step);
        }
        let (pressures, shear, multipliers) = contact_tractions(&cp)?;
        let surfaces = cp
            .pairs
            .iter()
            .map(|p| {
                let (s, m) = p.surfaces();
                (s.clone(), m.clone())
            })
            .collect();
        problem = cp.solid;
        contact_multipliers = multipliers;
        (report, pressures, surfaces, shear)
    };
    let elno = cell_node_stresses(mesh, &problem.asm, &problem.u)?;
    let stress = nodal_stresses(mesh, &problem.asm, &elno, None)?;
    let mut probes = vec![];
    for p in &case.output.probe {
        probes.push((p.name.clone(), probe(&problem, p, &elno, &stress)?));
    }
    Ok(Outcome {
        report,
        steps,
        contact_pressure,
        contact_multipliers,
        contact_surfaces,
        contact_shear,
        reactions: problem.reactions(),
        u: problem.u.clone(),
        stress,
        probes,
    })
}
