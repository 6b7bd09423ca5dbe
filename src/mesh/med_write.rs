//! MED 3.x mesh writer (the layout `med.rs` reads, as the MED library writes it): one
//! mesh, one computation step, no-interlace coordinates and connectivity, cells in
//! MED's clockwise order, groups as families (cells: negative numbers, nodes: positive).

use super::families::{cell_families, node_families, Families};
use super::{CellKind, Mesh};
use crate::error::{Error, Result};
use hdf5_pure::{
    AttrValue, Datatype, DatatypeByteOrder, FileBuilder, FixedPointLayout, GroupBuilder,
};
use std::path::Path;

const STEP: &str = "-0000000000000000001-0000000000000000001";

fn med_name(kind: CellKind) -> (&'static str, i64) {
    match kind {
        CellKind::Point1 => ("PO1", 1),
        CellKind::Seg2 => ("SE2", 102),
        CellKind::Seg3 => ("SE3", 103),
        CellKind::Tri3 => ("TR3", 203),
        CellKind::Tri6 => ("TR6", 206),
        CellKind::Quad4 => ("QU4", 204),
        CellKind::Quad8 => ("QU8", 208),
    }
}

fn text(s: &str) -> AttrValue {
    // MED writes its fixed strings NUL-terminated, sized to the content.
    AttrValue::ascii_string_sized(s, s.len() as u32 + 1).unwrap_or(AttrValue::String(s.into()))
}

fn counted<'g>(
    g: &'g mut GroupBuilder,
    name: &str,
    count: usize,
) -> &'g mut hdf5_pure::DatasetBuilder {
    let ds = g.create_dataset(name);
    ds.set_attr("NBR", AttrValue::I64(count as i64));
    ds.set_attr("CGT", AttrValue::I64(1));
    ds
}

/// The bytes MED gives a group name (`GRO/NOM` rows).
pub const GROUP_NAME_BYTES: usize = 80;

/// Writes `mesh` as a MED file named `mesh_name` inside (atomically). A group name longer
/// than MED holds is refused: cut, it could merge with another group.
pub fn write(path: &Path, mesh: &Mesh, mesh_name: &str) -> Result<()> {
    for name in mesh.group_names() {
        if name.len() > GROUP_NAME_BYTES {
            return Err(Error::model(format!(
                "{}: group '{name}' is {} bytes long; MED holds group names of at most \
                 {GROUP_NAME_BYTES} bytes (cut, it could merge with another group): rename it",
                path.display(),
                name.len()
            )));
        }
    }
    let bytes = to_bytes(mesh, mesh_name)
        .map_err(|e| Error::model(format!("{}: cannot encode MED: {e}", path.display())))?;
    crate::error::write_atomic(path, &bytes)
}

