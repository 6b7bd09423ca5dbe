//! Case files: load and check a TOML case, build the mesh and the discrete problem, run it.
//!
//! | file | what |
//! |---|---|
//! | `schema.rs` | serde structs of the TOML format (unknown keys rejected) |
//! | `checks.rs` | every value finite and in range, every key meaningful, before any work |
//! | `loading.rs` | time functions, loads and imposed motions, step ends, output times |
//! | `solve.rs` | a run: the solve and its outcome, or what a failed one kept |
//! | `ssnp154.rs` | the built-in SSNP154 cases |

pub mod checks;
pub mod loading;
pub mod schema;
pub mod solve;
pub mod ssnp154;

pub use solve::{run, run_keeping, Failure, Multipliers, Outcome, StepOutcome};

use crate::assembly::dofs::{DofMap, Relation};
use crate::assembly::Assembler;
use crate::contact::mortar::Mortar;
use crate::contact::pair::ContactPair;
use crate::contact::point_segment::{self, InitialStatus, Integration, PointToSegment};
use crate::contact::surface::Surface;
use crate::error::{Error, Result};
use crate::fem::material::{Elastic, Modelisation};
use crate::fem::solid::{Kinematics, SolidModel};
use crate::mesh::{generate, CellKind, Mesh};
use crate::post::stress::{nodal_stresses, CellNodeStresses};
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

/// Stress component of a probe field (4 = von Mises), None for displacements.
fn probe_component(spec: &schema::ProbeSpec) -> Result<Option<usize>> {
    Ok(match spec.field.as_str() {
        "dx" | "dy" => None,
        "sixx" => Some(0),
        "siyy" => Some(1),
        "sizz" => Some(2),
        "sixy" => Some(3),
        "vmis" => Some(4),
        other => {
            return Err(Error::model(format!(
                "probe '{}': field '{other}' is not one of dx, dy, sixx, siyy, sizz, sixy, vmis",
                spec.name
            )))
        }
    })
}

/// The nodes a probe averages over: its group's, or the node nearest to its point.
pub(crate) fn probe_nodes(mesh: &Mesh, spec: &schema::ProbeSpec) -> Result<Vec<usize>> {
    let what = format!("probe '{}'", spec.name);
    match (&spec.group, spec.at) {
        (Some(g), None) => mesh
            .node_group(g)
            .map_err(|e| Error::model(format!("{what}: {e}"))),
        (None, Some(p)) => {
            let cells: Vec<usize> = match &spec.stress_group {
                Some(g) => mesh
                    .cell_group(g)
                    .map_err(|e| Error::model(format!("{what}: {e}")))?
                    .to_vec(),
                None => mesh.cells_of_dim(2).collect(),
            };
            let nearest = cells
                .iter()
                .flat_map(|&c| mesh.cell_nodes(c).iter().copied())
                .min_by(|&a, &b| {
                    let d = |n: usize| (mesh.coords[n][0] - p[0]).hypot(mesh.coords[n][1] - p[1]);
                    d(a).total_cmp(&d(b))
                })
                .ok_or_else(|| Error::model(format!("{what}: no node to probe")))?;
            Ok(vec![nearest])
        }
        _ => Err(Error::model(format!(
            "{what}: give either group = \"NAME\" or at = [x, y]"
        ))),
    }
}

/// Value of a probe: mean of the field over the nodes of its group (or at its node).
/// `elno` are the cell-node stresses of the state, `all` their average over every cell.
pub fn probe(
    problem: &SolidProblem,
    spec: &schema::ProbeSpec,
    elno: &CellNodeStresses,
    all: &[[f64; 4]],
) -> Result<f64> {
    let mesh = problem.mesh;
    let what = format!("probe '{}'", spec.name);
    let nodes = probe_nodes(mesh, spec)?;
    let comp = probe_component(spec)?;
    let values: Vec<f64> = match comp {
        None => {
            let c = if spec.field == "dx" { 0 } else { 1 };
            nodes.iter().map(|&n| problem.u[2 * n + c]).collect()
        }
        Some(k) => {
            let local;
            let s = match &spec.stress_group {
                Some(g) => {
                    local = nodal_stresses(mesh, &problem.asm, elno, Some(g))
                        .map_err(|e| Error::model(format!("{what}: {e}")))?;
                    &local
                }
                None => all,
            };
            nodes
                .iter()
                .map(|&n| {
                    if k == 4 {
                        crate::fem::material::von_mises(&s[n])
                    } else {
                        s[n][k]
                    }
                })
                .collect()
        }
    };
    if values.iter().any(|v| v.is_nan()) {
        return Err(Error::model(format!(
            "{what}: some nodes of group '{}' are in no cell of the stress group",
            spec.group.as_deref().unwrap_or("")
        )));
    }
    Ok(values.iter().sum::<f64>() / values.len() as f64)
}

