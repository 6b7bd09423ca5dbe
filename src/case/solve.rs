//! Running a case: the solve, then the fields of each converged output step and of the
//! final state. A solve that fails after some converged steps still hands back what they
//! gave (`Failure::partial`), so that a caller can keep the results it has.

pub use super::rigid::RigidState;
use super::schema::CaseFile;
use super::{build_pairs, build_problem, loading, probes};
use crate::contact::problem::ContactProblem;
use crate::contact::surface::Surface;
use crate::error::{Error, Result};
use crate::fem::material::Modelisation;
use crate::fem::solid::{Kinematics, StressMeasure};
use crate::mesh::Mesh;
use crate::post::contact_fields::{contact_fields, ContactFields};
pub use crate::post::contact_state::Multipliers;
use crate::post::contact_summary::PairResult;
use crate::post::probe::StateFields;
use crate::post::stress::{cell_node_stresses, cell_node_stresses_as, nodal_stresses};
use crate::solver::linear::Method;
use crate::solver::newton::{self, NewtonReport, NewtonSettings, Nonlinear};
use crate::solver::problem::SolidProblem;
use std::cell::RefCell;
use std::rc::Rc;

/// What a run produces.
pub struct Outcome {
    pub report: NewtonReport,
    /// The state after each converged load step (when the case writes VTU files).
    pub steps: Vec<StepOutcome>,
    /// Per contact pair: (slave node, pressure) from the multipliers (open nodes: 0).
    pub contact_pressure: Vec<Vec<(usize, f64)>>,
    /// Per contact pair: the slave nodes' contact values and what they add up to.
    pub contact: Vec<PairResult>,
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
    /// The same for the second Piola–Kirchhoff stress (large kinematics only).
    pub pk2: Option<Vec<[f64; 4]>>,
    pub probes: Vec<(String, f64)>,
    /// Per `[[rigid]]`: the reference point's motion and reaction.
    pub rigid: Vec<RigidState>,
}

/// The fields of one converged load step.
pub struct StepOutcome {
    pub time: f64,
    pub probes: Vec<(String, f64)>,
    pub u: Vec<f64>,
    pub reactions: Vec<f64>,
    pub stress: Vec<[f64; 4]>,
    pub pk2: Option<Vec<[f64; 4]>>,
    pub contact_pressure: Vec<Vec<(usize, f64)>>,
    pub contact_shear: Vec<(f64, Vec<(usize, f64)>)>,
    pub contact_multipliers: Vec<Multipliers>,
    pub contact: Vec<PairResult>,
    pub rigid: Vec<RigidState>,
}

impl StepOutcome {
    /// Cuts the nodal fields to the first `nodes` nodes (those of the given mesh).
    fn cut(&mut self, nodes: usize) {
        self.u.truncate(2 * nodes);
        self.reactions.truncate(2 * nodes);
        self.stress.truncate(nodes);
        if let Some(p) = &mut self.pk2 {
            p.truncate(nodes);
        }
    }
}

impl Outcome {
    /// `StepOutcome::cut` of the final state and of every step.
    fn cut(&mut self, nodes: usize) {
        self.u.truncate(2 * nodes);
        self.reactions.truncate(2 * nodes);
        self.stress.truncate(nodes);
        if let Some(p) = &mut self.pk2 {
            p.truncate(nodes);
        }
        for s in &mut self.steps {
            s.cut(nodes);
        }
    }
}

