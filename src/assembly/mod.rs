//! Global assembly: element kernels in, reduced residual and sparse tangent out.
//!
//! | file | what |
//! |---|---|
//! | `coupled/` | the solid matrix extended in place by contact triplets over extra unknowns |
//! | `dofs.rs` | `DofMap`: free, imposed and linked dofs (elimination) |
//! | `matrix.rs` | CSC matrix with a fixed pattern, faer view |
//! | `pattern.rs` | the assembler's pattern and per-cell scatter positions |
//! | `loads.rs` | nodal forces, edge pressures and tractions |
//!
//! The pattern and, per cell, the position of every local entry in the global value array
//! are computed once (`Assembler::new`); each assembly only refills values. Element
//! matrices are computed in parallel blocks and scattered serially (no locking), the
//! scatter of one block overlapping the kernels of the next.

pub mod coupled;
pub mod dofs;
pub mod loads;
pub mod matrix;
mod pattern;

use crate::error::{Error, Result};
use crate::fem::solid::{residual_tangent, SolidModel, MAX_DOFS};
use crate::mesh::Mesh;
use dofs::DofMap;
use matrix::SparseMatrix;
use rayon::prelude::*;

const NONE: u32 = u32::MAX;
/// Marks a local entry that involves a linked dof: handled on the slow path.
const LINKED: u32 = u32::MAX - 1;
/// Cells per block: small enough that the first block's kernels and the last block's
/// scatter, which run alone, are short.
const BLOCK: usize = 256;

pub struct Assembler {
    pub dofs: DofMap,
    /// Over the free dofs; a contact problem extends it to its multipliers and contact
    /// entries (`coupled::CoupledMatrix`), the scatter then following its pattern.
    pub matrix: SparseMatrix,
    /// Counts the assemblies of `matrix` (a copy of it is current while this is unchanged).
    pub matrix_generation: u64,
    /// The 2D cells that carry stiffness, and the solid model of each.
    pub cells: Vec<usize>,
    pub cell_model: Vec<SolidModel>,
    scatter_start: Vec<usize>,
    scatter: Vec<u32>,
    /// Only the lower triangle is stored (enough for Cholesky; halves the memory).
    pub lower_only: bool,
    /// Element vectors and matrices of two blocks of cells, kept between assemblies (a
    /// fresh buffer per call costs more in page faults than the kernels).
    bufs: [(Vec<f64>, Vec<f64>); 2],
}

impl Assembler {
    /// `cells[i]` gets `models[i]`. Builds the pattern over the free dofs; with
    /// `lower_only`, only its lower triangle (rows ≥ column) is stored and assembled.
    pub fn new(
        mesh: &Mesh,
        cells: Vec<usize>,
        models: Vec<SolidModel>,
        dofs: DofMap,
        lower_only: bool,
    ) -> Result<Self> {
        let pattern::Pattern {
            matrix,
            scatter_start,
            scatter,
        } = pattern::build(mesh, &cells, &dofs, lower_only);
        if matrix.nnz() >= LINKED as usize {
            return Err(Error::solve(
                "matrix too large for 32-bit scatter positions",
            ));
        }
        Ok(Assembler {
            dofs,
            matrix,
            cells,
            cell_model: models,
            scatter_start,
            scatter,
            lower_only,
            matrix_generation: 0,
            bufs: Default::default(),
        })
    }

    /// The matrix and the cells' scatter, for `CoupledMatrix::update` (which may extend
    /// the pattern and move the scatter with it), and the dof map.
    pub fn solid_target(&mut self) -> (coupled::SolidTarget<'_>, &DofMap) {
        let target = coupled::SolidTarget {
            matrix: &mut self.matrix,
            generation: self.matrix_generation,
            cell_scatter: &mut self.scatter,
            reserved: LINKED,
        };
        (target, &self.dofs)
    }

