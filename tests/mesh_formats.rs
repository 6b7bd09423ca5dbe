//! Mesh formats: round trips MSH 4.1 / MSH 2.2 / MED keep every node, cell and group; the
//! MED layout (no-interlace, clockwise cells, families); MED errors name the file and the
//! place; mutated MED files never panic.

use hdf5_pure::{AttrValue, File, FileBuilder};
use std::path::PathBuf;
use tribo::mesh::compare::compare;
use tribo::mesh::generate::{rectangle, ssnp154, Ssnp154Options};
use tribo::mesh::gmsh_write::{self, MshVersion};
use tribo::mesh::{med, med_write, CellKind, Mesh, MeshBuilder};

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tribo-mesh-formats-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Two squares (Quad8 + Tri6 pair) with overlapping cell groups, a node group of two
/// nodes and an ungrouped boundary segment.
fn overlapping_groups() -> Mesh {
    let base = rectangle([0.0, 0.0], 2.0, 1.0, 2, 1, CellKind::Quad8, 0.0).unwrap();
    let mut b = MeshBuilder::new("test");
    b.append(&base, |n| n.to_string());
    b.add_to_cell_group("Left", 0);
    b.add_to_cell_group("Both", 0);
    b.add_to_cell_group("Both", 1);
    b.add_to_node_group("Pins", 0);
    b.add_to_node_group("Pins", 2);
    b.add_to_node_group("Corner", 0);
    b.finish().unwrap()
}

fn meshes() -> Vec<(&'static str, Mesh)> {
    let lin = ssnp154(&Ssnp154Options {
        quadratic: false,
        size: 3.0,
        global_refine: 0,
    })
    .unwrap();
    let quad = ssnp154(&Ssnp154Options {
        quadratic: true,
        size: 3.0,
        global_refine: 0,
    })
    .unwrap();
    vec![
        ("ssnp154 linear", lin),
        ("ssnp154 quadratic", quad),
        ("overlapping groups", overlapping_groups()),
    ]
}

fn assert_same(name: &str, a: &Mesh, b: &Mesh) {
    let c = compare(a, b, 1e-12);
    assert!(c.differences.is_empty(), "{name}: {:?}", c.differences);
    assert!(c.same_numbering, "{name}: node numbering changed");
    assert!(
        c.max_node_distance <= 1e-12,
        "{name}: {}",
        c.max_node_distance
    );
    // Every group keeps its name and its node set (compare checks the sets).
    assert_eq!(a.group_names(), b.group_names(), "{name}");
    assert_eq!(
        b.reoriented, 0,
        "{name}: the writer broke the format's orientation"
    );
}

#[test]
fn round_trips_keep_nodes_cells_and_groups() {
    for (name, mesh) in meshes() {
        for v in [MshVersion::V41, MshVersion::V22] {
            let text = gmsh_write::to_string(&mesh, v);
            let back = tribo::mesh::gmsh::parse(text.as_bytes(), "rt.msh").unwrap();
            assert_same(&format!("{name} {v:?}"), &mesh, &back);
        }
        let bytes = med_write::to_bytes(&mesh, "m").unwrap();
        let back = med::parse(bytes, "rt.med").unwrap();
        assert_same(&format!("{name} MED"), &mesh, &back);
        // Node groups come back as node groups from MED (MED orders cells by type, so
        // cell indices change; `compare` checked the cell groups as cell sets).
        assert_eq!(mesh.node_groups, back.node_groups, "{name}");
        // MSH -> VTU -> mesh: every node, cell (all dimensions) and group.
        let pv = tmp("rt.vtu");
        tribo::post::vtu::write_mesh(&pv, &mesh).unwrap();
        let back = tribo::mesh::read(&pv).unwrap();
        assert_same(&format!("{name} VTU"), &mesh, &back);
        assert_eq!(mesh.cell_groups, back.cell_groups, "{name} VTU");
        assert_eq!(mesh.node_groups, back.node_groups, "{name} VTU");
        assert_eq!(mesh.num_cells(), back.num_cells(), "{name} VTU");
        // MSH -> MED -> MSH through files and `mesh::read` (extension dispatch).
        let (pm, pd) = (tmp("rt.msh"), tmp("rt.med"));
        gmsh_write::write(&pm, &mesh, MshVersion::V41).unwrap();
        let from_msh = tribo::mesh::read(&pm).unwrap();
        med_write::write(&pd, &from_msh, "m").unwrap();
        let from_med = tribo::mesh::read(&pd).unwrap();
        gmsh_write::write(&pm, &from_med, MshVersion::V22).unwrap();
        assert_same(
            &format!("{name} chain"),
            &mesh,
            &tribo::mesh::read(&pm).unwrap(),
        );
    }
}

