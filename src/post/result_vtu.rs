//! The result fields of one state written as a VTU file, and a load history as a `.pvd`
//! time series of them (the load factor as time). README.md ("result.vtu") lists every
//! field. Cells: the 2D cells, then the boundary edges (Seg2/Seg3 line cells) with their
//! groups as `group_NAME` flags and `cell_dim` telling them apart. Contact fields exist on
//! the slave nodes only: NaN elsewhere; open slave nodes carry exactly 0.

use super::contact_state::Multipliers;
use super::contact_summary::PairResult;
use super::vtu::{self, Field};
use crate::error::Result;
use crate::fem::material::von_mises;
use crate::mesh::Mesh;
use std::path::{Path, PathBuf};

/// The fields of one state.
pub struct State<'a> {
    pub u: &'a [f64],
    pub reactions: &'a [f64],
    /// Cauchy stress [xx, yy, zz, xy] at the nodes.
    pub stress: &'a [[f64; 4]],
    /// Second Piola–Kirchhoff stress at the nodes (large kinematics).
    pub pk2: Option<&'a [[f64; 4]]>,
    /// Per contact pair: the slave nodes' contact values.
    pub contact: &'a [PairResult],
    /// Per contact pair: (slave node, [normal, tangential] multiplier) as stored.
    pub multipliers: &'a [Multipliers],
}

/// What stays the same from state to state.
pub struct Setting<'a> {
    pub mesh: &'a Mesh,
    /// Group of each material (None: every 2D cell), in the case file's order (cell data
    /// `material` = index + 1).
    pub material_groups: &'a [Option<String>],
}

fn xyz(v: &[f64]) -> Vec<f64> {
    v.chunks(2).flat_map(|d| [d[0], d[1], 0.0]).collect()
}

/// Symmetric tensors as ParaView expects them: XX, YY, ZZ, XY, YZ, XZ.
fn tensor(s: &[[f64; 4]]) -> Vec<f64> {
    s.iter()
        .flat_map(|s| [s[0], s[1], s[2], s[3], 0.0, 0.0])
        .collect()
}

pub fn write_state(path: &Path, s: &Setting, st: &State) -> Result<()> {
    let mesh = s.mesh;
    let cells: Vec<usize> = mesh.cells_of_dim(2).chain(mesh.cells_of_dim(1)).collect();
    let disp = xyz(st.u);
    let sig = tensor(st.stress);
    let pk2 = st.pk2.map(tensor);
    let vm: Vec<f64> = st.stress.iter().map(von_mises).collect();
    let react = xyz(st.reactions);
    let n = mesh.num_nodes();
    let nan = f64::NAN;
    let (mut cp, mut shear, mut gap, mut status, mut pair) = (
        vec![nan; n],
        vec![nan; n],
        vec![nan; n],
        vec![nan; n],
        vec![nan; n],
    );
    let mut force = vec![nan; 3 * n];
    let (mut lam_n, mut lam_t) = (vec![nan; n], vec![nan; n]);
    for (i, result) in st.contact.iter().enumerate() {
        for c in &result.nodes {
            let k = c.node;
            cp[k] = c.pressure;
            shear[k] = c.shear;
            gap[k] = c.gap;
            status[k] = c.status as f64;
            pair[k] = (i + 1) as f64;
            force[3 * k..3 * k + 3].copy_from_slice(&[c.force[0], c.force[1], 0.0]);
        }
        for &(node, m) in st.multipliers.get(i).map_or(&[][..], |m| &m[..]) {
            lam_n[node] = m[0];
            lam_t[node] = m[1];
        }
    }
    let mut material = vec![0i32; mesh.num_cells()];
    for (k, g) in s.material_groups.iter().enumerate() {
        let cells: Vec<usize> = match g {
            Some(g) => mesh.cell_groups.get(g).cloned().unwrap_or_default(),
            None => mesh.cells_of_dim(2).collect(),
        };
        for c in cells {
            material[c] = k as i32 + 1;
        }
    }
    let material: Vec<i32> = cells.iter().map(|&c| material[c]).collect();
    let dims: Vec<i32> = cells.iter().map(|&c| mesh.kind(c).dim() as i32).collect();
    let group_fields = vtu::cell_group_flags(mesh, &cells);
    let mut fields = vec![
        Field::Point {
            name: "displacement",
            ncomp: 3,
            values: &disp,
            components: &["DX", "DY", "DZ"],
        },
        Field::Point {
            name: "stress",
            ncomp: 6,
            values: &sig,
            components: &["SIXX", "SIYY", "SIZZ", "SIXY", "SIYZ", "SIXZ"],
        },
    ];
    if let Some(pk2) = &pk2 {
        fields.push(Field::Point {
            name: "stress_pk2",
            ncomp: 6,
            values: pk2,
            components: &["SXX", "SYY", "SZZ", "SXY", "SYZ", "SXZ"],
        });
    }
    fields.extend([
        Field::Point {
            name: "von_mises",
            ncomp: 1,
            values: &vm,
            components: &[],
        },
        Field::Point {
            name: "reaction",
            ncomp: 3,
            values: &react,
            components: &["RX", "RY", "RZ"],
        },
    ]);
    if !st.contact.is_empty() {
        for (name, values) in [
            ("contact_pressure", &cp),
            ("contact_shear", &shear),
            ("contact_gap", &gap),
            ("contact_status", &status),
            ("contact_pair", &pair),
            ("contact_multiplier_normal", &lam_n),
            ("contact_multiplier_tangential", &lam_t),
        ] {
            fields.push(Field::Point {
                name,
                ncomp: 1,
                values,
                components: &[],
            });
        }
        fields.push(Field::Point {
            name: "contact_force",
            ncomp: 3,
            values: &force,
            components: &["FX", "FY", "FZ"],
        });
    }
    fields.push(Field::CellInt {
        name: "cell_dim",
        values: &dims,
    });
    fields.push(Field::CellInt {
        name: "material",
        values: &material,
    });
    for (name, vals) in &group_fields {
        fields.push(Field::CellInt { name, values: vals });
    }
    vtu::write(path, mesh, &cells, &fields)
}

/// Writes `dir/stem_NNNN.vtu` for each (load factor, state) and `dir/stem.pvd` listing
/// them; returns the files written.
pub fn write_series(
    dir: &Path,
    stem: &str,
    s: &Setting,
    states: &[(f64, State)],
) -> Result<Vec<PathBuf>> {
    use rayon::prelude::*;
    let names: Vec<String> = (1..=states.len())
        .map(|k| format!("{stem}_{k:04}.vtu"))
        .collect();
    // one file per state, independent: written in parallel (100-step histories)
    states
        .par_iter()
        .zip(&names)
        .try_for_each(|((_, st), name)| write_state(&dir.join(name), s, st))?;
    let entries: Vec<(f64, String)> = states
        .iter()
        .zip(&names)
        .map(|((t, _), n)| (*t, n.clone()))
        .collect();
    let mut files: Vec<PathBuf> = names.iter().map(|n| dir.join(n)).collect();
    let pvd = dir.join(format!("{stem}.pvd"));
    vtu::write_pvd(&pvd, &entries)?;
    files.push(pvd);
    Ok(files)
}