/// The contact pairs of a case.
/// The nodes of the node groups listed under `key` of a contact entry.
fn group_nodes(mesh: &Mesh, groups: &[String], what: &str, key: &str) -> Result<Vec<usize>> {
    let mut nodes = vec![];
    for g in groups {
        nodes.extend(
            mesh.node_group(g)
                .map_err(|e| Error::model(format!("{what}: {key}: {e}")))?,
        );
    }
    Ok(nodes)
}

/// The smallest Young's modulus of the case and the shortest cell chord of `slave`: the
/// scales of the contact parameters' defaults (no units in a default).
fn stiffness_scale(case: &CaseFile, mesh: &Mesh, slave: &Surface) -> (f64, f64) {
    let e_min = case
        .material
        .iter()
        .map(|m| m.young)
        .fold(f64::INFINITY, f64::min);
    let h_min = slave
        .cells
        .iter()
        .map(|&e| {
            let n = mesh.cell_nodes(e);
            let (a, b) = (mesh.coords[n[0]], mesh.coords[n[1]]);
            (a[0] - b[0]).hypot(a[1] - b[1])
        })
        .fold(f64::INFINITY, f64::min);
    (e_min, h_min)
}

/// The multiplier indices of `nodes` on a mortar pair: a node of the surface that carries
/// the multipliers, or one at the same place on the other surface (the pair may have put
/// the multipliers on the surface the user named master); Err(node) for a node on neither.
fn multiplier_indices(
    mesh: &Mesh,
    m: &Mortar,
    nodes: &[usize],
) -> std::result::Result<Vec<usize>, usize> {
    let (lo, hi) = crate::mesh::quality::bounding_box(mesh);
    let tol = 1e-9 * (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let mut out = vec![];
    for &n in nodes {
        if let Some(k) = m.mult_nodes.iter().position(|&s| s == n) {
            out.push(k);
            continue;
        }
        if !m.master.nodes.contains(&n) {
            return Err(n);
        }
        let x = mesh.coords[n];
        if let Some(k) = m.mult_nodes.iter().position(|&s| {
            let y = mesh.coords[s];
            (x[0] - y[0]).hypot(x[1] - y[1]) <= tol
        }) {
            out.push(k);
        }
    }
    Ok(out)
}

pub fn build_pairs(case: &CaseFile, mesh: &Mesh) -> Result<Vec<Box<dyn ContactPair>>> {
    let mut pairs: Vec<Box<dyn ContactPair>> = vec![];
    // per cell, the compliance of its material (1 when it has none: an obstacle's cells
    // all have one, but a malformed case is reported elsewhere)
    let mut compliance = vec![1.0; mesh.num_cells()];
    for spec in &case.material {
        let c = match case.model.modelisation {
            Modelisation::PlaneStress => 1.0 / spec.young,
            _ => (1.0 - spec.nu * spec.nu) / spec.young,
        };
        if let Ok(cells) = mesh.cell_group(&spec.group) {
            for &cell in cells {
                compliance[cell] = c;
            }
        }
    }
    let bodies = crate::mesh::topology::node_bodies(mesh);
    for (i, c) in case.contact.iter().enumerate() {
        let what = format!("[[contact]] {} ({} on {})", i + 1, c.slave, c.master);
        if c.slave == c.master {
            return Err(Error::model(format!(
                "{what}: slave and master must be different groups"
            )));
        }
        let slave = Surface::from_group(mesh, &c.slave, "slave")
            .map_err(|e| Error::model(format!("{what}: {e}")))?;
        let master = Surface::from_group(mesh, &c.master, "master")
            .map_err(|e| Error::model(format!("{what}: {e}")))?;
        // Checked after the options, so that their errors come first.
        let same_body = || -> Result<()> {
            let of = |s: &Surface| -> std::collections::BTreeSet<usize> {
                s.nodes.iter().map(|&n| bodies[n]).collect()
            };
            if of(&slave).is_disjoint(&of(&master)) {
                return Ok(());
            }
            Err(Error::model(format!(
                "{what}: '{}' and '{}' belong to the same body (its cells are connected \
                 through shared nodes); self-contact is not supported: split the body or pick \
                 surfaces of two bodies",
                c.slave, c.master
            )))
        };
        let integration = match c.integration.as_str() {
            "gauss" if (1..=10).contains(&c.gauss_points) => Integration::Gauss(c.gauss_points),
            "gauss" => {
                return Err(Error::model(format!(
                    "{what}: gauss_points must be 1 to 10, got {}",
                    c.gauss_points
                )))
            }
            "nodal" => Integration::Nodal,
            other => {
                return Err(Error::model(format!(
                    "{what}: integration '{other}' is not one of gauss, nodal"
                )))
            }
        };
        let initial = match c.initial.as_str() {
            "all" => InitialStatus::All,
            "closed" => InitialStatus::Closed,
            other => {
                return Err(Error::model(format!(
                    "{what}: initial '{other}' is not one of all, closed"
                )))
            }
        };
        if let Some(g) = c.initial_gap {
            if g.is_nan() || g < 0.0 || initial != InitialStatus::Closed {
                return Err(Error::model(format!(
                    "{what}: initial_gap must be 0 or positive and goes with initial = \"closed\", got {g} \
                     with initial = \"{}\"",
                    c.initial
                )));
            }
        }
        if c.friction.is_nan() || c.friction < 0.0 {
            return Err(Error::model(format!(
                "{what}: friction must be 0 or positive, got {}",
                c.friction
            )));
        }
        if let Some(a) = c.adjust {
            if !(a.is_finite() && a >= 0.0) || c.formulation != "mortar" {
                return Err(Error::model(format!(
                    "{what}: adjust (a distance: initial gaps and overlaps up to it are removed) \
                     must be finite and 0 or positive and goes with formulation = \"mortar\", \
                     got {a} with formulation = \"{}\"",
                    c.formulation
                )));
            }
        }
        let node_to_segment = c.formulation == "node-to-segment";
        if !node_to_segment && (c.penalty.is_some() || !c.exclude.is_empty()) {
            return Err(Error::model(format!(
                "{what}: penalty and exclude go with formulation = \"node-to-segment\""
            )));
        }
        if let Some(k) = c.penalty {
            if k.is_nan() || k <= 0.0 {
                return Err(Error::model(format!(
                    "{what}: penalty must be positive, got {k}"
                )));
            }
        }
        match c.formulation.as_str() {
            "point-to-segment" | "node-to-segment" => {}
            "mortar" => {
                same_body()?;
                let (slave, master, _) = crate::contact::mortar::multiplier_side(mesh, slave, master);
                // complementarity parameter: the softest E over the shortest slave cell
                let (e_min, h_min) = stiffness_scale(case, mesh, &slave);
                let mut mortar = Mortar::new(
                    mesh,
                    slave,
                    master,
                    e_min / h_min,
                    case.model.modelisation,
                    case.model.thickness,
                    case.model.kinematics == Kinematics::Small,
                );
                mortar.initial_gap = c.initial_gap;
                mortar.adjust = c.adjust;
                let of = |s: &Surface| -> Vec<f64> {
                    s.parent.iter().map(|&p| compliance[p]).collect()
                };
                mortar.compliance = (of(&mortar.slave), of(&mortar.master));
                // a micro-strain of the softest body: below it a pressure is round-off
                mortar.pressure_floor = 1e-6 * e_min;
                if c.friction > 0.0 {
                    mortar.friction = Some(c.friction);
                    let nodes = group_nodes(mesh, &c.friction_exclude, &what, "friction_exclude")?;
                    mortar.friction_excluded = multiplier_indices(mesh, &mortar, &nodes)
                        .map_err(|n| {
                            Error::model(format!(
                                "{what}: friction_exclude: node {} is on neither contact surface",
                                n + 1
                            ))
                        })?;
                }
                pairs.push(Box::new(mortar));
                continue;
            }
            other => {
                return Err(Error::model(format!(
                    "{what}: formulation '{other}' is not one of point-to-segment, node-to-segment, mortar"
                )))
            }
        }
        // scale-free defaults: the softest body's modulus over the shortest slave cell
        let (e_min, h_min) = stiffness_scale(case, mesh, &slave);
        let friction_excluded = group_nodes(mesh, &c.friction_exclude, &what, "friction_exclude")?;
        let contact_excluded = group_nodes(mesh, &c.exclude, &what, "exclude")?;
        let opts = point_segment::Options {
            integration,
            node_to_segment,
            penalty: c.penalty,
            contact_excluded,
            rho: c.rho.unwrap_or(1e-3 * e_min / h_min),
            initial,
            initial_gap: c.initial_gap,
            friction: (c.friction > 0.0).then_some(c.friction),
            rho_f: c.rho_f.unwrap_or(60.0 / h_min),
            friction_excluded,
            ..Default::default()
        };
        same_body()?;
        pairs.push(Box::new(PointToSegment::new(
            mesh,
            slave,
            master,
            opts,
            case.model.modelisation,
            case.model.thickness,
        )));
    }
    Ok(pairs)
}
