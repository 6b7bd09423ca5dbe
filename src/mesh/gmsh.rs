//! Gmsh MSH reader (placeholder until the reader lands).
use super::Mesh;
use crate::error::{Error, Result};
pub fn read(path: &std::path::Path) -> Result<Mesh> {
    Err(Error::model(format!("{}: not yet", path.display())))
}
