//! Built-in meshes (placeholder until the generator lands).
use super::{CellKind, Mesh};
use crate::error::{Error, Result};

#[derive(Clone, Debug)]
pub struct Ssnp154Options {
    pub quadratic: bool,
    pub size: f64,
    pub global_refine: usize,
}
impl Default for Ssnp154Options {
    fn default() -> Self {
        Ssnp154Options {
            quadratic: false,
            size: 1.5,
            global_refine: 0,
        }
    }
}
pub fn ssnp154(_o: &Ssnp154Options) -> Result<Mesh> {
    Err(Error::model("not yet"))
}
pub fn rectangle(
    _o: [f64; 2],
    _w: f64,
    _h: f64,
    _nx: usize,
    _ny: usize,
    _k: CellKind,
    _d: f64,
) -> Result<Mesh> {
    Err(Error::model("not yet"))
}
pub fn ring(_a: f64, _b: f64, _n: usize, _m: usize, _ang: f64, _k: CellKind) -> Result<Mesh> {
    Err(Error::model("not yet"))
}
