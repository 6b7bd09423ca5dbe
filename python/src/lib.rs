//! `tribo._native`: the Rust side of the Python package. PyO3 (the maintained Rust–Python
//! binding; abi3, so that one build serves every Python from 3.8) over the library
//! functions that `tribo run` uses: `case::parse`, `case::build_mesh`,
//! `case::run_keeping`, `post::results::summary`, the VTU writer. Nothing of the solve is
//! repeated here. Nodal fields cross as raw little-endian f64 bytes that the Python side
//! views as numpy arrays (no numpy crate: no version to keep in step with PyO3's).
//!
//! | file | what |
//! |---|---|
//! | `convert.rs` | Python values <-> TOML values (a case given as a dict) |
//! | `mesh.rs` | `read_mesh` and the nodal arrays of a mesh |

mod convert;
mod mesh;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use std::path::{Path, PathBuf};
use std::time::Instant;
use tribo::case::schema::CaseFile;
use tribo::case::{self, Failure, Outcome};
use tribo::mesh::Mesh;
use tribo::post::results;
use tribo::Error;

create_exception!(
    _native,
    TriboError,
    PyException,
    "An error reported by tribo."
);
create_exception!(
    _native,
    CaseError,
    TriboError,
    "A case that cannot be run: unreadable, malformed, or describing an invalid model."
);
create_exception!(
    _native,
    SolveError,
    TriboError,
    "The solve failed; `report` holds the Newton report, `time` the time of the step that failed."
);

/// A tribo error as the Python exception of its kind, with tribo's message.
fn py_err(e: Error) -> PyErr {
    match e {
        Error::Solve(_) => SolveError::new_err(e.to_string()),
        Error::Memory(_) => TriboError::new_err(e.to_string()),
        _ => CaseError::new_err(e.to_string()),
    }
}

/// A solved case: the case, its mesh, the outcome, and results.json's numbers.
#[pyclass(module = "tribo._native", frozen)]
struct Run {
    case: CaseFile,
    mesh: Mesh,
    outcome: Outcome,
    /// results.json as `tribo run` writes it, less `case` and `files`.
    results: String,
    history_csv: Option<String>,
}

fn f64_bytes<'py>(py: Python<'py>, v: impl Iterator<Item = f64>) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = v.flat_map(f64::to_le_bytes).collect();
    PyBytes::new(py, &bytes)
}

#[pymethods]
impl Run {
    /// results.json's content (JSON text).
    fn results_json(&self) -> &str {
        &self.results
    }
    /// history.csv's content, or None.
    fn history_csv(&self) -> Option<&str> {
        self.history_csv.as_deref()
    }
    /// A nodal field as (f64 little-endian bytes, number of columns); None if the run has
    /// no such field. Contact values are NaN off the slave surfaces.
    fn field<'py>(
        &self,
        py: Python<'py>,
        name: &str,
    ) -> PyResult<Option<(Bound<'py, PyBytes>, usize)>> {
        let o = &self.outcome;
        let flat4 = |s: &[[f64; 4]]| s.iter().flatten().copied().collect::<Vec<_>>();
        let at = results::node_contact(o);
        let n = self.mesh.num_nodes();
        let contact = |f: &dyn Fn(&tribo::post::contact_summary::NodeContact) -> f64| {
            (0..n)
                .map(|i| at.get(&i).map_or(f64::NAN, |c| f(c)))
                .collect::<Vec<f64>>()
        };
        let (values, cols): (Vec<f64>, usize) = match name {
            "coordinates" => (self.mesh.coords.iter().flatten().copied().collect(), 2),
            "displacement" => (o.u.clone(), 2),
            "reactions" => (o.reactions.clone(), 2),
            "stress" => (flat4(&o.stress), 4),
            "von_mises" => (
                o.stress
                    .iter()
                    .map(tribo::fem::material::von_mises)
                    .collect(),
                1,
            ),
            "pk2" => match &o.pk2 {
                Some(p) => (flat4(p), 4),
                None => return Ok(None),
            },
            "contact_pressure" => (contact(&|c| c.pressure), 1),
            "contact_shear" => (contact(&|c| c.shear), 1),
            "contact_gap" => (contact(&|c| c.gap), 1),
            "contact_status" => (contact(&|c| c.status as f64), 1),
            other => {
                return Err(pyo3::exceptions::PyKeyError::new_err(format!(
                    "no nodal field '{other}'"
                )))
            }
        };
        Ok(Some((f64_bytes(py, values.into_iter()), cols)))
    }
    /// The nodes of a group (0-based), from a node group or the nodes of a cell group.
    fn node_group(&self, name: &str) -> PyResult<Vec<usize>> {
        self.mesh.node_group(name).map_err(py_err)
    }
    /// The group names of the mesh.
    fn groups(&self) -> Vec<String> {
        mesh::group_names(&self.mesh)
    }
    /// Writes the final state as `tribo run`'s result.vtu.
    fn write_vtu(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        py.detach(|| {
            let materials = results::material_groups(&self.case);
            let setting = tribo::post::result_vtu::Setting {
                mesh: &self.mesh,
                material_groups: &materials,
            };
            tribo::post::result_vtu::write_state(
                &path,
                &setting,
                &results::final_state(&self.outcome),
            )
        })
        .map_err(py_err)
    }
}

