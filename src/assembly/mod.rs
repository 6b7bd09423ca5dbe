//! Global assembly: element kernels in, reduced residual and sparse tangent out.
//!
//! | file | what |
//! |---|---|
//! | `coupled.rs` | solid matrix + contact triplets over extra unknowns, pattern rebuilt on change |
//! | `dofs.rs` | `DofMap`: free, imposed and linked dofs (elimination) |
//! | `matrix.rs` | CSC matrix with a fixed pattern, faer view |
//! | `loads.rs` | nodal forces, edge pressures and tractions |
//!
//! The pattern and, per cell, the position of every local entry in the global value array
//! are computed once (`Assembler::new`); each assembly only refills values. Element
//! matrices are computed in parallel blocks and scattered serially (no locking).

pub mod coupled;
pub mod dofs;
pub mod loads;
pub mod matrix;

use crate::error::{Error, Result};
use crate::fem::solid::{residual_tangent, SolidModel, MAX_DOFS};
use crate::mesh::Mesh;
use dofs::{DofMap, Role};
use matrix::SparseMatrix;
use rayon::prelude::*;

const NONE: u32 = u32::MAX;
/// Marks a local entry that involves a linked dof: handled on the slow path.
const LINKED: u32 = u32::MAX - 1;
const BLOCK: usize = 2048;

