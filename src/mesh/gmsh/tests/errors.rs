//! Error messages: truncated files, bad numbers and tags, unsupported versions and
//! element types, missing names and end markers, counts that do not match.

use super::*;

#[test]
fn truncated_ascii() {
    let t = cut_after(BASE41, "2 1 \"Plate\"\n");
    assert_eq!(
        err(t.as_bytes()),
        format!(
            "t.msh:{}: unexpected end of file in $PhysicalNames \
             (expected physical group dimension)",
            line_of(BASE41, "2 1 \"Plate\"")
        )
    );
    let t = cut_after(BASE41, "10\n0 0");
    assert_eq!(
        err(t.as_bytes()),
        format!(
            "t.msh:{}: unexpected end of file in $Nodes (expected z coordinate)",
            line_of(BASE41, "10\n0 0") + 1
        )
    );
    let t = cut_after(BASE41, "5 10 20 30");
    assert_eq!(
        err(t.as_bytes()),
        format!(
            "t.msh:{}: unexpected end of file in $Elements (expected node tag)",
            line_of(BASE41, "5 10 20 30")
        )
    );
    let t = cut_after(BASE41, "7 50 60 30\n");
    assert_eq!(
        err(t.as_bytes()),
        format!(
            "t.msh:{}: unexpected end of file in $Elements (expected $EndElements)",
            line_of(BASE41, "7 50 60 30")
        )
    );
    let t = cut_after(BASE22, "4 0 2 0\n");
    assert_eq!(
        err(t.as_bytes()),
        format!(
            "t.msh:{}: unexpected end of file in $Nodes (expected node number)",
            line_of(BASE22, "4 0 2 0")
        )
    );
    let t = cut_after(BASE41, "$Comments\n");
    assert_eq!(
        err(t.as_bytes()),
        format!(
            "t.msh:{}: unexpected end of file (expected $EndComments)",
            line_of(BASE41, "$Comments")
        )
    );
    assert_eq!(err(b""), "t.msh: empty file: not a Gmsh MSH file");
    assert_eq!(
        err(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"),
        "t.msh: no $Nodes section"
    );
    let t = cut_after(BASE41, "$EndNodes\n");
    assert_eq!(err(t.as_bytes()), "t.msh: no $Elements section");
}

#[test]
fn truncated_binary() {
    let (bytes, m) = base41_binary();
    assert_eq!(
        err(&bytes[..m.node_tag_30 + 3]),
        format!(
            "t.msh (byte {}): unexpected end of file in $Nodes (expected node tag)",
            m.node_tag_30
        )
    );
    assert_eq!(
        err(&bytes[..m.quad_node_30 + 9]),
        format!(
            "t.msh (byte {}): unexpected end of file in $Elements (expected node tag)",
            m.quad_node_30 + 8
        )
    );
    assert_eq!(
        err(&bytes[..m.one + 2]),
        format!(
            "t.msh (byte {}): unexpected end of file in $MeshFormat \
             (expected the integer 1 in binary)",
            m.one
        )
    );
    let end = bytes.len() - "$EndElements\n".len();
    assert_eq!(
        err(&bytes[..end]),
        format!("t.msh (byte {end}): unexpected end of file in $Elements (expected $EndElements)")
    );
}

#[test]
fn binary_errors() {
    let (bytes, m) = base41_binary();
    let mut b = bytes.clone();
    b[m.quad_node_30..m.quad_node_30 + 8].copy_from_slice(&99u64.to_le_bytes());
    assert_eq!(
        err(&b),
        format!(
            "t.msh (byte {}): element 5 refers to node 99, which is not in $Nodes",
            m.quad_node_30
        )
    );
    let mut b = bytes.clone();
    b[m.quad_type..m.quad_type + 4].copy_from_slice(&4i32.to_le_bytes());
    assert_eq!(
        err(&b),
        format!(
            "t.msh (byte {}): element type 4 (4-node tetrahedron) is not supported; \
             supported Gmsh element types are {SUPPORTED_TYPES}",
            m.quad_type
        )
    );
    let mut b = bytes.clone();
    b[m.one..m.one + 4].copy_from_slice(&1i32.to_be_bytes());
    assert_eq!(
        err(&b),
        format!(
            "t.msh (byte {}): big-endian binary files are not supported",
            m.one
        )
    );
    // A huge count must fail cleanly, without a huge allocation.
    let mut b = bytes.clone();
    let count = m.node_tag_30 - 8;
    b[count..count + 8].copy_from_slice(&(u64::MAX / 2).to_le_bytes());
    assert!(err(&b).starts_with("t.msh (byte "));
}

#[test]
fn non_numeric_coordinate() {
    let text = replace_once(BASE41, "1 1 0\n0 1 0\n", "1 1 0\n0 abc 0\n");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: expected y coordinate, found 'abc'",
            line_of(&text, "0 abc 0")
        )
    );
    let text = replace_once(BASE41, "1 1 0\n0 1 0\n", "1 1 0\n0 nan 0\n");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: node 40 has a non-finite coordinate",
            line_of(&text, "0 nan 0")
        )
    );
}

#[test]
fn unsupported_element_type() {
    let text = replace_once(
        BASE41,
        "2 1 3 1\n5 10 20 30 40\n",
        "2 1 10 1\n5 10 20 30 40 50 60 10 20 30\n",
    );
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: element type 10 (9-node quadrangle) is not supported; supported \
             Gmsh element types are 15 (Point1), 1 (Seg2), 8 (Seg3), 2 (Tri3), \
             9 (Tri6), 3 (Quad4), 16 (Quad8)",
            line_of(&text, "2 1 10 1")
        )
    );
    let text = replace_once(BASE22, "5 1 0 1 2", "5 4 0 1 2 3 4");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: element type 4 (4-node tetrahedron) is not supported; \
             supported Gmsh element types are {SUPPORTED_TYPES}",
            line_of(&text, "5 4 0 1 2 3 4")
        )
    );
    let text = replace_once(BASE22, "5 1 0 1 2", "5 99 0 1 2");
    assert!(err(text.as_bytes()).contains("element type 99 is not supported;"));
}

