//! MSH 2.2 (ASCII) entries: two quadrangles A and B, edges, two points; and one Quad8.

use super::{Entry, Set};

/// Lines 13–21 are $Nodes, 22–34 $Elements.
pub const BASE: &str = "$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
6
2 1 \"A\"
2 2 \"B\"
1 3 \"Bottom\"
1 4 \"Top\"
1 5 \"Left\"
0 6 \"P\"
$EndPhysicalNames
$Nodes
6
1 0 0 0
2 1 0 0
3 2 0 0
4 0 1 0
5 1 1 0
6 2 1 0
$EndNodes
$Elements
10
1 3 2 1 1 1 2 5 4
1 3 2 2 1 1 2 5 4
2 3 2 1 1 2 3 6 5
3 1 2 3 2 1 2
4 1 2 3 2 2 3
5 1 2 4 3 5 4
6 1 2 4 3 6 5
7 1 2 5 4 4 1
8 15 2 6 5 4
9 15 2 6 5 6
$EndElements
";

/// One Quad8 (nodes 1–4 corners, 5–8 mid-sides) in group \"S\".
const QUAD8: &str = "$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
2 1 \"S\"
$EndPhysicalNames
$Nodes
8
1 0 0 0
2 2 0 0
3 2 2 0
4 0 2 0
5 1 0 0
6 2 1 0
7 1 2 0
8 0 1 0
$EndNodes
$Elements
1
1 16 2 1 1 1 2 3 4 5 6 7 8
$EndElements
";