#[test]
fn compare_finds_moved_nodes_missing_cells_and_changed_groups() {
    let mesh = overlapping_groups();
    let mut moved = mesh.clone();
    moved.coords[3][1] += 1e-9;
    let c = compare(&mesh, &moved, 1e-12);
    assert!(c.differences[0].starts_with("1 nodes of the first mesh have no node"));
    let mut regrouped = mesh.clone();
    regrouped.cell_groups.get_mut("Left").unwrap().push(1);
    let c = compare(&mesh, &regrouped, 1e-12);
    assert!(
        c.differences.iter().any(|d| d.starts_with("group 'Left'")),
        "{:?}",
        c.differences
    );
    // Same nodes in another order are matched by coordinates.
    let mut b = MeshBuilder::new("reversed");
    let n = mesh.num_nodes();
    for i in (0..n).rev() {
        b.add_node(mesh.coords[i]);
    }
    for c in 0..mesh.num_cells() {
        let nodes: Vec<usize> = mesh.cell_nodes(c).iter().map(|&k| n - 1 - k).collect();
        b.add_cell(mesh.kind(c), &nodes, c as u64 + 1);
    }
    for (g, cells) in &mesh.cell_groups {
        for &c in cells {
            b.add_to_cell_group(g, c);
        }
    }
    for (g, nodes) in &mesh.node_groups {
        for &k in nodes {
            b.add_to_node_group(g, n - 1 - k);
        }
    }
    let c = compare(&mesh, &b.finish().unwrap(), 1e-12);
    assert!(c.differences.is_empty(), "{:?}", c.differences);
    assert!(!c.same_numbering);
}

#[test]
fn med_layout_is_no_interlace_clockwise_with_families() {
    let mesh = rectangle([0.0, 0.0], 1.0, 1.0, 1, 1, CellKind::Quad4, 0.0).unwrap();
    let mut b = MeshBuilder::new("t");
    b.append(&mesh, |n| n.to_string());
    b.add_to_cell_group("Plate", 0);
    b.add_to_node_group("Origin", 0);
    let mesh = b.finish().unwrap();
    let f = File::from_bytes(med_write::to_bytes(&mesh, "sq").unwrap()).unwrap();
    let step = "ENS_MAA/sq/-0000000000000000001-0000000000000000001";
    let coo = f
        .dataset(&format!("{step}/NOE/COO"))
        .unwrap()
        .read_f64()
        .unwrap();
    let xs: Vec<f64> = mesh.coords.iter().map(|x| x[0]).collect();
    assert_eq!(&coo[..4], xs.as_slice()); // all x first
    let nod = f
        .dataset(&format!("{step}/MAI/QU4/NOD"))
        .unwrap()
        .read_i64()
        .unwrap();
    let c = mesh.cell_nodes(0);
    let clockwise: Vec<i64> = [0, 3, 2, 1].iter().map(|&a| c[a] as i64 + 1).collect();
    assert_eq!(nod, clockwise);
    let fam = f
        .dataset(&format!("{step}/MAI/QU4/FAM"))
        .unwrap()
        .read_i64()
        .unwrap();
    assert!(fam[0] < 0, "cell families are negative");
    let families = f.group("FAS/sq/ELEME").unwrap().groups().unwrap();
    assert!(families.iter().any(|n| n.contains("Plate")), "{families:?}");
    let nfam = f
        .dataset(&format!("{step}/NOE/FAM"))
        .unwrap()
        .read_i64()
        .unwrap();
    assert!(nfam[0] > 0 && nfam[1..].iter().all(|&v| v == 0));
}