pub fn to_bytes(mesh: &Mesh, mesh_name: &str) -> std::result::Result<Vec<u8>, hdf5_pure::Error> {
    let mut fb = FileBuilder::new();
    let mut info = fb.create_group("INFOS_GENERALES");
    info.set_attr("MAJ", AttrValue::I32(3));
    info.set_attr("MIN", AttrValue::I32(3));
    info.set_attr("REL", AttrValue::I32(0));
    fb.add_group(info.finish());

    let cells = cell_families(mesh);
    let nodes = node_families(mesh);

    let mut ens = fb.create_group("ENS_MAA");
    let mut m = ens.create_group(mesh_name);
    for (k, v) in [
        ("DIM", 2),
        ("ESP", 2),
        ("REP", 0),
        ("TYP", 0),
        ("SRT", 1),
        ("NXT", -1),
        ("NXI", -1),
    ] {
        m.set_attr(k, AttrValue::I64(v));
    }
    m.set_attr("NOM", text(&format!("{:<16}{:<16}", "X", "Y")));
    m.set_attr("UNI", text(&format!("{:<16}{:<16}", "", "")));
    m.set_attr("DES", text("written by tribo"));
    m.set_attr("UNT", text(""));
    let mut step = m.create_group(STEP);
    for (k, v) in [
        ("CGT", 1),
        ("NDT", -1),
        ("NOR", -1),
        ("NXI", -1),
        ("NXT", -1),
        ("PVI", -1),
        ("PVT", -1),
    ] {
        step.set_attr(k, AttrValue::I64(v));
    }
    step.set_attr("PDT", AttrValue::F64(-1.0));

    let n = mesh.num_nodes();
    let mut noe = step.create_group("NOE");
    noe.set_attr("CGS", AttrValue::I64(1));
    noe.set_attr("CGT", AttrValue::I64(1));
    noe.set_attr("PFL", text("MED_NO_PROFILE_INTERNAL"));
    let coo: Vec<f64> = (0..2)
        .flat_map(|d| mesh.coords.iter().map(move |x| x[d]))
        .collect();
    counted(&mut noe, "COO", n).with_f64_data(&coo);
    let node_fam: Vec<i64> = nodes.of.iter().map(|&f| f as i64).collect();
    counted(&mut noe, "FAM", n).with_i64_data(&node_fam);
    step.add_group(noe.finish());

    let mut mai = step.create_group("MAI");
    mai.set_attr("CGT", AttrValue::I64(1));
    let mut kinds: Vec<CellKind> = mesh.kind_counts().into_keys().collect();
    kinds.sort_by_key(|&k| med_name(k).0);
    for kind in kinds {
        let (name, geo) = med_name(kind);
        let of_kind: Vec<usize> = (0..mesh.num_cells())
            .filter(|&c| mesh.kind(c) == kind)
            .collect();
        let count = of_kind.len();
        let nn = kind.num_nodes();
        let perm = kind.reverse_permutation();
        let mut conn = vec![0i64; count * nn];
        for (i, &c) in of_kind.iter().enumerate() {
            let nodes = mesh.cell_nodes(c);
            for a in 0..nn {
                // ours (counter-clockwise) → MED's clockwise order; the permutation is
                // its own inverse.
                let from = if kind.dim() == 2 { perm[a] } else { a };
                conn[a * count + i] = nodes[from] as i64 + 1;
            }
        }
        let fam: Vec<i64> = of_kind.iter().map(|&c| -(cells.of[c] as i64)).collect();
        let mut g = mai.create_group(name);
        g.set_attr("CGS", AttrValue::I64(1));
        g.set_attr("CGT", AttrValue::I64(1));
        g.set_attr("GEO", AttrValue::I64(geo));
        g.set_attr("PFL", text("MED_NO_PROFILE_INTERNAL"));
        counted(&mut g, "NOD", count).with_i64_data(&conn);
        counted(&mut g, "FAM", count).with_i64_data(&fam);
        mai.add_group(g.finish());
    }
    step.add_group(mai.finish());
    m.add_group(step.finish());
    ens.add_group(m.finish());
    fb.add_group(ens.finish());

    let mut fas = fb.create_group("FAS");
    let mut fm = fas.create_group(mesh_name);
    let mut zero = fm.create_group("FAMILLE_ZERO");
    zero.set_attr("NUM", AttrValue::I64(0));
    fm.add_group(zero.finish());
    for (table, fams, sign) in [("ELEME", &cells, -1i64), ("NOEUD", &nodes, 1)] {
        if fams.sets.len() > 1 {
            let t = family_table(&mut fm, table, fams, sign);
            fm.add_group(t);
        }
    }
    fas.add_group(fm.finish());
    fb.add_group(fas.finish());
    fb.finish()
}

fn family_table(
    parent: &mut GroupBuilder,
    table: &str,
    fams: &Families,
    sign: i64,
) -> hdf5_pure::FinishedGroup {
    let mut t = parent.create_group(table);
    for (i, set) in fams.sets.iter().enumerate().skip(1) {
        let num = sign * i as i64;
        // Family names are at most 64 characters in MED; the number keeps them apart.
        let mut name = format!("FAM_{num}_{}", set.join("_"));
        let mut end = name.len().min(64);
        while !name.is_char_boundary(end) {
            end -= 1;
        }
        name.truncate(end);
        let mut f = t.create_group(&name);
        f.set_attr("NUM", AttrValue::I64(num));
        let mut gro = f.create_group("GRO");
        gro.set_attr("NBR", AttrValue::I64(set.len() as i64));
        let mut raw = vec![0u8; 80 * set.len()];
        for (k, g) in set.iter().enumerate() {
            let b = g.as_bytes();
            let len = b.len().min(80);
            raw[80 * k..80 * k + len].copy_from_slice(&b[..len]);
        }
        let i8_type = Datatype::FixedPoint {
            size: 1,
            byte_order: DatatypeByteOrder::LittleEndian,
            layout: FixedPointLayout {
                signed: true,
                bit_offset: 0,
                bit_precision: 8,
            },
        };
        gro.create_dataset("NOM")
            .with_array_data(i8_type, &[80], raw, set.len() as u64);
        f.add_group(gro.finish());
        t.add_group(f.finish());
    }
    t.finish()
}