/// Nodal stresses, probes and the fields of the problem's current state.
fn step_outcome(
    case: &CaseFile,
    mesh: &Mesh,
    solid: &SolidProblem,
    time: f64,
    contact: ContactFields,
) -> Result<StepOutcome> {
    let elno = cell_node_stresses(mesh, &solid.asm, &solid.u)?;
    let stress = nodal_stresses(mesh, &solid.asm, &elno, None)?;
    let large = solid
        .asm
        .cell_model
        .iter()
        .any(|m| m.kinematics == Kinematics::Large);
    let pk2_elno = if large {
        Some(cell_node_stresses_as(
            mesh,
            &solid.asm,
            &solid.u,
            StressMeasure::Pk2,
        )?)
    } else {
        None
    };
    let pk2 = match &pk2_elno {
        Some(e) => Some(nodal_stresses(mesh, &solid.asm, e, None)?),
        None => None,
    };
    let fields = StateFields {
        mesh,
        asm: &solid.asm,
        u: &solid.u,
        elno: &elno,
        stress: &stress,
        pk2: pk2_elno.as_ref().zip(pk2.as_deref()),
        deformed: large,
        contact: &contact.pairs,
    };
    let mut values = vec![];
    for p in probes(case, mesh)? {
        values.push((p.name.clone(), p.value(&fields)?));
    }
    let rigid = super::rigid::states(
        &super::rigid::bodies(case, mesh)?,
        mesh,
        &solid.u,
        &solid.residual_full,
        &solid.fext,
        large,
    );
    Ok(StepOutcome {
        rigid,
        time,
        probes: values,
        u: solid.u.clone(),
        reactions: solid.reactions(),
        stress,
        pk2,
        contact_pressure: contact.pressure,
        contact_shear: contact.shear,
        contact_multipliers: contact.multipliers,
        contact: contact.pairs,
    })
}

/// A run that failed: why, and once the solve had begun, its report, the time of the step
/// that failed, and the outcome of the last converged state (None before any converged).
pub struct Failure {
    pub error: Error,
    pub report: Option<Box<NewtonReport>>,
    pub time: Option<f64>,
    pub partial: Option<Box<Outcome>>,
}

impl From<Error> for Failure {
    /// A failure before the solve: nothing to keep.
    fn from(error: Error) -> Self {
        Failure {
            error,
            report: None,
            time: None,
            partial: None,
        }
    }
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
    run_keeping(case, mesh, verbose).map_err(|f| f.error)
}

/// `run` whose failure keeps the converged steps (see `Failure`). With rigid surfaces the
/// solve is on the mesh with their edges and reference nodes added (`rigid::augment`); the
/// nodal fields handed back are cut to the given mesh's nodes.
pub fn run_keeping(
    case: &CaseFile,
    mesh: &Mesh,
    verbose: bool,
) -> std::result::Result<Outcome, Failure> {
    let augmented = super::rigid::augment(case, mesh)?;
    let Some(solved_on) = &augmented else {
        return solve_on(case, mesh, verbose);
    };
    let nodes = mesh.num_nodes();
    solve_on(case, solved_on, verbose)
        .map(|mut o| {
            o.cut(nodes);
            o
        })
        .map_err(|mut f| {
            if let Some(p) = &mut f.partial {
                p.cut(nodes);
            }
            f
        })
}

fn solve_on(case: &CaseFile, mesh: &Mesh, verbose: bool) -> std::result::Result<Outcome, Failure> {
    let mut problem = build_problem(case, mesh)?;
    // Probes are checked before the (possibly long) solve.
    for c in &case.output.curve {
        crate::post::curve::chain(mesh, &c.group)
            .map_err(|e| Error::model(format!("[[output.curve]] '{}': {e}", c.name)))?;
    }
    let probes = probes(case, mesh)?;
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
    let is_output = move |t: f64| {
        output_times
            .as_ref()
            .is_none_or(|o| o.iter().any(|&x| (x - t).abs() <= 1e-9 * end))
    };
    let mut report = NewtonReport::default();
    if case.contact.is_empty() {
        off_surface_probes(&probes, &[])?;
        let solved = newton::solve_into(&mut problem, &settings, Method::Cholesky, &mut report);
        let states = output_states(std::mem::take(&mut report.states), is_output);
        let kept = (solved.is_ok() || !states.is_empty())
            .then(|| without_contact(case, mesh, &mut problem, &states, settings.keep_states));
        finish(solved, kept, report)
    } else {
        let pairs = build_pairs(case, mesh)?;
        supported_slave_nodes(case, &problem, &pairs)?;
        let slaves: Vec<&[usize]> = pairs.iter().map(|p| &p.surfaces().0.nodes[..]).collect();
        off_surface_probes(&probes, &slaves)?;
        let mut cp = ContactProblem::new(problem, pairs);
        if let Some(e) = cp.initial_overlap() {
            return Err(Error::model(e).into());
        }
        // Contact tangents are saddle-point matrices, non-symmetric with friction and mortar
        // geometry terms: condensed on the contact interface (exact), or for a large
        // interface LDLᵀ of a symmetric approximation with GMRES on the exact matrix (LU if
        // that fails).
        let recorded = Rc::new(RefCell::new(vec![]));
        if settings.keep_states {
            let (into, axisymmetric) = (recorded.clone(), is_axisymmetric(case));
            let wanted = is_output.clone();
            cp.on_commit = Some(Box::new(move |cp: &ContactProblem| {
                let t = cp.solid.time;
                if wanted(t) {
                    into.borrow_mut()
                        .push((t, contact_fields(cp, axisymmetric)));
                }
            }));
        }
        let solved = newton::solve_into(&mut cp, &settings, Method::SaddleLdlt, &mut report);
        cp.on_commit = None;
        let recorded = recorded.take();
        let states = output_states(std::mem::take(&mut report.states), is_output);
        let kept = (solved.is_ok() || !states.is_empty())
            .then(|| with_contact(case, mesh, &mut cp, &states, recorded, settings.keep_states));
        finish(solved, kept, report)
    }
}