/// A hand-built MED file: one Quad4 (clockwise, as MED stores it), `edit` may change it.
fn med_file(edit: impl FnOnce(&mut Parts)) -> Vec<u8> {
    let mut p = Parts {
        space_dim: 2,
        coo: vec![0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0],
        cell_type: "QU4",
        nod: vec![1, 4, 3, 2],
        cell_fam: vec![-1],
        families: true,
        ens: true,
        step_group: true,
    };
    edit(&mut p);
    let mut fb = FileBuilder::new();
    if p.ens {
        let mut ens = fb.create_group("ENS_MAA");
        let mut m = ens.create_group("M");
        m.set_attr("ESP", AttrValue::I64(p.space_dim));
        m.set_attr("TYP", AttrValue::I64(0));
        // MED 3/4: NOE and MAI in a computation-step group; MED 2: directly in the mesh
        let mut s = if p.step_group {
            m.create_group("-0000000000000000001-0000000000000000001")
        } else {
            std::mem::replace(&mut m, ens.create_group("unused"))
        };
        let mut noe = s.create_group("NOE");
        let n = p.coo.len() as i64 / p.space_dim;
        noe.create_dataset("COO")
            .with_f64_data(&p.coo)
            .set_attr("NBR", AttrValue::I64(n));
        s.add_group(noe.finish());
        let mut mai = s.create_group("MAI");
        let mut t = mai.create_group(p.cell_type);
        let nc = p.cell_fam.len() as i64;
        t.create_dataset("NOD")
            .with_i64_data(&p.nod)
            .set_attr("NBR", AttrValue::I64(nc));
        t.create_dataset("FAM")
            .with_i64_data(&p.cell_fam)
            .set_attr("NBR", AttrValue::I64(nc));
        mai.add_group(t.finish());
        s.add_group(mai.finish());
        if p.step_group {
            m.add_group(s.finish());
            ens.add_group(m.finish());
        } else {
            ens.add_group(s.finish());
        }
        fb.add_group(ens.finish());
    }
    if p.families {
        let mut fas = fb.create_group("FAS");
        let mut fm = fas.create_group("M");
        let mut el = fm.create_group("ELEME");
        let mut f = el.create_group("F1");
        f.set_attr("NUM", AttrValue::I64(-1));
        let mut gro = f.create_group("GRO");
        let mut raw = vec![0u8; 80];
        raw[..5].copy_from_slice(b"Plate");
        gro.create_dataset("NOM")
            .with_array_data(hdf5_pure::make_i8_type(), &[80], raw, 1);
        f.add_group(gro.finish());
        el.add_group(f.finish());
        fm.add_group(el.finish());
        fas.add_group(fm.finish());
        fb.add_group(fas.finish());
    }
    fb.finish().unwrap()
}

struct Parts {
    space_dim: i64,
    coo: Vec<f64>,
    cell_type: &'static str,
    nod: Vec<i64>,
    cell_fam: Vec<i64>,
    families: bool,
    ens: bool,
    step_group: bool,
}

fn med_err(edit: impl FnOnce(&mut Parts)) -> String {
    med::parse(med_file(edit), "bad.med")
        .unwrap_err()
        .to_string()
}

#[test]
fn hand_built_med_file_reads_counter_clockwise() {
    let m = med::parse(med_file(|_| {}), "ok.med").unwrap();
    assert_eq!(m.num_nodes(), 4);
    assert_eq!(m.cell_nodes(0), &[0, 1, 2, 3]);
    assert_eq!(m.reoriented, 0);
    assert_eq!(m.cell_groups["Plate"], vec![0]);
    // MED 2.x layout: no computation-step group
    let m2 = med::parse(med_file(|p| p.step_group = false), "med2.med").unwrap();
    assert_eq!(m2.cell_nodes(0), &[0, 1, 2, 3]);
    assert_eq!(m2.cell_groups["Plate"], vec![0]);
    // Space dimension 3 with z = 0, as Salome writes planar meshes.
    let m = med::parse(
        med_file(|p| {
            p.space_dim = 3;
            p.coo.extend([0.0; 4]);
        }),
        "ok3.med",
    )
    .unwrap();
    assert_eq!(m.cell_nodes(0), &[0, 1, 2, 3]);
}

