//! MED mesh reader (MED 3.x/4.x as written by Salome and code_aster; MED 2.x layout too),
//! on the pure-Rust `hdf5-pure` crate so that the default build needs no system library.
//!
//! Layout read (all names are HDF5 groups/datasets):
//! - `ENS_MAA/<mesh>/<step>/NOE/COO`: coordinates, no-interlace (all x, then all y);
//!   `NOE/FAM`: node family numbers. (MED 2.x: `NOE` directly under `<mesh>`.)
//! - `ENS_MAA/<mesh>/<step>/MAI/<type>/NOD`: nodal connectivity, no-interlace, 1-based;
//!   `MAI/<type>/FAM`: cell family numbers.
//! - `FAS/<mesh>/{NOEUD,ELEME}/<family>/@NUM` and `GRO/NOM` (80-character group names):
//!   a family is a set of groups; family 0 carries none.
//!
//! MED stores 2D cells clockwise: they are given our (counter-clockwise) order here, so
//! that `Mesh::reoriented` only counts cells that break the format's own convention.
//! A space dimension of 3 is accepted when every z is zero (Salome writes planar meshes so).
//!
//! Files of HDF5 before 1.6.3 (older MED 2.x) store data-layout messages of versions 1
//! and 2, which `hdf5-pure` 0.47 refuses (`invalid data layout version: 2`). The fix is
//! made in the crate, vendored with a patch to `DataLayout::parse` (vendor/hdf5-pure,
//! PATCH.md, ready to send upstream: 80 lines of parser and comments, 108 of unit tests),
//! rather than wrapped here: `hdf5-pure` keeps a dataset's object header private, so a
//! wrapper would need its own reader of the old format (superblock 0, symbol-table groups
//! with their B-trees and heaps, version 1 object headers and continuations, chunk
//! B-trees and deflate) only to reach a message the crate already locates, some 400
//! lines duplicating tested code. The vendored copy is the published 0.47.0 otherwise
//! (126 892 lines, 6.3 MB, compiled either way: no build-time change);
//! tests/med_layouts.rs reads one mesh in layout versions 1 to 4, contiguous, chunked and
//! compact.

use super::{CellKind, Mesh, MeshBuilder};
use crate::error::{Error, Result};
use hdf5_pure::{AttrValue, File, Group};
use std::collections::BTreeMap;
use std::path::Path;

/// MED geometry type names (the `MAI` subgroups) we read, with their cell kinds.
const SUPPORTED: [(&str, CellKind); 7] = [
    ("PO1", CellKind::Point1),
    ("SE2", CellKind::Seg2),
    ("SE3", CellKind::Seg3),
    ("TR3", CellKind::Tri3),
    ("TR6", CellKind::Tri6),
    ("QU4", CellKind::Quad4),
    ("QU8", CellKind::Quad8),
];

/// A few MED types that users meet, for a clearer error than the bare code.
fn describe_unsupported(name: &str) -> &'static str {
    match name {
        "SE4" => "cubic segment",
        "TR7" => "7-node triangle",
        "QU9" => "9-node quadrangle",
        "TE4" | "T10" => "tetrahedron",
        "HE8" | "H20" | "H27" => "hexahedron",
        "PE6" | "P15" | "P18" => "pentahedron",
        "PY5" | "P13" => "pyramid",
        "POG" | "POQ" => "polygon",
        "POE" => "polyhedron",
        _ => "unknown type",
    }
}

pub fn read(path: &Path) -> Result<Mesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse(bytes, &path.display().to_string())
}

/// Parses the bytes of a MED file; `source` names it in errors.
pub fn parse(bytes: Vec<u8>, source: &str) -> Result<Mesh> {
    let err = |msg: String| Error::parse(source, msg);
    if !hdf5_pure::is_hdf5_bytes(&bytes) {
        return Err(err("not an HDF5 file (no HDF5 signature)".into()));
    }
    if let Some(eof) = end_of_file(&bytes).filter(|&e| e > bytes.len() as u64) {
        return Err(err(format!(
            "truncated HDF5 file: {} bytes, its superblock says {eof}",
            bytes.len()
        )));
    }
    let file = File::from_bytes(bytes).map_err(|e| err(format!("unreadable HDF5 file: {e}")))?;
    let reader = Reader { source, file };
    reader.mesh()
}