/// A probe of a contact field on a node of no slave surface (`slaves`: their nodes,
/// sorted) is refused before the solve: the node has no contact values.
fn off_surface_probes(probes: &[crate::post::probe::Probe], slaves: &[&[usize]]) -> Result<()> {
    match probes
        .iter()
        .find_map(|p| p.off_surface(slaves).map(|n| (p, n)))
    {
        Some((p, n)) => Err(Error::model(format!(
            "probe '{}': node {} is on no slave surface of a [[contact]] (the surface that \
             carries the multipliers): it has no contact values",
            p.name,
            n + 1
        ))),
        None => Ok(()),
    }
}

/// The outcome of a solve (`solved`) from the fields of its last converged state (`kept`,
/// None when no step converged).
fn finish(
    solved: Result<()>,
    kept: Option<Result<Outcome>>,
    report: NewtonReport,
) -> std::result::Result<Outcome, Failure> {
    let time = report.steps.last().filter(|s| !s.converged).map(|s| s.time);
    match (solved, kept.transpose()) {
        (Ok(()), Ok(Some(mut o))) => {
            o.report = report;
            Ok(o)
        }
        (Ok(()), Ok(None)) => Err(Failure {
            error: Error::solve("the solve ended without a converged state"),
            report: Some(Box::new(report)),
            time,
            partial: None,
        }),
        (Ok(()), Err(error)) => Err(Failure {
            error,
            report: Some(Box::new(report)),
            time,
            partial: None,
        }),
        (Err(error), kept) => {
            // an error in the outputs of the kept states leaves the solve's error as the cause
            let partial = kept.ok().flatten().map(|mut o| {
                o.report = report.clone();
                Box::new(o)
            });
            Err(Failure {
                error,
                report: Some(Box::new(report)),
                time,
                partial,
            })
        }
    }
}

/// The outcome of a problem without contact: its output states evaluated in order (the
/// problem is left in the last one), the output steps among them when `keep`.
fn without_contact(
    case: &CaseFile,
    mesh: &Mesh,
    problem: &mut SolidProblem,
    states: &[(f64, Vec<f64>, bool)],
    keep: bool,
) -> Result<Outcome> {
    let mut steps = vec![];
    let mut r = vec![0.0; problem.num_unknowns()];
    for (lf, x, output) in states {
        problem.evaluate(x, *lf, &mut r, false)?;
        if *output && keep {
            steps.push(step_outcome(
                case,
                mesh,
                problem,
                *lf,
                ContactFields::none(),
            )?);
        }
    }
    final_outcome(case, mesh, problem, steps, ContactFields::none())
}

fn is_axisymmetric(case: &CaseFile) -> bool {
    case.model.modelisation == Modelisation::Axisymmetric
}