#[test]
fn malformed_med_files_are_clear_errors() {
    let step = "ENS_MAA/M/-0000000000000000001-0000000000000000001";
    assert_eq!(
        med_err(|p| p.ens = false),
        "bad.med: no mesh in the file (no ENS_MAA group): not a MED mesh file"
    );
    assert_eq!(
        med_err(|p| {
            p.cell_type = "QU9";
            p.nod = (1..=9).map(|i| i.min(4)).collect();
        }),
        format!(
            "bad.med: {step}/MAI/QU9: cells of MED type QU9 (9-node quadrangle) are not \
             supported; supported: PO1, SE2, SE3, TR3, TR6, QU4, QU8"
        )
    );
    assert_eq!(
        med_err(|p| p.cell_type = "HE8"),
        format!(
            "bad.med: {step}/MAI/HE8: cells of MED type HE8 (hexahedron) are not \
             supported; supported: PO1, SE2, SE3, TR3, TR6, QU4, QU8"
        )
    );
    assert_eq!(
        med_err(|p| p.nod.pop().map(|_| ()).unwrap()),
        format!("bad.med: {step}/MAI/QU4/NOD: 3 node numbers for 1 cells of 4 nodes")
    );
    assert_eq!(
        med_err(|p| p.nod[2] = 9),
        format!("bad.med: {step}/MAI/QU4/NOD: cell 1 refers to node 9, the mesh has 4 nodes")
    );
    assert_eq!(
        med_err(|p| p.coo.push(0.5)),
        format!("bad.med: {step}/NOE/COO: 9 values for 4 nodes in 2D (expected 8)")
    );
    assert_eq!(
        med_err(|p| p.families = false),
        "bad.med: cell family -1 is used but not defined in FAS/M/ELEME"
    );
    assert_eq!(
        med_err(|p| {
            p.space_dim = 3;
            p.coo.extend([0.0, 0.0, 0.5, 0.0]);
        }),
        "bad.med: node 3 has z = 0.5: 3D meshes are not supported \
         (all nodes must lie in the plane z = 0)"
    );
    // Truncated files and non-HDF5 bytes.
    let full = med_file(|_| {});
    let e = med::parse(b"$MeshFormat".to_vec(), "x.med")
        .unwrap_err()
        .to_string();
    assert_eq!(e, "x.med: not an HDF5 file (no HDF5 signature)");
    for cut in [8, 100, full.len() / 2, full.len() - 1] {
        let r = std::panic::catch_unwind(|| med::parse(full[..cut].to_vec(), "cut.med"));
        let e = r
            .expect("panic on a truncated file")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("cut.med: "), "{e}");
    }
}

/// xorshift64 for the mutations.
struct XorShift(u64);
impl XorShift {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}

#[test]
fn mutated_med_files_never_panic() {
    let seed = med_write::to_bytes(&overlapping_groups(), "m").unwrap();
    let mut rng = XorShift(0x2545_F491_4F6C_DD1D);
    let mut rejected = 0;
    let tries = 300;
    for i in 0..tries {
        let mut m = seed.clone();
        for _ in 0..1 + rng.next() % 4 {
            let at = (rng.next() % m.len() as u64) as usize;
            m[at] = rng.next() as u8;
        }
        match std::panic::catch_unwind(|| med::parse(m, "fuzz.med")) {
            Err(_) => panic!("panic on mutation {i}"),
            Ok(Err(e)) => {
                assert!(e.to_string().starts_with("fuzz.med"), "{e}");
                rejected += 1
            }
            Ok(Ok(_)) => {}
        }
    }
    // Most single-byte changes hit data, not structure; some must still be caught.
    assert!(rejected > 0, "no mutation of {tries} was rejected");
}