#[test]
fn missing_physical_name() {
    let text = replace_once(BASE41, "4\n0 3 \"Corner\"\n", "3\n");
    assert_eq!(
        err(text.as_bytes()),
        "t.msh: physical group 3 (dim 0) of element 1 has no name in $PhysicalNames"
    );
    let text = replace_once(BASE22, "2 2 \"Body\"\n", "1 2 \"Body\"\n");
    assert_eq!(
        err(text.as_bytes()),
        "t.msh: physical group 2 (dim 2) of element 3 has no name in $PhysicalNames"
    );
    let text = replace_once(BASE41, "\"All\"", "All");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: expected a physical name in double quotes, found 'All'",
            line_of(&text, "2 2 All")
        )
    );
}

#[test]
fn unknown_node_tag() {
    let text = replace_once(BASE41, "6 20 50 30", "6 20 55 30");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: element 6 refers to node 55, which is not in $Nodes",
            line_of(&text, "6 20 55 30")
        )
    );
    let text = replace_once(BASE22, "2 8 2 1 1 1 2 5", "2 8 2 1 1 1 2 9");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: element 2 refers to node 9, which is not in $Nodes",
            line_of(&text, "2 8 2 1 1 1 2 9")
        )
    );
}

#[test]
fn unsupported_versions() {
    for v in ["3.0", "4.0", "2.1", "4"] {
        let text = replace_once(BASE41, "4.1 0 8", &format!("{v} 0 8"));
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:2: unsupported MSH version {v}; supported versions are 4.1 \
                 (ASCII or binary) and 2.2 (ASCII)"
            )
        );
    }
    let text = replace_once(BASE22, "2.2 0 8", "2.2 1 8");
    assert_eq!(
        err(text.as_bytes()),
        "t.msh:2: binary MSH 2.2 files are not supported; supported versions are 4.1 \
         (ASCII or binary) and 2.2 (ASCII)"
    );
    assert_eq!(
        err(b"solid cube\nfacet normal 0 0 1\n"),
        "t.msh:1: not a Gmsh MSH file: expected $MeshFormat, found 'solid'"
    );
}

#[test]
fn missing_or_wrong_end_marker() {
    let text = replace_once(BASE41, "$EndElements\n", "");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: unexpected end of file in $Elements (expected $EndElements)",
            line_of(&text, "7 50 60 30")
        )
    );
    let text = replace_once(BASE41, "$EndElements\n", "$EndElement\n");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: expected $EndElements, found '$EndElement'",
            line_of(&text, "$EndElement")
        )
    );
    // One more element than the count says.
    let text = replace_once(BASE22, "$Elements\n6\n", "$Elements\n5\n");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: expected $EndElements, found '6' \
             (do the counts in the section match its data?)",
            line_of(&text, "6 1 2 0 1 3 4")
        )
    );
}

#[test]
fn counts_that_do_not_match() {
    let text = replace_once(BASE41, "6 7 1 7", "6 8 1 8");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: the $Elements header announces 8 elements but its blocks hold 7",
            line_of(&text, "6 8 1 8")
        )
    );
    let text = replace_once(BASE41, "3 6 10 60", "3 5 10 60");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: the $Nodes header announces 5 nodes but its blocks hold 6",
            line_of(&text, "3 5 10 60")
        )
    );
}

#[test]
fn other_errors() {
    let text = replace_once(BASE41, "2 1 0\n$EndNodes", "2 1 0.5\n$EndNodes");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: node 60 has z = 0.5: 3D meshes are not supported \
             (all nodes must lie in the plane z = 0)",
            line_of(&text, "2 1 0.5")
        )
    );
    let text = replace_once(BASE22, "20 4 0 0", "2 4 0 0");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: node tag 2 appears twice in $Nodes",
            line_of(&text, "2 4 0 0")
        )
    );
    // A node listed twice in an element is refused where it is read.
    let text = replace_once(BASE41, "5 10 20 30 40", "5 10 20 20 40");
    assert_eq!(
        err(text.as_bytes()),
        format!(
            "t.msh:{}: element 5 lists node 20 twice",
            line_of(&text, "5 10 20 20 40")
        )
    );
    // A degenerate cell is rejected by the mesh builder, naming the element.
    let text = replace_once(BASE41, "5 10 20 30 40", "5 10 20 40 30");
    assert_eq!(
        err(text.as_bytes()),
        "t.msh: cell 5 (Quad4) is inverted or tangled (its Jacobian changes sign or vanishes)"
    );
    let text = replace_once(BASE41, "$Nodes\n", "$EndFoo\n");
    assert!(err(text.as_bytes()).contains("'$EndFoo' closes no open section"));
}

#[test]
fn read_names_the_file() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/mesh/gmsh/mod.rs");
    let e = read(Path::new(path)).unwrap_err().to_string();
    assert_eq!(
        e,
        format!("{path}:1: not a Gmsh MSH file: expected $MeshFormat, found '//!'")
    );
    let missing = concat!(env!("CARGO_MANIFEST_DIR"), "/no/such/file.msh");
    let e = read(Path::new(missing)).unwrap_err().to_string();
    assert!(e.starts_with(&format!("{missing}: ")), "{e}");
}