/// `without_contact` with contact: the pressures, shear and multipliers of each output
/// state too, those `recorded` at the state's commit (by time).
fn with_contact(
    case: &CaseFile,
    mesh: &Mesh,
    cp: &mut ContactProblem,
    states: &[(f64, Vec<f64>, bool)],
    mut recorded: Vec<(f64, Result<ContactFields>)>,
    keep: bool,
) -> Result<Outcome> {
    let axisymmetric = is_axisymmetric(case);
    let mut steps = vec![];
    let mut r = vec![0.0; cp.num_unknowns()];
    for (lf, x, output) in states {
        cp.evaluate(x, *lf, &mut r, false)?;
        if !(*output && keep) {
            continue;
        }
        // (evaluated again here, a state would get the last step's statuses and friction
        // history: every output state is recorded at its commit)
        let contact = match recorded.iter().position(|(t, _)| t == lf) {
            Some(k) => recorded.swap_remove(k).1?,
            None => {
                return Err(Error::solve(format!(
                    "internal error: no contact outputs were recorded for the state at t = {lf}"
                )))
            }
        };
        steps.push(step_outcome(case, mesh, &cp.solid, *lf, contact)?);
    }
    let contact = contact_fields(cp, axisymmetric)?;
    let mut o = final_outcome(case, mesh, &cp.solid, steps, contact)?;
    o.contact_surfaces = cp
        .pairs
        .iter()
        .map(|p| {
            let (s, m) = p.surfaces();
            (s.clone(), m.clone())
        })
        .collect();
    Ok(o)
}

/// The outcome of the problem's current state (no contact fields, an empty report).
fn final_outcome(
    case: &CaseFile,
    mesh: &Mesh,
    problem: &SolidProblem,
    steps: Vec<StepOutcome>,
    contact: ContactFields,
) -> Result<Outcome> {
    let last = step_outcome(case, mesh, problem, 0.0, contact)?;
    Ok(Outcome {
        report: NewtonReport::default(),
        steps,
        contact_pressure: last.contact_pressure,
        contact_multipliers: last.contact_multipliers,
        contact_surfaces: vec![],
        contact_shear: last.contact_shear,
        contact: last.contact,
        reactions: last.reactions,
        u: last.u,
        stress: last.stress,
        pk2: last.pk2,
        probes: last.probes,
        rigid: last.rigid,
    })
}

/// A slave node with both displacements imposed (a support, a rotation) facing a master
/// node with both imposed too has a contact constraint that acts on nothing:
/// node-to-segment's row is then empty (a singular system naming nothing) and quadratic
/// mortar's nearly so (displacements of 1e16 without an error). Refused, naming the node
/// and what to do.
fn supported_slave_nodes(
    case: &CaseFile,
    problem: &SolidProblem,
    pairs: &[Box<dyn crate::contact::pair::ContactPair>],
) -> Result<()> {
    // (a dof that depends on no unknown: imposed, or linked to imposed ones only, as the
    // nodes of a rigid surface whose motion is imposed)
    let dofs = &problem.asm.dofs;
    let held = |d: usize| {
        let mut on = vec![];
        dofs.expand_dof(d, &mut on);
        on.is_empty()
    };
    let fixed = |n: usize| held(2 * n) && held(2 * n + 1);
    let coords = &problem.mesh.coords;
    for (i, (p, c)) in pairs.iter().zip(&case.contact).enumerate() {
        let master = &p.surfaces().1.nodes;
        // (a slave moved as a whole, a rigid indenter, still acts on the master's nodes)
        // (the nearest master node is searched only for the supported slave nodes)
        let nearest = |n: usize| {
            let d = |m: usize| (coords[m][0] - coords[n][0]).hypot(coords[m][1] - coords[n][1]);
            master
                .iter()
                .copied()
                .min_by(|&a, &b| d(a).total_cmp(&d(b)))
        };
        let held = p.multiplier_nodes().iter().find(|&&n| {
            !p.excluded_nodes().contains(&n) && fixed(n) && nearest(n).is_some_and(fixed)
        });
        if let Some(&n) = held {
            return Err(Error::model(format!(
                "[[contact]] {} ({} on {}): slave node {} has both displacements imposed, and \
                 so has the master node it faces: its contact constraint acts on nothing; \
                 impose one component only, leave the node out of the slave surface, or \
                 list it in exclude",
                i + 1,
                c.slave,
                c.master,
                n + 1
            )));
        }
    }
    Ok(())
}