#[test]
fn vtu_reader_takes_ascii_arrays_and_rejects_what_it_cannot_read() {
    let ascii = r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">
<UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="2">
<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">
0 0 0  1 0 0  1 1 0  0 1 0</DataArray></Points>
<Cells>
<DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3 0 1</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">4 6</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">9 3</DataArray>
</Cells>
<CellData><DataArray type="Int32" Name="group_Bottom" format="ascii">0 1</DataArray></CellData>
</Piece></UnstructuredGrid></VTKFile>
"#;
    let m = tribo::mesh::vtu_read::parse(ascii.as_bytes(), "a.vtu").unwrap();
    assert_eq!(m.num_nodes(), 4);
    assert_eq!(m.kind(0), CellKind::Quad4);
    assert_eq!(m.cell_groups["Bottom"], vec![1]);
    let bad = |from: &str, to: &str| {
        let text = ascii.replace(from, to);
        tribo::mesh::vtu_read::parse(text.as_bytes(), "b.vtu")
            .unwrap_err()
            .to_string()
    };
    assert_eq!(
        bad("9 3", "12 3"),
        "b.vtu: cell 1: VTK cell type 12 is not supported (1, 3, 21, 5, 22, 9, 23)"
    );
    assert_eq!(
        bad("4 6", "4 5"),
        "b.vtu: array 'connectivity': 6 values, expected 5"
    );
    assert_eq!(
        bad("1 1 0  0 1 0", "1 1 0  0 1 2"),
        "b.vtu: point 4 has z = 2: 3D meshes are not supported"
    );
    assert_eq!(
        bad(
            "byte_order=\"LittleEndian\"",
            "byte_order=\"LittleEndian\" compressor=\"vtkLZ4DataCompressor\""
        ),
        "b.vtu: compressor 'vtkLZ4DataCompressor' is not supported (only vtkZLibDataCompressor)"
    );
    let e = bad("format=\"ascii\">\n0 0 0", "format=\"binary\">\n0 0 0");
    // ("0 0 0 1 0 0 ..." without its spaces is base64, of a wrong size)
    assert!(
        e.starts_with("b.vtu: array 'Points' (binary): 3543485907 bytes announced"),
        "{e}"
    );
    // Truncated raw appended data.
    let mesh = overlapping_groups();
    let p = tmp("cut.vtu");
    tribo::post::vtu::write_mesh(&p, &mesh).unwrap();
    let full = std::fs::read(&p).unwrap();
    let e = tribo::mesh::vtu_read::parse(&full[..full.len() - 100], "cut.vtu")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("cut.vtu: array '"), "{e}");
}

/// MED holds 80 bytes of a group name: a longer one is refused, not cut (two names with
/// the same first 80 bytes would merge into one group).
#[test]
fn med_writer_refuses_a_group_name_it_would_cut() {
    let square = rectangle([0.0, 0.0], 1.0, 1.0, 1, 1, CellKind::Quad4, 0.0).unwrap();
    let long = format!("{}_top", "x".repeat(80));
    let mut b = MeshBuilder::new("long");
    b.append(
        &square,
        |g| if g == "Top" { long.clone() } else { g.into() },
    );
    let mesh = b.finish().unwrap();
    let p = tmp("long.med");
    let _ = std::fs::remove_file(&p);
    let e = med_write::write(&p, &mesh, "m").unwrap_err().to_string();
    assert_eq!(
        e,
        format!(
            "{}: group '{long}' is 84 bytes long; MED holds group names of at most 80 bytes \
             (cut, it could merge with another group): rename it",
            p.display()
        )
    );
    assert!(!p.exists(), "nothing written");
    // 80 bytes exactly is kept whole
    let exact = "y".repeat(80);
    let mut b = MeshBuilder::new("exact");
    b.append(
        &square,
        |g| if g == "Top" { exact.clone() } else { g.into() },
    );
    med_write::write(&p, &b.finish().unwrap(), "m").unwrap();
    let back = tribo::mesh::read(&p).unwrap();
    assert!(
        back.group_names().contains(&exact),
        "{:?}",
        back.group_names()
    );
}
