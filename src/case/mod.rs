//! Case files: load and check a TOML case, build the mesh and the discrete problem, run it.
//!
//! | file | what |
//! |---|---|
//! | `schema.rs` | serde structs of the TOML format (unknown keys rejected) |
//! | `checks.rs` | every value finite and in range, every key meaningful, before any work |
//! | `loading/` | time functions, loads and imposed motions, step ends, output times |
//! | `pairs.rs` | the contact pairs |
//! | `rigid/` | rigid surfaces moved by a reference point: mesh, dof links, reactions |
//! | `solve.rs` | a run: the solve and its outcome, or what a failed one kept |
//! | `sizes.rs` | memory estimates of generated meshes and of the model, checked before work |
//! | `ssnp154.rs` | the built-in SSNP154 cases |

pub mod checks;
pub mod loading;
pub mod pairs;
pub mod rigid;
pub mod schema;
mod sizes;
pub mod solve;
pub mod ssnp154;

pub use pairs::build_pairs;
pub use solve::{run, run_keeping, Failure, Multipliers, Outcome, RigidState, StepOutcome};

use crate::assembly::dofs::{DofMap, Relation};
use crate::assembly::Assembler;
use crate::error::{Error, Result};
use crate::fem::material::{Elastic, Modelisation};
use crate::fem::solid::SolidModel;
use crate::mesh::{generate, CellKind, Mesh};
use crate::solver::problem::SolidProblem;
use schema::CaseFile;
use std::path::{Path, PathBuf};

/// Reads a case file; syntax errors and unknown keys name the file, line and valid keys.
pub fn load(path: &Path) -> Result<(CaseFile, PathBuf)> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let case = parse(&text, &path.display().to_string())?;
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    Ok((case, dir))
}

/// Parses the text of a case; `source` names it in error messages (a file, or what the text
/// came from).
pub fn parse(text: &str, source: &str) -> Result<CaseFile> {
    toml::from_str(text).map_err(|e| Error::parse(source, e.to_string().trim_end().to_string()))
}

/// The probes of a case, checked against the mesh (errors name the probe).
pub fn probes(case: &CaseFile, mesh: &Mesh) -> Result<Vec<crate::post::probe::Probe>> {
    case.output
        .probe
        .iter()
        .map(|p| {
            crate::post::probe::Probe::new(
                mesh,
                &crate::post::probe::ProbeInput {
                    name: &p.name,
                    group: p.group.as_deref(),
                    at: p.at,
                    field: &p.field,
                    stress_group: p.stress_group.as_deref(),
                    centre: p.center,
                },
            )
        })
        .collect()
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
    sizes::check_generated(spec)?;
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
    sizes::check_model(case, mesh)?;
    let m = &case.model;
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
        let what = format!("[[material]] for {}", spec.label());
        let cells = spec
            .cells(mesh)
            .map_err(|e| Error::model(format!("[[material]]: {e}")))?;
        if let Some(g) = &spec.group {
            if mesh.group_dim(g) != Some(2) {
                return Err(Error::model(format!(
                    "{what}: the group is not made of 2D cells"
                )));
            }
        }
        materials.push(Elastic::new(spec.young, spec.nu, &what)?);
        for c in cells {
            if let Some(j) = material_of[c] {
                return Err(Error::model(format!(
                    "{what}: cell {} is also in {} of [[material]] {}: a cell has one \
                     material",
                    c + 1,
                    case.material[j].label(),
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
    // a rigid surface's reference point: its translation and rotation dofs
    let rigid = rigid::bodies(case, mesh)?;
    for b in &rigid {
        used[2 * b.ref_node] = true;
        used[2 * b.ref_node + 1] = true;
        used[2 * b.rot_node] = true;
    }
    let loading::Built {
        fixed,
        rhs,
        loading,
    } = loading::build(case, mesh)?;
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
        if cancel && rhs[i] == 0.0 && loading.relation_exprs[i].is_none() {
            return Err(Error::model(format!(
                "[[relation]] '{name}': its terms cancel (the coefficients of each dof add up \
                 to zero), the relation says nothing"
            )));
        }
        relations.push(Relation {
            terms,
            rhs: rhs[i],
            name,
        });
    }
    let mut dofs = DofMap::new(&used, &fixed, &relations)?;
    rigid::link(&mut dofs, mesh, &rigid);
    // Without contact the matrix is SPD: Cholesky reads the lower triangle only.
    let asm = Assembler::new(mesh, cells, models, dofs, case.contact.is_empty())?;
    Ok(SolidProblem::with_loading(mesh, asm, loading))
}
