//! MED files written by older HDF5 versions: one MED 2.x mesh (tests/med_layouts/, made by
//! its make.py) stored in every data-layout message version HDF5 writers have produced
//! (1 and 2: HDF5 before 1.6.3; 3; 4) and every storage class (contiguous, chunked,
//! compact). Each must read to the same nodes, cells and groups, exactly.

use std::collections::BTreeMap;
use std::path::PathBuf;
use tribo::mesh::CellKind;

const FILES: [&str; 11] = [
    "v1_contiguous",
    "v1_chunked",
    "v2_contiguous",
    "v2_chunked",
    "v2_compact",
    "v3_contiguous",
    "v3_chunked",
    "v3_compact",
    "v4_contiguous",
    "v4_chunked",
    "v4_compact",
];

/// Datasets in each file (COO, FAM, NOD and FAM of three cell types, five GRO/NOM).
const DATASETS: usize = 13;

fn path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("tests/med_layouts/{name}.med"))
}

/// How many version 1/2 layout messages of `class` the file holds for 1D datasets: the
/// message header (type 8) followed by version, dimensionality 2, class, 5 reserved bytes.
fn old_layout_messages(bytes: &[u8], version: u8, class: u8) -> usize {
    bytes
        .windows(16)
        .enumerate()
        .filter(|(at, w)| {
            at % 8 == 0
                && w[..2] == [8, 0]
                && w[5..8] == [0, 0, 0]
                && w[8..] == [version, 2, class, 0, 0, 0, 0, 0]
        })
        .count()
}

#[test]
fn the_files_hold_the_layout_versions_they_are_named_after() {
    for name in FILES
        .iter()
        .filter(|n| n.starts_with("v1") || n.starts_with("v2"))
    {
        let bytes = std::fs::read(path(name)).unwrap();
        let version = name.as_bytes()[1] - b'0';
        let class = match &name[3..] {
            "compact" => 0,
            "contiguous" => 1,
            _ => 2,
        };
        assert_eq!(
            old_layout_messages(&bytes, version, class),
            DATASETS,
            "{name}"
        );
    }
}

#[test]
fn every_layout_version_and_class_reads_the_same_mesh() {
    let coords = [
        [0.0, 0.0],
        [1.0, 0.0],
        [2.0, 0.0],
        [0.0, 1.0],
        [1.0, 1.0],
        [2.0, 1.0],
        [3.0, 0.5],
    ];
    // MED's clockwise cells in our counter-clockwise order; types in name order.
    let cells: [(CellKind, &[usize]); 5] = [
        (CellKind::Quad4, &[0, 1, 4, 3]),
        (CellKind::Quad4, &[1, 2, 5, 4]),
        (CellKind::Seg2, &[0, 1]),
        (CellKind::Seg2, &[1, 2]),
        (CellKind::Tri3, &[2, 6, 5]),
    ];
    let cell_groups = BTreeMap::from([
        ("body".to_string(), vec![0, 1, 4]),
        ("bottom".to_string(), vec![2, 3]),
        ("left".to_string(), vec![0]),
        ("right".to_string(), vec![1, 4]),
    ]);
    let node_groups = BTreeMap::from([
        ("corner".to_string(), vec![0]),
        ("tip".to_string(), vec![6]),
    ]);
    for name in FILES {
        let m = tribo::mesh::read(&path(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(m.coords, coords, "{name}");
        assert_eq!(m.num_cells(), cells.len(), "{name}");
        for (c, (kind, nodes)) in cells.iter().enumerate() {
            assert_eq!(
                (m.kind(c), m.cell_nodes(c)),
                (*kind, *nodes),
                "{name} cell {c}"
            );
        }
        assert_eq!(m.reoriented, 0, "{name}");
        assert_eq!(m.cell_groups, cell_groups, "{name}");
        assert_eq!(m.node_groups, node_groups, "{name}");
    }
}