pub struct Assembler {
    pub dofs: DofMap,
    pub matrix: SparseMatrix,
    /// The 2D cells that carry stiffness, and the solid model of each.
    pub cells: Vec<usize>,
    pub cell_model: Vec<SolidModel>,
    scatter_start: Vec<usize>,
    scatter: Vec<u32>,
    /// Only the lower triangle is stored (enough for Cholesky; halves the memory).
    pub lower_only: bool,
    /// Element vectors and matrices of one block of cells, kept between assemblies (a
    /// fresh 4 MB buffer per call costs more in page faults than the kernels).
    fbuf: Vec<f64>,
    kbuf: Vec<f64>,
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
        let nf = dofs.num_free;
        // Free unknowns touched by each cell.
        let mut tmp = vec![];
        let mut touched_start = vec![0usize];
        let mut touched = vec![];
        for &c in &cells {
            let mut set = vec![];
            for &n in mesh.cell_nodes(c) {
                for comp in 0..2 {
                    dofs.expand_dof(2 * n + comp, &mut tmp);
                    set.extend(tmp.iter().map(|t| t.0));
                }
            }
            set.sort_unstable();
            set.dedup();
            touched.extend_from_slice(&set);
            touched_start.push(touched.len());
        }
        // free unknown → cells touching it
        let mut count = vec![0usize; nf + 1];
        for &j in &touched {
            count[j + 1] += 1;
        }
        for j in 0..nf {
            count[j + 1] += count[j];
        }
        let mut fill = count.clone();
        let mut cells_of = vec![0usize; touched.len()];
        for i in 0..cells.len() {
            for &j in &touched[touched_start[i]..touched_start[i + 1]] {
                cells_of[fill[j]] = i;
                fill[j] += 1;
            }
        }
        let mut mark = vec![usize::MAX; nf];
        let columns = (0..nf).map(|j| {
            let mut col = vec![];
            for &i in &cells_of[count[j]..count[j + 1]] {
                for &k in &touched[touched_start[i]..touched_start[i + 1]] {
                    if mark[k] != j && (!lower_only || k >= j) {
                        mark[k] = j;
                        col.push(k);
                    }
                }
            }
            if col.is_empty() {
                col.push(j);
            }
            col.sort_unstable();
            col
        });
        let matrix = SparseMatrix::from_columns(nf, columns);
        if matrix.nnz() >= LINKED as usize {
            return Err(Error::solve(
                "matrix too large for 32-bit scatter positions",
            ));
        }
        let mut scatter_start = vec![0usize];
        let mut scatter = vec![];
        for &c in &cells {
            let nodes = mesh.cell_nodes(c);
            let nd = 2 * nodes.len();
            for a in 0..nd {
                let ra = dofs.roles[2 * nodes[a / 2] + a % 2];
                for b in 0..nd {
                    let rb = dofs.roles[2 * nodes[b / 2] + b % 2];
                    let pos = match (ra, rb) {
                        (Role::Free(i), Role::Free(j)) if lower_only && i < j => NONE,
                        (Role::Free(i), Role::Free(j)) => matrix.position(i, j).unwrap() as u32,
                        (Role::Fixed, _) | (_, Role::Fixed) => NONE,
                        _ => LINKED,
                    };
                    scatter.push(pos);
                }
            }
            scatter_start.push(scatter.len());
        }
        Ok(Assembler {
            dofs,
            matrix,
            cells,
            cell_model: models,
            scatter_start,
            scatter,
            lower_only,
            fbuf: vec![],
            kbuf: vec![],
        })
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
        }
        let block = BLOCK.min(self.cells.len()).max(1);
        let mut fbuf = std::mem::take(&mut self.fbuf);
        let mut kbuf = std::mem::take(&mut self.kbuf);
        fbuf.resize(block * MAX_DOFS, 0.0);
        if with_matrix {
            kbuf.resize(block * MAX_DOFS * MAX_DOFS, 0.0);
        }
        let mut tmp_a = vec![];
        let mut tmp_b = vec![];
        for start in (0..self.cells.len()).step_by(block) {
            let end = (start + block).min(self.cells.len());
            let cells = &self.cells[start..end];
            let models = &self.cell_model[start..end];
            let compute = |i: usize,
                           fe: &mut [f64],
                           ke: Option<&mut [f64]>|
             -> std::result::Result<(), usize> {
                let c = cells[i];
                let kind = mesh.kind(c);
                let (x, nn) = mesh.cell_coords(c);
                let mut ue = [[0.0; 2]; 8];
                for (a, &n) in mesh.cell_nodes(c).iter().enumerate() {
                    ue[a] = [u[2 * n], u[2 * n + 1]];
                }
                residual_tangent(kind, &x[..nn], &ue[..nn], &models[i], fe, ke).map_err(|_| c)
            };
            let res: std::result::Result<Vec<()>, usize> = if with_matrix {
                fbuf.par_chunks_mut(MAX_DOFS)
                    .zip(kbuf.par_chunks_mut(MAX_DOFS * MAX_DOFS))
                    .take(end - start)
                    .enumerate()
                    .map(|(i, (fe, ke))| compute(i, fe, Some(ke)))
                    .collect()
            } else {
                fbuf.par_chunks_mut(MAX_DOFS)
                    .take(end - start)
                    .enumerate()
                    .map(|(i, fe)| compute(i, fe, None))
                    .collect()
            };
            if let Err(c) = res {
                return Err(Error::solve(format!(
                    "cell {} ({}) has a non-positive Jacobian at a quadrature point",
                    c + 1,
                    mesh.kind(c)
                )));
            }
            for (i, &c) in cells.iter().enumerate() {
                let nodes = mesh.cell_nodes(c);
                let nd = 2 * nodes.len();
                let fe = &fbuf[i * MAX_DOFS..];
                for a in 0..nd {
                    fint[2 * nodes[a / 2] + a % 2] += fe[a];
                }
                if !with_matrix {
                    continue;
                }
                let ke = &kbuf[i * MAX_DOFS * MAX_DOFS..];
                let sc = &self.scatter[self.scatter_start[start + i]..];
                for a in 0..nd {
                    for b in 0..nd {
                        let p = sc[a * nd + b];
                        if p < LINKED {
                            self.matrix.values[p as usize] += ke[a * nd + b];
                        } else if p == LINKED {
                            let da = 2 * nodes[a / 2] + a % 2;
                            let db = 2 * nodes[b / 2] + b % 2;
                            self.dofs.expand_dof(da, &mut tmp_a);
                            self.dofs.expand_dof(db, &mut tmp_b);
                            for &(i2, ca) in &tmp_a {
                                for &(j2, cb) in &tmp_b {
                                    if self.lower_only && i2 < j2 {
                                        continue;
                                    }
                                    let pos =
                                        self.matrix.position(i2, j2).expect("pattern covers links");
                                    self.matrix.values[pos] += ca * cb * ke[a * nd + b];
                                }
                            }
                        }
                    }
                }
            }
        }
        self.fbuf = fbuf;
        self.kbuf = kbuf;
        Ok(())
    }
}
