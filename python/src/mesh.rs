//! `read_mesh`: a mesh file (Gmsh .msh, MED, VTU) read by tribo's readers, with its
//! coordinates, cells and groups for Python.

use crate::py_err;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::path::PathBuf;
use tribo::mesh::Mesh;

/// The names of the cell and node groups of a mesh, sorted, once each.
pub fn group_names(mesh: &Mesh) -> Vec<String> {
    let mut names: Vec<String> = mesh
        .cell_groups
        .keys()
        .chain(mesh.node_groups.keys())
        .cloned()
        .collect();
    names.sort();
    names.dedup();
    names
}

#[pyclass(name = "Mesh", module = "tribo._native", frozen)]
pub struct PyMesh {
    mesh: Mesh,
}

#[pymethods]
impl PyMesh {
    fn num_nodes(&self) -> usize {
        self.mesh.num_nodes()
    }
    fn num_cells(&self) -> usize {
        self.mesh.num_cells()
    }
    /// The coordinates as f64 little-endian bytes, (x, y) per node.
    fn coordinates<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let bytes: Vec<u8> = self
            .mesh
            .coords
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        PyBytes::new(py, &bytes)
    }
    /// The kind of each cell (Tri3, Quad4, Seg2, ...).
    fn cell_types(&self) -> Vec<&'static str> {
        (0..self.mesh.num_cells())
            .map(|c| self.mesh.kind(c).name())
            .collect()
    }
    /// The nodes of each cell (0-based).
    fn cells(&self) -> Vec<Vec<usize>> {
        (0..self.mesh.num_cells())
            .map(|c| self.mesh.cell_nodes(c).to_vec())
            .collect()
    }
    fn groups(&self) -> Vec<String> {
        group_names(&self.mesh)
    }
    /// The cells of a cell group (0-based), or None for a node group only.
    fn cell_group(&self, name: &str) -> Option<Vec<usize>> {
        self.mesh.cell_groups.get(name).cloned()
    }
    /// The nodes of a group (0-based).
    fn node_group(&self, name: &str) -> PyResult<Vec<usize>> {
        self.mesh.node_group(name).map_err(py_err)
    }
}

/// Reads a mesh file (format from its extension, as `tribo mesh info`).
#[pyfunction]
pub fn read_mesh(py: Python<'_>, path: PathBuf) -> PyResult<PyMesh> {
    let mesh = py.detach(|| tribo::mesh::read(&path)).map_err(py_err)?;
    Ok(PyMesh { mesh })
}