/// The end-of-file address of an HDF5 superblock at the start of the file (versions 0–3,
/// 8-byte addresses): a shorter file was cut, and would otherwise read as one without
/// its groups.
fn end_of_file(b: &[u8]) -> Option<u64> {
    if !b.starts_with(b"\x89HDF\r\n\x1a\n") {
        return None;
    }
    let (size_at, eof_at) = match *b.get(8)? {
        0 => (13, 40),
        1 => (13, 44),
        2 | 3 => (9, 28),
        _ => return None,
    };
    if *b.get(size_at)? != 8 {
        return None;
    }
    Some(u64::from_le_bytes(
        b.get(eof_at..eof_at + 8)?.try_into().ok()?,
    ))
}

struct Reader<'a> {
    source: &'a str,
    file: File,
}

impl Reader<'_> {
    fn err(&self, msg: impl Into<String>) -> Error {
        Error::parse(self.source, msg.into())
    }

    /// An HDF5 error while reading `what`.
    fn h5(&self, what: &str) -> impl Fn(hdf5_pure::Error) -> Error + '_ {
        let what = what.to_string();
        move |e| self.err(format!("{what}: {e}"))
    }

    fn mesh(&self) -> Result<Mesh> {
        let ens = self
            .file
            .group("ENS_MAA")
            .map_err(|_| self.err("no mesh in the file (no ENS_MAA group): not a MED mesh file"))?;
        let names = ens.groups().map_err(self.h5("ENS_MAA"))?;
        let mesh_name = match names.as_slice() {
            [one] => one.clone(),
            [] => return Err(self.err("the MED file holds no mesh (ENS_MAA is empty)")),
            many => {
                return Err(self.err(format!(
                    "the MED file holds {} meshes ({}); tribo reads files with one mesh",
                    many.len(),
                    many.join(", ")
                )))
            }
        };
        let at = format!("ENS_MAA/{mesh_name}");
        let mesh_group = ens.group(&mesh_name).map_err(self.h5(&at))?;
        let attrs = mesh_group.attrs().map_err(self.h5(&at))?;
        if let Some(t) = int_attr(&attrs, "TYP") {
            if t != 0 {
                return Err(self.err(format!(
                    "{at}: structured meshes (TYP = {t}) are not supported, only unstructured ones"
                )));
            }
        }
        let space_dim = int_attr(&attrs, "ESP")
            .or_else(|| int_attr(&attrs, "DIM"))
            .ok_or_else(|| self.err(format!("{at}: no space dimension (attribute ESP)")))?;
        if !(2..=3).contains(&space_dim) {
            return Err(self.err(format!(
                "{at}: space dimension {space_dim}; tribo reads 2D meshes (2, or 3 with z = 0)"
            )));
        }
        // MED 3/4: one subgroup per computation step; MED 2: NOE/MAI directly here.
        let subgroups = mesh_group.groups().map_err(self.h5(&at))?;
        let (step, step_at) = if subgroups.iter().any(|g| g == "NOE") {
            (mesh_group, at.clone())
        } else {
            let first = subgroups
                .iter()
                .min()
                .ok_or_else(|| self.err(format!("{at}: no computation step (no subgroup)")))?;
            let step_at = format!("{at}/{first}");
            (mesh_group.group(first).map_err(self.h5(&step_at))?, step_at)
        };

        let mut b = MeshBuilder::new(self.source);
        let node_fams = self.nodes(&step, &step_at, space_dim as usize, &mut b)?;
        let cells = self.cells(&step, &step_at, &mut b)?;
        let families = self.families(&mesh_name)?;
        for (i, &f) in node_fams.iter().enumerate() {
            for g in self.family_groups(&families, f, "node", "NOEUD", &mesh_name)? {
                b.add_to_node_group(g, i);
            }
        }
        for &(c, f) in &cells {
            for g in self.family_groups(&families, f, "cell", "ELEME", &mesh_name)? {
                b.add_to_cell_group(g, c);
            }
        }
        b.finish()
    }

    fn nodes(
        &self,
        step: &Group,
        at: &str,
        space_dim: usize,
        b: &mut MeshBuilder,
    ) -> Result<Vec<i64>> {
        let at = format!("{at}/NOE");
        let noe = step.group("NOE").map_err(self.h5(&at))?;
        let coo_at = format!("{at}/COO");
        let coo = noe
            .dataset("COO")
            .map_err(|_| self.err(format!("{coo_at}: missing (no node coordinates)")))?;
        let count = dataset_count(&coo).ok_or_else(|| self.err(format!("{coo_at}: no NBR")))?;
        let xyz = coo.read_f64().map_err(self.h5(&coo_at))?;
        if Some(xyz.len()) != count.checked_mul(space_dim) {
            return Err(self.err(format!(
                "{coo_at}: {} values for {count} nodes in {space_dim}D (expected {})",
                xyz.len(),
                count.saturating_mul(space_dim)
            )));
        }
        let diag = bbox_diagonal(&xyz, count);
        for i in 0..count {
            if space_dim == 3 {
                let z = xyz[2 * count + i];
                if z.abs() > 1e-12 * diag.max(f64::MIN_POSITIVE) {
                    return Err(self.err(format!(
                        "node {} has z = {z}: 3D meshes are not supported \
                         (all nodes must lie in the plane z = 0)",
                        i + 1
                    )));
                }
            }
            b.add_node([xyz[i], xyz[count + i]]);
        }
        self.families_of(&noe, &format!("{at}/FAM"), count)
    }

    /// Family numbers of the entities of `group` (`FAM` dataset; all 0 when absent).
    fn families_of(&self, group: &Group, at: &str, count: usize) -> Result<Vec<i64>> {
        match group.dataset("FAM") {
            Err(_) => Ok(vec![0; count]),
            Ok(ds) => {
                let f = ds.read_i64().map_err(self.h5(at))?;
                if f.len() != count {
                    return Err(self.err(format!(
                        "{at}: {} family numbers for {count} entities",
                        f.len()
                    )));
                }
                Ok(f)
            }
        }
    }

    /// Adds the cells of every `MAI` subgroup; returns (cell index, family number).
    fn cells(&self, step: &Group, at: &str, b: &mut MeshBuilder) -> Result<Vec<(usize, i64)>> {
        let at = format!("{at}/MAI");
        let mai = step
            .group("MAI")
            .map_err(|_| self.err(format!("{at}: missing (no cells)")))?;
        let mut out = vec![];
        let mut types = mai.groups().map_err(self.h5(&at))?;
        types.sort();
        let n_nodes = b.num_nodes();
        for name in types {
            let tat = format!("{at}/{name}");
            let Some(&(_, kind)) = SUPPORTED.iter().find(|(n, _)| *n == name) else {
                return Err(self.err(format!(
                    "{tat}: cells of MED type {name} ({}) are not supported; supported: {}",
                    describe_unsupported(&name),
                    SUPPORTED.map(|s| s.0).join(", ")
                )));
            };
            let g = mai.group(&name).map_err(self.h5(&tat))?;
            let nod_at = format!("{tat}/NOD");
            let nod = g.dataset("NOD").map_err(|_| {
                self.err(format!(
                    "{nod_at}: missing (only nodal connectivity is supported)"
                ))
            })?;
            let count = dataset_count(&nod).ok_or_else(|| self.err(format!("{nod_at}: no NBR")))?;
            let conn = nod.read_i64().map_err(self.h5(&nod_at))?;
            let nn = kind.num_nodes();
            if Some(conn.len()) != count.checked_mul(nn) {
                return Err(self.err(format!(
                    "{nod_at}: {} node numbers for {count} cells of {nn} nodes",
                    conn.len()
                )));
            }
            let fams = self.families_of(&g, &format!("{tat}/FAM"), count)?;
            let perm = kind.reverse_permutation();
            let mut nodes = vec![0usize; nn];
            for c in 0..count {
                for (a, slot) in nodes.iter_mut().enumerate() {
                    // 2D cells: MED's clockwise order → ours; 0D/1D cells keep theirs.
                    let from = if kind.dim() == 2 { perm[a] } else { a };
                    let n = conn[from * count + c];
                    if n < 1 || n as usize > n_nodes {
                        return Err(self.err(format!(
                            "{nod_at}: cell {} refers to node {n}, the mesh has {n_nodes} nodes",
                            c + 1
                        )));
                    }
                    *slot = n as usize - 1;
                }
                let cell = b.add_cell(kind, &nodes, (c + 1) as u64);
                out.push((cell, fams[c]));
            }
        }
        Ok(out)
    }

    /// Family number → group names, from `FAS/<mesh>`.
    fn families(&self, mesh_name: &str) -> Result<BTreeMap<i64, Vec<String>>> {
        let mut out = BTreeMap::new();
        let at = format!("FAS/{mesh_name}");
        let Ok(fas) = self.file.group(&at) else {
            return Ok(out); // no families: no groups
        };
        for kind in ["NOEUD", "ELEME"] {
            let Ok(g) = fas.group(kind) else { continue };
            let kat = format!("{at}/{kind}");
            for fam in g.groups().map_err(self.h5(&kat))? {
                let fat = format!("{kat}/{fam}");
                let fg = g.group(&fam).map_err(self.h5(&fat))?;
                let attrs = fg.attrs().map_err(self.h5(&fat))?;
                let num = int_attr(&attrs, "NUM")
                    .ok_or_else(|| self.err(format!("{fat}: no family number (attribute NUM)")))?;
                let mut names = vec![];
                if let Ok(gro) = fg.group("GRO") {
                    let nat = format!("{fat}/GRO/NOM");
                    let nom = gro.dataset("NOM").map_err(self.h5(&nat))?;
                    let raw = nom.read_raw().map_err(self.h5(&nat))?;
                    if raw.len() % 80 != 0 {
                        return Err(self.err(format!(
                            "{nat}: {} bytes, not a list of 80-character names",
                            raw.len()
                        )));
                    }
                    for chunk in raw.chunks(80) {
                        let name = String::from_utf8_lossy(chunk)
                            .trim_end_matches(['\0', ' '])
                            .to_string();
                        if !name.is_empty() {
                            names.push(name);
                        }
                    }
                }
                if out.insert(num, names).is_some() {
                    return Err(self.err(format!("{fat}: family number {num} defined twice")));
                }
            }
        }
        Ok(out)
    }

    fn family_groups<'f>(
        &self,
        families: &'f BTreeMap<i64, Vec<String>>,
        f: i64,
        entity: &str,
        table: &str,
        mesh_name: &str,
    ) -> Result<&'f [String]> {
        if f == 0 {
            return Ok(&[]);
        }
        families.get(&f).map(|v| v.as_slice()).ok_or_else(|| {
            self.err(format!(
                "{entity} family {f} is used but not defined in FAS/{mesh_name}/{table}"
            ))
        })
    }
}

fn int_attr(attrs: &std::collections::HashMap<String, AttrValue>, key: &str) -> Option<i64> {
    match attrs.get(key)? {
        AttrValue::I64(v) => Some(*v),
        AttrValue::I32(v) => Some(*v as i64),
        AttrValue::I16(v) => Some(*v as i64),
        AttrValue::I8(v) => Some(*v as i64),
        AttrValue::U32(v) => Some(*v as i64),
        AttrValue::U16(v) => Some(*v as i64),
        AttrValue::U8(v) => Some(*v as i64),
        _ => None,
    }
}

/// The `NBR` attribute of a dataset (its entity count).
fn dataset_count(ds: &hdf5_pure::Dataset) -> Option<usize> {
    let n = int_attr(&ds.attrs().ok()?, "NBR")?;
    usize::try_from(n).ok()
}

fn bbox_diagonal(xyz: &[f64], count: usize) -> f64 {
    let mut d2 = 0.0;
    for k in 0..xyz.len() / count.max(1) {
        let v = &xyz[k * count..(k + 1) * count];
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if hi >= lo {
            d2 += (hi - lo).powi(2);
        }
    }
    d2.sqrt()
}
