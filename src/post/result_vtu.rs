//! The result fields of one state written as a VTU file, and a load history as a `.pvd`
//! time series of them (the load factor as time). Point data: displacement, stress (XX,
//! YY, ZZ, XY), von Mises, reactions, and on the slave nodes of each contact pair the
//! pressure and shear from the multipliers (in stress units), the gap, the status (0 open,
//! 1 stick, 2 slip) and the multipliers as the formulation stores them (normal: −p for
//! point-to-segment, a force for node-to-segment, p for mortar; tangential: Λ with
//! |Λ| ≤ 1 for point-to-segment, the traction for mortar). Cell data: groups and the
//! material of each 2D cell.

use super::contact_state::{gaps, statuses};
use super::vtu::{self, Field};
use crate::contact::surface::Surface;
use crate::error::Result;
use crate::fem::material::von_mises;
use crate::mesh::Mesh;
use std::path::{Path, PathBuf};

/// The fields of one state.
pub struct State<'a> {
    pub u: &'a [f64],
    pub reactions: &'a [f64],
    pub stress: &'a [[f64; 4]],
    /// Per contact pair: (slave node, pressure) and (μ, (slave node, shear)).
    pub pressure: &'a [Vec<(usize, f64)>],
    pub shear: &'a [(f64, Vec<(usize, f64)>)],
    /// Per contact pair: (slave node, [normal, tangential] multiplier) as stored.
    pub multipliers: &'a [crate::case::Multipliers],
}

/// What stays the same from state to state.
pub struct Setting<'a> {
    pub mesh: &'a Mesh,
    pub surfaces: &'a [(Surface, Surface)],
    /// Group of each material (None: every 2D cell), in the case file's order (cell data
    /// `material` = index + 1).
    pub material_groups: &'a [Option<String>],
}

fn xyz(v: &[f64]) -> Vec<f64> {
    v.chunks(2).flat_map(|d| [d[0], d[1], 0.0]).collect()
}

pub fn write_state(path: &Path, s: &Setting, st: &State) -> Result<()> {
    let mesh = s.mesh;
    let cells: Vec<usize> = mesh.cells_of_dim(2).collect();
    let disp = xyz(st.u);
    // Symmetric tensor as ParaView expects: XX, YY, ZZ, XY, YZ, XZ.
    let sig: Vec<f64> = st
        .stress
        .iter()
        .flat_map(|s| [s[0], s[1], s[2], s[3], 0.0, 0.0])
        .collect();
    let vm: Vec<f64> = st.stress.iter().map(von_mises).collect();
    let react = xyz(st.reactions);
    let n = mesh.num_nodes();
    let (mut cp, mut shear, mut gap, mut status) =
        (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut lam_n, mut lam_t) = (vec![0.0; n], vec![0.0; n]);
    for (i, pressures) in st.pressure.iter().enumerate() {
        let (mu, sh) = st.shear.get(i).map_or((0.0, &[][..]), |s| (s.0, &s.1[..]));
        for &(node, p) in pressures {
            cp[node] = p;
        }
        for &(node, t) in sh {
            shear[node] = t;
        }
        for (node, code) in statuses(pressures, sh, mu) {
            status[node] = code as f64;
        }
        for &(node, m) in st.multipliers.get(i).map_or(&[][..], |m| &m[..]) {
            lam_n[node] = m[0];
            lam_t[node] = m[1];
        }
        if let Some((slave, master)) = s.surfaces.get(i) {
            for (node, g) in gaps(mesh, st.u, slave, master) {
                gap[node] = g;
            }
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
    ];
    if !st.pressure.is_empty() {
        for (name, values) in [
            ("contact_pressure", &cp),
            ("contact_shear", &shear),
            ("contact_gap", &gap),
            ("contact_status", &status),
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
    }
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