pub fn entries() -> Vec<Entry> {
    let mut s = Set {
        base: BASE,
        ext: "msh",
        prefix: "m22",
        out: vec![],
    };
    s.ok("base", BASE.into(), 6, 9);
    // truncations
    s.cut(
        "cut_header",
        "2.2",
        ":2: unexpected end of file in $MeshFormat (expected file type",
    );
    s.cut(
        "cut_nodes",
        "3 2 0 0\n",
        ":17: unexpected end of file in $Nodes (expected node number)",
    );
    s.cut(
        "cut_node_line",
        "3 2 0",
        ":17: unexpected end of file in $Nodes (expected z coordinate)",
    );
    s.cut(
        "cut_elements",
        "2 3 2 1 1 2 3",
        "unexpected end of file in $Elements (expected node number)",
    );
    s.cut("cut_before_elements", "$EndNodes\n", "no $Elements section");
    s.cut(
        "cut_no_end",
        "9 15 2 6 5 6\n",
        "unexpected end of file in $Elements (expected $EndElements)",
    );
    s.cut(
        "cut_names",
        "2 2 \"B\"",
        "unexpected end of file in $PhysicalNames",
    );
    s.text("empty", "", "empty file: not a Gmsh MSH file");
    s.text("blank", "\n\n  \n", "empty file: not a Gmsh MSH file");
    // wrong counts
    s.sub(
        "nodes_count_more",
        "$Nodes\n6\n",
        "$Nodes\n7\n",
        ":21: expected node number, found '$EndNodes'",
    );
    s.sub(
        "nodes_count_less",
        "$Nodes\n6\n",
        "$Nodes\n5\n",
        ":20: expected $EndNodes, found '6' (do the counts in the section match its data?)",
    );
    s.sub(
        "elements_count_more",
        "$Elements\n10\n",
        "$Elements\n11\n",
        ":34: expected element number, found '$EndElements'",
    );
    s.sub(
        "elements_count_less",
        "$Elements\n10\n",
        "$Elements\n9\n",
        ":33: expected $EndElements, found '9'",
    );
    s.sub(
        "names_count_more",
        "$PhysicalNames\n6\n",
        "$PhysicalNames\n7\n",
        ":12: expected physical group dimension, found '$EndPhysicalNames'",
    );
    s.sub(
        "nodes_count_negative",
        "$Nodes\n6\n",
        "$Nodes\n-6\n",
        ":14: expected number of nodes, found '-6'",
    );
    s.sub(
        "nodes_count_overflow",
        "$Nodes\n6\n",
        "$Nodes\n99999999999999999999999\n",
        ":14: expected number of nodes, found '99999999999999999999999'",
    );
    // memory bombs: huge declared counts with little data
    s.sub(
        "nodes_count_huge",
        "$Nodes\n6\n",
        "$Nodes\n1000000000000000\n",
        ":21: expected node number, found '$EndNodes'",
    );
    s.sub(
        "elements_count_huge",
        "$Elements\n10\n",
        "$Elements\n18446744073709551615\n",
        ":34: expected element number, found '$EndElements'",
    );
    s.sub(
        "tags_count_huge",
        "3 1 2 3 2 1 2",
        "3 1 999999999999 3 2 1 2",
        ":34: expected element tag, found '$EndElements'",
    );
    // coordinates
    s.sub(
        "x_nan",
        "2 1 0 0",
        "2 nan 0 0",
        ":16: node 2 has a non-finite coordinate",
    );
    s.sub(
        "y_NaN_caps",
        "2 1 0 0",
        "2 1 NaN 0",
        ":16: node 2 has a non-finite coordinate",
    );
    s.sub(
        "x_inf",
        "3 2 0 0",
        "3 inf 0 0",
        ":17: node 3 has a non-finite coordinate",
    );
    s.sub(
        "y_minus_inf",
        "3 2 0 0",
        "3 2 -inf 0",
        ":17: node 3 has a non-finite coordinate",
    );
    s.sub(
        "z_nan",
        "4 0 1 0",
        "4 0 1 nan",
        ":18: node 4 has a non-finite coordinate",
    );
    s.sub(
        "x_overflow",
        "5 1 1 0",
        "5 1e400 1 0",
        ":19: node 5 has a non-finite coordinate",
    );
    s.sub(
        "x_comma",
        "5 1 1 0",
        "5 1,5 1 0",
        ":19: expected x coordinate, found '1,5'",
    );
    s.sub(
        "x_word",
        "5 1 1 0",
        "5 one 1 0",
        ":19: expected x coordinate, found 'one'",
    );
    s.sub(
        "z_nonzero",
        "3 2 0 0",
        "3 2 0 0.5",
        ":17: node 3 has z = 0.5: 3D meshes are not supported",
    );
    // node ids
    s.sub(
        "node_tag_negative",
        "1 0 0 0",
        "-1 0 0 0",
        ":15: expected node number, found '-1'",
    );
    s.sub(
        "node_tag_duplicate",
        "2 1 0 0",
        "1 1 0 0",
        ":16: node tag 1 appears twice in $Nodes",
    );
    s.sub(
        "node_tag_float",
        "2 1 0 0",
        "2.5 1 0 0",
        ":16: expected node number, found '2.5'",
    );
    s.sub(
        "node_tag_missing",
        "1 0 0 0",
        "7 0 0 0",
        ":24: element 1 refers to node 1, which is not in $Nodes",
    );
    s.sub(
        "node_tag_renumbered",
        "6 2 1 0",
        "60 2 1 0",
        ":26: element 2 refers to node 6, which is not in $Nodes",
    );
    let huge = BASE
        .replacen("6 2 1 0", "18446744073709551615 2 1 0", 1)
        .replacen("1 2 3 6 5", "1 2 3 18446744073709551615 5", 1)
        .replacen("4 3 6 5", "4 3 18446744073709551615 5", 1)
        .replacen("6 5 6\n", "6 5 18446744073709551615\n", 1);
    s.ok("node_tags_sparse_huge", huge.into_bytes(), 6, 9);
    s.sub(
        "elem_node_out_of_range",
        "3 1 2 3 2 1 2",
        "3 1 2 3 2 1 99",
        ":27: element 3 refers to node 99, which is not in $Nodes",
    );
    s.sub(
        "elem_node_negative",
        "3 1 2 3 2 1 2",
        "3 1 2 3 2 1 -2",
        ":27: expected node number, found '-2'",
    );
    s.sub(
        "elem_node_zero",
        "3 1 2 3 2 1 2",
        "3 1 2 3 2 0 2",
        ":27: element 3 refers to node 0, which is not in $Nodes",
    );
    s.sub(
        "elem_node_overflow",
        "3 1 2 3 2 1 2",
        "3 1 2 3 2 1 18446744073709551616",
        ":27: expected node number, found '18446744073709551616'",
    );
    s.sub_ok(
        "node_tags_unused",
        "6\n1 0 0 0",
        "7\n100 5 5 0\n1 0 0 0",
        7,
        9,
    );
    // element types
    s.sub(
        "type_unknown",
        "2 3 2 1 1 2 3 6 5",
        "2 99 2 1 1 2 3 6 5",
        ":26: element type 99 is not supported",
    );
    s.sub(
        "type_tetra",
        "2 3 2 1 1 2 3 6 5",
        "2 4 2 1 1 2 3 6 5",
        "element type 4 (4-node tetrahedron) is not supported",
    );
    s.sub(
        "type_quad9",
        "2 3 2 1 1 2 3 6 5",
        "2 10 2 1 1 2 3 6 5",
        "element type 10 (9-node quadrangle) is not supported",
    );
    s.sub(
        "type_negative",
        "2 3 2 1 1 2 3 6 5",
        "2 -3 2 1 1 2 3 6 5",
        ":26: element type -3 is not supported",
    );
    s.sub(
        "type_word",
        "2 3 2 1 1 2 3 6 5",
        "2 quad 2 1 1 2 3 6 5",
        ":26: expected element type, found 'quad'",
    );
    s.sub(
        "type_wrong_node_count",
        "3 1 2 3 2 1 2",
        "3 2 2 3 2 1 2",
        ":31: element 4 refers to node 7, which is not in $Nodes",
    );
    // repeated nodes, zero area, inverted cells
    s.sub(
        "quad_repeated_node",
        "2 3 2 1 1 2 3 6 5",
        "2 3 2 1 1 2 3 3 5",
        ":26: element 2 lists node 3 twice",
    );
    s.sub(
        "seg_repeated_node",
        "3 1 2 3 2 1 2",
        "3 1 2 3 2 1 1",
        ":27: element 3 lists node 1 twice",
    );
    s.sub_ok("point_twice", "9 15 2 6 5 6", "9 15 2 6 5 4", 6, 9);
    let zero_seg = BASE
        .replacen("$Nodes\n6\n", "$Nodes\n7\n7 0 0 0\n", 1)
        .replacen("$Elements\n10\n", "$Elements\n11\n10 1 2 5 4 1 7\n", 1);
    s.text(
        "seg_zero_length",
        &zero_seg,
        "cell 10 (Seg2) is of zero length",
    );
    s.sub("quad_collapsed", "5 1 1 0", "5 1 0 0", "cell 1 (Quad4) is");
    s.sub(
        "quad_bowtie",
        "2 3 2 1 1 2 3 6 5",
        "2 3 2 1 1 2 3 5 6",
        "cell 2 (Quad4) is inverted or tangled",
    );
    s.sub(
        "quad_nonconvex",
        "5 1 1 0",
        "5 0.2 0.2 0",
        "cell 1 (Quad4) is inverted or tangled",
    );
    s.sub_ok(
        "quad_clockwise",
        "2 3 2 1 1 2 3 6 5",
        "2 3 2 1 1 5 6 3 2",
        6,
        9,
    );
    s.sub("quad_tiny_coordinates", "$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 0 1 0\n5 1 1 0\n6 2 1 0", "$Nodes\n6\n1 0 0 0\n2 1e-200 0 0\n3 2e-200 0 0\n4 0 1e-200 0\n5 1e-200 1e-200 0\n6 2e-200 1e-200 0", "cell 1 (Quad4) is of zero area");
    s.sub("quad_huge_coordinates", "$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 0 1 0\n5 1 1 0\n6 2 1 0", "$Nodes\n6\n1 0 0 0\n2 1e200 0 0\n3 2e200 0 0\n4 0 1e200 0\n5 1e200 1e200 0\n6 2e200 1e200 0", "(Quad4) is of zero area");
    // groups
    s.sub(
        "physical_unnamed",
        "2 3 2 1 1 2 3 6 5",
        "2 3 2 7 1 2 3 6 5",
        "physical group 7 (dim 2) of element 2 has no name in $PhysicalNames",
    );
    s.sub(
        "name_unquoted",
        "2 1 \"A\"",
        "2 1 A",
        ":6: expected a physical name in double quotes, found 'A'",
    );
    s.sub(
        "name_empty",
        "2 1 \"A\"",
        "2 1 \"\"",
        ":6: empty physical name",
    );
    s.sub(
        "name_dim_bad",
        "2 1 \"A\"",
        "5 1 \"A\"",
        ":6: physical group dimension must be 0, 1, 2 or 3, found 5",
    );
    s.bytes(
        "name_latin1",
        BASE.replacen("\"A\"", "\"\u{1}\"", 1)
            .bytes()
            .map(|b| if b == 1 { 0xe9 } else { b })
            .collect(),
        ":6: physical name is not valid UTF-8",
    );
    s.sub_ok(
        "group_empty",
        "6\n2 1 \"A\"",
        "7\n2 8 \"Unused\"\n2 1 \"A\"",
        6,
        9,
    );
    s.sub("names_none", "$PhysicalNames\n6\n2 1 \"A\"\n2 2 \"B\"\n1 3 \"Bottom\"\n1 4 \"Top\"\n1 5 \"Left\"\n0 6 \"P\"\n$EndPhysicalNames\n", "", "physical group 1 (dim 2) of element 1 has no name in $PhysicalNames");
    s.sub(
        "element_redefined",
        "2 3 2 1 1 2 3 6 5",
        "1 3 2 1 1 2 3 6 5",
        "element 1 is defined twice with different nodes",
    );
    s.sub_ok("elements_none", "$Elements\n10\n1 3 2 1 1 1 2 5 4\n1 3 2 2 1 1 2 5 4\n2 3 2 1 1 2 3 6 5\n3 1 2 3 2 1 2\n4 1 2 3 2 2 3\n5 1 2 4 3 5 4\n6 1 2 4 3 6 5\n7 1 2 5 4 4 1\n8 15 2 6 5 4\n9 15 2 6 5 6\n", "$Elements\n0\n", 6, 0);
    // sections
    s.sub(
        "version_3",
        "2.2 0 8",
        "3.0 0 8",
        ":2: unsupported MSH version 3.0",
    );
    s.sub(
        "version_word",
        "2.2 0 8",
        "two 0 8",
        ":2: expected version number, found 'two'",
    );
    s.sub(
        "binary_22",
        "2.2 0 8",
        "2.2 1 8",
        ":2: binary MSH 2.2 files are not supported",
    );
    s.sub(
        "file_type_2",
        "2.2 0 8",
        "2.2 2 8",
        ":2: file type must be 0 (ASCII) or 1 (binary), found 2",
    );
    s.sub(
        "no_meshformat",
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n",
        "",
        ":1: not a Gmsh MSH file: expected $MeshFormat, found '$PhysicalNames'",
    );
    s.sub(
        "meshformat_twice",
        "$PhysicalNames\n6",
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n6",
        ":4: second $MeshFormat section",
    );
    s.sub(
        "nodes_twice",
        "$Elements\n10",
        "$Nodes\n0\n$EndNodes\n$Elements\n10",
        ":22: second $Nodes section",
    );
    s.sub(
        "no_end_nodes",
        "$EndNodes\n",
        "",
        ":21: expected $EndNodes, found '$Elements'",
    );
    s.sub(
        "end_twice",
        "$EndNodes\n",
        "$EndNodes\n$EndNodes\n",
        ":22: '$EndNodes' closes no open section",
    );
    s.sub(
        "garbage_line",
        "$Elements\n",
        "hello\n$Elements\n",
        ":22: expected a section header such as $Nodes, found 'hello'",
    );
    s.sub(
        "unknown_section_open",
        "$Elements\n",
        "$Foo\n1 2 3\n",
        "unexpected end of file (expected $EndFoo)",
    );
    s.sub_ok(
        "unknown_section_skipped",
        "$Elements\n",
        "$Comments\nanything $Nodes 1 2\n$EndComments\n$Elements\n",
        6,
        9,
    );
    s.sub(
        "elements_before_nodes",
        "$Nodes\n",
        "$Elements\n0\n$EndElements\n$Nodes\n",
        ":13: $Elements comes before $Nodes",
    );
    s.ok("crlf", BASE.replace('\n', "\r\n").into_bytes(), 6, 9);
    s.bytes(
        "nul_bytes",
        {
            let mut b = BASE.as_bytes().to_vec();
            b.splice(200..200, [0u8; 16]);
            b
        },
        "m22_nul_bytes.msh:34: unexpected end of file",
    );
    // quadratic cells
    let mut q = Set {
        base: QUAD8,
        ext: "msh",
        prefix: "m22q",
        out: vec![],
    };
    q.ok("quad8", QUAD8.into(), 8, 1);
    q.sub(
        "midside_outside",
        "6 2 1 0",
        "6 -1 1 0",
        "cell 1 (Quad8) is inverted or tangled",
    );
    q.sub(
        "midside_on_corner",
        "5 1 0 0",
        "5 0 0 0",
        "cell 1 (Quad8) is",
    );
    q.sub(
        "midside_repeated",
        "1 2 3 4 5 6 7 8",
        "1 2 3 4 5 5 7 8",
        ":21: element 1 lists node 5 twice",
    );
    q.sub(
        "too_few_nodes",
        "1 2 3 4 5 6 7 8",
        "1 2 3 4 5 6 7",
        ":22: expected node number, found '$EndElements'",
    );
    q.sub(
        "as_quad4",
        "1 16 2 1 1",
        "1 3 2 1 1",
        ":21: expected $EndElements, found '5'",
    );
    s.out.extend(q.out);
    s.out
}