/// A run's failure: the error, and for a failed solve the report and the failing time.
enum RunError {
    Before(Error),
    Solve(Error, String, Option<f64>),
}

fn solve(case: CaseFile, dir: &Path, t0: Instant) -> Result<Run, RunError> {
    let mesh = case::build_mesh(&case.mesh, dir).map_err(RunError::Before)?;
    let outcome = match case::run_keeping(&case, &mesh, false) {
        Ok(o) => o,
        Err(Failure {
            error,
            report: Some(report),
            time,
            ..
        }) => {
            let report = serde_json::to_string(&report).unwrap_or_default();
            return Err(RunError::Solve(error, report, time));
        }
        Err(f) => return Err(RunError::Before(f.error)),
    };
    let summary = results::summary(&case, &mesh, &outcome).map_err(RunError::Before)?;
    let mut json = results::header(&case, &mesh);
    json["status"] = "converged".into();
    if let (Some(all), serde_json::Value::Object(add)) = (json.as_object_mut(), summary.json) {
        all.extend(add);
    }
    json["wall_s"] = t0.elapsed().as_secs_f64().into();
    Ok(Run {
        results: json.to_string(),
        history_csv: summary.history_csv,
        case,
        mesh,
        outcome,
    })
}

/// Solves a case given as a file path (`is_path`) or as TOML text; a text's mesh file is
/// relative to `base_dir`. The GIL is released from parsing to the end of the solve.
/// `threads`: the element kernels' threads (a pool of its own; default: all cores), 1 for
/// variants run side by side, whose own threads would only contend for the cores.
#[pyfunction]
#[pyo3(signature = (source, is_path, base_dir, name, threads=None))]
fn run(
    py: Python<'_>,
    source: String,
    is_path: bool,
    base_dir: PathBuf,
    name: String,
    threads: Option<usize>,
) -> PyResult<Run> {
    let t0 = Instant::now();
    let work = move || {
        let (case, dir) = if is_path {
            case::load(Path::new(&source)).map_err(RunError::Before)?
        } else {
            (
                case::parse(&source, &name).map_err(RunError::Before)?,
                base_dir,
            )
        };
        solve(case, &dir, t0)
    };
    let done = py.detach(move || match threads {
        None => work(),
        Some(n) => match rayon::ThreadPoolBuilder::new()
            .num_threads(n.max(1))
            .build()
        {
            Ok(pool) => pool.install(work),
            Err(e) => Err(RunError::Before(Error::model(format!("thread pool: {e}")))),
        },
    });
    match done {
        Ok(r) => Ok(r),
        Err(RunError::Before(e)) => Err(py_err(e)),
        Err(RunError::Solve(e, report, time)) => {
            let err = SolveError::new_err(e.to_string());
            let value = err.value(py);
            let report = py.import("json")?.call_method1("loads", (report,))?;
            value.setattr("report", report)?;
            value.setattr("time", time)?;
            Err(err)
        }
    }
}

/// A case dict as TOML text (the addresses of values without a TOML form are named).
#[pyfunction]
fn dict_to_toml(case: &Bound<'_, PyDict>) -> PyResult<String> {
    match convert::to_toml(case.as_any(), "")? {
        toml::Value::Table(t) => {
            toml::to_string(&t).map_err(|e| CaseError::new_err(format!("case dict: {e}")))
        }
        _ => unreachable!("a dict converts to a table"),
    }
}

/// A case's TOML text (or file, `is_path`) as a dict; errors name the file and line.
/// `check`: against the case format (false for other TOML files, a sweep's).
#[pyfunction]
#[pyo3(signature = (source, is_path, check=true))]
fn load_case<'py>(
    py: Python<'py>,
    source: &str,
    is_path: bool,
    check: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (text, name) = if is_path {
        let p = Path::new(source);
        let text = std::fs::read_to_string(p).map_err(|e| py_err(Error::io(p, e)))?;
        (text, source.to_string())
    } else {
        (source.to_string(), "case text".to_string())
    };
    // checked against the case format first, so that a misspelt key is reported at once
    if check {
        case::parse(&text, &name).map_err(py_err)?;
    }
    let table: toml::Table = toml::from_str(&text)
        .map_err(|e| py_err(Error::parse(name, e.to_string().trim_end().to_string())))?;
    convert::to_py(py, &toml::Value::Table(table))
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("TriboError", py.get_type::<TriboError>())?;
    m.add("CaseError", py.get_type::<CaseError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    m.add_class::<Run>()?;
    m.add_class::<mesh::PyMesh>()?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(dict_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(load_case, m)?)?;
    m.add_function(wrap_pyfunction!(mesh::read_mesh, m)?)?;
    Ok(())
}
