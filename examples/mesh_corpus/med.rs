//! MED entries: files of our MED writer with bad coordinates or connectivity patched in,
//! truncated or damaged, and files that are not HDF5 at all.

use super::{Entry, Set};
use tribo::mesh::{med_write, CellKind, Mesh, MeshBuilder};

/// One unit square Quad4 in group "S", with an edge "E"; with `extra`, a fifth node below
/// the first corner and an edge "Z" to it.
fn square_with(extra: bool) -> Mesh {
    let mut b = MeshBuilder::new("square");
    for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
        b.add_node(p);
    }
    if extra {
        b.add_node([0.0, -1.0]);
        let z = b.add_cell(CellKind::Seg2, &[0, 4], 3);
        b.add_to_cell_group("Z", z);
    }
    let q = b.add_cell(CellKind::Quad4, &[0, 1, 2, 3], 1);
    b.add_to_cell_group("S", q);
    let e = b.add_cell(CellKind::Seg2, &[0, 1], 2);
    b.add_to_cell_group("E", e);
    b.finish().unwrap()
}

fn square() -> Mesh {
    square_with(false)
}

fn bytes(m: &Mesh) -> Vec<u8> {
    med_write::to_bytes(m, "mesh").unwrap()
}

/// Offset of the Quad4 connectivity: four consecutive i64 that are 1, 2, 3, 4 in some order.
fn quad_conn(b: &[u8]) -> usize {
    (0..b.len() - 32)
        .find(|&i| {
            let mut v: Vec<i64> = (0..4)
                .map(|k| i64::from_le_bytes(b[i + 8 * k..i + 8 * k + 8].try_into().unwrap()))
                .collect();
            v.sort();
            v == [1, 2, 3, 4]
        })
        .expect("no Quad4 connectivity in the MED bytes")
}

pub fn entries() -> Vec<Entry> {
    let mut s = Set {
        base: "",
        ext: "med",
        prefix: "med",
        out: vec![],
    };
    let good = bytes(&square());
    s.ok("base", good.clone(), 4, 2);
    let with = |f: &dyn Fn(&mut Mesh)| {
        let mut m = square();
        f(&mut m);
        bytes(&m)
    };
    s.bytes(
        "x_nan",
        with(&|m| m.coords[1][0] = f64::NAN),
        "node 2 has a non-finite coordinate",
    );
    s.bytes(
        "y_inf",
        with(&|m| m.coords[2][1] = f64::INFINITY),
        "node 3 has a non-finite coordinate",
    );
    s.bytes(
        "zero_area",
        with(&|m| m.coords[2] = [1.0, 0.0]),
        "(Quad4) is",
    );
    s.bytes(
        "bowtie",
        with(&|m| m.coords.swap(2, 3)),
        "cell 1 (Quad4) is inverted or tangled",
    );
    let mut z = square_with(true);
    z.coords[4] = [1e-14, 0.0];
    s.bytes("seg_zero_length", bytes(&z), "(Seg2) is of zero length");
    let at = quad_conn(&good);
    for (name, v, detail) in [
        (
            "conn_out_of_range",
            9i64,
            "MAI/QU4/NOD: cell 1 refers to node 9, the mesh has 4 nodes",
        ),
        (
            "conn_zero",
            0,
            "MAI/QU4/NOD: cell 1 refers to node 0, the mesh has 4 nodes",
        ),
        (
            "conn_negative",
            -3,
            "MAI/QU4/NOD: cell 1 refers to node -3, the mesh has 4 nodes",
        ),
        (
            "conn_huge",
            i64::MAX,
            "MAI/QU4/NOD: cell 1 refers to node 9223372036854775807, the mesh has 4 nodes",
        ),
    ] {
        let mut b = good.clone();
        b[at..at + 8].copy_from_slice(&v.to_le_bytes());
        s.bytes(name, b, detail);
    }
    let mut rep = good.clone();
    let second = rep[at + 8..at + 16].to_vec();
    rep[at..at + 8].copy_from_slice(&second);
    s.bytes("conn_repeated", rep, "cell 1 (Quad4) lists node");
    s.bytes("cut_8", good[..8].to_vec(), "unreadable HDF5 file");
    let n = good.len();
    for (name, len) in [
        ("cut_100", 100),
        ("cut_half", n / 2),
        ("cut_last_byte", n - 1),
    ] {
        s.bytes(
            name,
            good[..len].to_vec(),
            &format!("truncated HDF5 file: {len} bytes, its superblock says {n}"),
        );
    }
    let mut flip = good.clone();
    flip[9] ^= 0xff;
    s.bytes("superblock_damaged", flip, "unreadable HDF5 file");
    s.bytes("empty", vec![], "not an HDF5 file (no HDF5 signature)");
    s.bytes(
        "text",
        b"hello, not a mesh\n".to_vec(),
        "not an HDF5 file (no HDF5 signature)",
    );
    s.out
}