    /// Internal forces at full displacement `u` into `fint` (full dofs, overwritten) and,
    /// if `with_matrix`, the reduced tangent Tᵀ K T into `self.matrix.values`.
    pub fn assemble(
        &mut self,
        mesh: &Mesh,
        u: &[f64],
        fint: &mut [f64],
        with_matrix: bool,
    ) -> Result<()> {
        fint.fill(0.0);
        if with_matrix {
            self.matrix.values.fill(0.0);
            self.matrix_generation += 1;
        }
        let block = BLOCK.min(self.cells.len()).max(1);
        let per_cell = if with_matrix { MAX_DOFS * MAX_DOFS } else { 0 };
        // two buffers: the kernels fill one block while the other is scattered
        let mut bufs = std::mem::take(&mut self.bufs);
        for (fbuf, kbuf) in bufs.iter_mut() {
            fbuf.resize(block * MAX_DOFS, 0.0);
            if with_matrix {
                kbuf.resize(block * per_cell, 0.0);
            }
        }
        let Assembler {
            dofs,
            matrix,
            cells,
            cell_model,
            scatter_start,
            scatter,
            lower_only,
            ..
        } = self;
        let (cells, cell_model) = (&cells[..], &cell_model[..]);
        let compute = |start: usize, fbuf: &mut [f64], kbuf: &mut [f64]| -> Result<()> {
            let end = (start + block).min(cells.len());
            let kernel = |i: usize, fe: &mut [f64], ke: Option<&mut [f64]>| {
                let c = cells[start + i];
                let kind = mesh.kind(c);
                let (x, nn) = mesh.cell_coords(c);
                let mut ue = [[0.0; 2]; 8];
                for (a, &n) in mesh.cell_nodes(c).iter().enumerate() {
                    ue[a] = [u[2 * n], u[2 * n + 1]];
                }
                residual_tangent(kind, &x[..nn], &ue[..nn], &cell_model[start + i], fe, ke)
                    .map_err(|_| c)
            };
            let res: std::result::Result<Vec<()>, usize> = if with_matrix {
                fbuf.par_chunks_mut(MAX_DOFS)
                    .zip(kbuf.par_chunks_mut(per_cell))
                    .take(end - start)
                    .enumerate()
                    .map(|(i, (fe, ke))| kernel(i, fe, Some(ke)))
                    .collect()
            } else {
                fbuf.par_chunks_mut(MAX_DOFS)
                    .take(end - start)
                    .enumerate()
                    .map(|(i, fe)| kernel(i, fe, None))
                    .collect()
            };
            res.map(|_| ()).map_err(|c| {
                Error::solve(format!(
                    "cell {} ({}) has a non-positive Jacobian at a quadrature point",
                    c + 1,
                    mesh.kind(c)
                ))
            })
        };
        // Cells are scattered in their order whatever the blocks: the sums, and so the
        // results, are those of a serial assembly.
        let mut scatter_block = |start: usize, fbuf: &[f64], kbuf: &[f64]| {
            let end = (start + block).min(cells.len());
            let (mut tmp_a, mut tmp_b) = (vec![], vec![]);
            for (i, &c) in cells[start..end].iter().enumerate() {
                let nodes = mesh.cell_nodes(c);
                let nd = 2 * nodes.len();
                let fe = &fbuf[i * MAX_DOFS..];
                for a in 0..nd {
                    fint[2 * nodes[a / 2] + a % 2] += fe[a];
                }
                if !with_matrix {
                    continue;
                }
                let ke = &kbuf[i * per_cell..];
                let sc = &scatter[scatter_start[start + i]..];
                for a in 0..nd {
                    for b in 0..nd {
                        let p = sc[a * nd + b];
                        if p < LINKED {
                            matrix.values[p as usize] += ke[a * nd + b];
                        } else if p == LINKED {
                            let da = 2 * nodes[a / 2] + a % 2;
                            let db = 2 * nodes[b / 2] + b % 2;
                            dofs.expand_dof(da, &mut tmp_a);
                            dofs.expand_dof(db, &mut tmp_b);
                            for &(i2, ca) in &tmp_a {
                                for &(j2, cb) in &tmp_b {
                                    if *lower_only && i2 < j2 {
                                        continue;
                                    }
                                    let pos =
                                        matrix.position(i2, j2).expect("pattern covers links");
                                    matrix.values[pos] += ca * cb * ke[a * nd + b];
                                }
                            }
                        }
                    }
                }
            }
        };
        let starts: Vec<usize> = (0..cells.len()).step_by(block).collect();
        let [(f0, k0), (f1, k1)] = &mut bufs;
        let mut result = match starts.first() {
            Some(&s0) => compute(s0, f0, k0),
            None => Ok(()),
        };
        for (b, &s) in starts.iter().enumerate() {
            if result.is_err() {
                break;
            }
            // scatter block b while the kernels of block b + 1 run on the other buffer
            let ((fc, kc), (fnext, knext)) = if b % 2 == 0 {
                ((&*f0, &*k0), (&mut *f1, &mut *k1))
            } else {
                ((&*f1, &*k1), (&mut *f0, &mut *k0))
            };
            let next = starts.get(b + 1).copied();
            let ((), r) = rayon::join(
                || scatter_block(s, fc, kc),
                || next.map_or(Ok(()), |sn| compute(sn, fnext, knext)),
            );
            result = r;
        }
        self.bufs = bufs;
        result
    }
}
