//! MSH 4.1 (ASCII) entries: the two quadrangles as `tribo mesh convert` writes them.

use super::{Entry, Set};

/// Lines 13–21 are $Entities, 22–37 $Nodes (tags 25–30, coordinates 31–36), 38–55 $Elements.
const BASE: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
6
0 1 \"P\"
1 2 \"Bottom\"
1 3 \"Top\"
1 4 \"Left\"
2 5 \"A\"
2 6 \"B\"
$EndPhysicalNames
$Entities
1 3 2 0
7 0e0 1e0 0 1 1
4 0e0 0e0 0 2e0 0e0 0 1 2 0
5 0e0 1e0 0 2e0 1e0 0 1 3 0
6 0e0 0e0 0 0e0 1e0 0 1 4 0
2 0e0 0e0 0 1e0 1e0 0 2 5 6 0
3 1e0 0e0 0 2e0 1e0 0 1 5 0
$EndEntities
$Nodes
1 6 1 6
2 2 0 6
1
2
3
4
5
6
0e0 0e0 0
1e0 0e0 0
2e0 0e0 0
0e0 1e0 0
1e0 1e0 0
2e0 1e0 0
$EndNodes
$Elements
6 9 1 9
0 7 15 2
1 4
2 6
1 4 1 2
3 1 2
4 2 3
1 5 1 2
5 5 4
6 6 5
1 6 1 1
7 4 1
2 2 3 1
8 1 2 5 4
2 3 3 1
9 2 3 6 5
$EndElements
";

pub fn entries() -> Vec<Entry> {
    let mut s = Set {
        base: BASE,
        ext: "msh",
        prefix: "m41",
        out: vec![],
    };
    s.ok("base", BASE.into(), 6, 9);
    // truncations
    s.cut(
        "cut_entities",
        "4 0e0 0e0 0",
        ":16: unexpected end of file in $Entities (expected entity coordinate)",
    );
    s.cut(
        "cut_node_tags",
        "\n3\n",
        ":27: unexpected end of file in $Nodes (expected node tag)",
    );
    s.cut(
        "cut_coordinates",
        "2e0 0e0 0\n",
        ":33: unexpected end of file in $Nodes (expected x coordinate)",
    );
    s.cut(
        "cut_elements",
        "8 1 2",
        ":52: unexpected end of file in $Elements (expected node tag)",
    );
    s.cut(
        "cut_element_header",
        "$Elements\n6 9",
        ":39: unexpected end of file in $Elements (expected smallest element tag)",
    );
    // counts
    s.sub(
        "nodes_header_more",
        "$Nodes\n1 6 1 6",
        "$Nodes\n1 7 1 7",
        ":23: the $Nodes header announces 7 nodes but its blocks hold 6",
    );
    s.sub(
        "nodes_block_more",
        "2 2 0 6\n",
        "2 2 0 7\n",
        ":31: expected node tag, found '0e0'",
    );
    s.sub(
        "nodes_block_less",
        "2 2 0 6\n",
        "2 2 0 5\n",
        ":23: the $Nodes header announces 6 nodes but its blocks hold 5",
    );
    s.sub(
        "nodes_blocks_more",
        "$Nodes\n1 6 1 6",
        "$Nodes\n2 6 1 6",
        ":37: expected entity dimension, found '$EndNodes'",
    );
    s.sub(
        "nodes_blocks_huge",
        "$Nodes\n1 6 1 6",
        "$Nodes\n99999999999999 6 1 6",
        ":37: expected entity dimension, found '$EndNodes'",
    );
    s.sub(
        "nodes_block_huge",
        "2 2 0 6\n",
        "2 2 0 100000000000000\n",
        ":31: expected node tag, found '0e0'",
    );
    s.sub(
        "elements_header_more",
        "$Elements\n6 9 1 9",
        "$Elements\n6 10 1 10",
        ":39: the $Elements header announces 10 elements but its blocks hold 9",
    );
    s.sub(
        "elements_block_more",
        "2 3 3 1\n",
        "2 3 3 2\n",
        ":55: expected element tag, found '$EndElements'",
    );
    s.sub(
        "elements_block_huge",
        "2 3 3 1\n",
        "2 3 3 1000000000000000000\n",
        ":55: expected element tag, found '$EndElements'",
    );
    s.sub(
        "elements_blocks_huge",
        "$Elements\n6 9 1 9",
        "$Elements\n4000000000 9 1 9",
        ":55: expected entity dimension, found '$EndElements'",
    );
    s.sub(
        "entities_huge",
        "$Entities\n1 3 2 0",
        "$Entities\n1 3 99999999999 0",
        ":21: expected entity tag, found '$EndEntities'",
    );
    s.sub(
        "physical_tags_huge",
        "2 0e0 0e0 0 1e0 1e0 0 2 5 6 0",
        "2 0e0 0e0 0 1e0 1e0 0 99999999999 5 6 0",
        ":20: expected physical tag, found '1e0'",
    );
    s.sub(
        "count_negative",
        "$Nodes\n1 6 1 6",
        "$Nodes\n1 -6 1 6",
        ":23: expected number of nodes, found '-6'",
    );
    // coordinates
    s.sub(
        "x_nan",
        "1e0 0e0 0\n",
        "nan 0e0 0\n",
        ":32: node 2 has a non-finite coordinate",
    );
    s.sub(
        "y_inf",
        "2e0 0e0 0\n",
        "2e0 inf 0\n",
        ":33: node 3 has a non-finite coordinate",
    );
    s.sub(
        "z_nonzero",
        "2e0 1e0 0\n",
        "2e0 1e0 1e-3\n",
        ":36: node 6 has z = 0.001: 3D meshes are not supported",
    );
    s.sub(
        "z_minus_inf",
        "2e0 1e0 0\n",
        "2e0 1e0 -inf\n",
        ":36: node 6 has a non-finite coordinate",
    );
    s.sub(
        "x_hex",
        "1e0 0e0 0\n",
        "0x1 0e0 0\n",
        ":32: expected x coordinate, found '0x1'",
    );
    // node ids
    s.sub(
        "node_tag_duplicate",
        "\n4\n5\n",
        "\n4\n4\n",
        ":29: node tag 4 appears twice in $Nodes",
    );
    s.sub(
        "node_tag_negative",
        "\n4\n5\n",
        "\n4\n-5\n",
        ":29: expected node tag, found '-5'",
    );
    s.sub(
        "elem_node_missing",
        "8 1 2 5 4",
        "8 1 2 5 40",
        ":52: element 8 refers to node 40, which is not in $Nodes",
    );
    s.sub(
        "elem_node_zero",
        "8 1 2 5 4",
        "8 0 2 5 4",
        ":52: element 8 refers to node 0, which is not in $Nodes",
    );
    s.sub(
        "elem_node_negative",
        "8 1 2 5 4",
        "8 1 2 -5 4",
        ":52: expected node tag, found '-5'",
    );
    s.sub(
        "elem_tag_duplicate",
        "9 2 3 6 5",
        "8 2 3 6 5",
        ":54: element tag 8 appears twice in $Elements",
    );
    // element types and entities
    s.sub(
        "type_unknown",
        "2 3 3 1\n",
        "2 3 99 1\n",
        ":53: element type 99 is not supported",
    );
    s.sub(
        "type_hexahedron",
        "2 3 3 1\n",
        "2 3 5 1\n",
        "element type 5 (8-node hexahedron) is not supported",
    );
    s.sub(
        "type_tri_for_quad",
        "2 3 3 1\n",
        "2 3 2 1\n",
        ":54: expected $EndElements, found '5'",
    );
    s.sub(
        "entity_dim_bad",
        "2 3 3 1\n",
        "4 3 3 1\n",
        ":53: entity dimension must be 0, 1, 2 or 3, found 4",
    );
    s.sub(
        "node_entity_dim_bad",
        "2 2 0 6\n",
        "7 2 0 6\n",
        ":24: entity dimension must be 0, 1, 2 or 3, found 7",
    );
    s.sub(
        "parametric_flag_bad",
        "2 2 0 6\n",
        "2 2 7 6\n",
        ":24: parametric flag must be 0 or 1, found 7",
    );
    s.sub(
        "entity_undeclared",
        "2 3 3 1\n",
        "2 33 3 1\n",
        ":53: element block of entity 33 (dim 2): the entity is not in $Entities",
    );
    s.sub(
        "entity_physical_unnamed",
        "3 1e0 0e0 0 2e0 1e0 0 1 5 0",
        "3 1e0 0e0 0 2e0 1e0 0 1 9 0",
        "physical group 9 (dim 2) of element 9 has no name in $PhysicalNames",
    );
    s.sub("no_entities", "$Entities\n1 3 2 0\n7 0e0 1e0 0 1 1\n4 0e0 0e0 0 2e0 0e0 0 1 2 0\n5 0e0 1e0 0 2e0 1e0 0 1 3 0\n6 0e0 0e0 0 0e0 1e0 0 1 4 0\n2 0e0 0e0 0 1e0 1e0 0 2 5 6 0\n3 1e0 0e0 0 2e0 1e0 0 1 5 0\n$EndEntities\n", "", "$PhysicalNames but no $Entities section");
    s.sub(
        "entities_twice",
        "$Nodes\n1 6",
        "$Entities\n0 0 0 0\n$EndEntities\n$Nodes\n1 6",
        ":22: second $Entities section",
    );
    // cells
    s.sub(
        "quad_repeated_node",
        "9 2 3 6 5",
        "9 2 3 6 6",
        ":54: element 9 lists node 6 twice",
    );
    s.sub(
        "seg_repeated_node",
        "3 1 2\n",
        "3 1 1\n",
        ":44: element 3 lists node 1 twice",
    );
    s.sub(
        "quad_bowtie",
        "9 2 3 6 5",
        "9 2 3 5 6",
        "cell 9 (Quad4) is inverted or tangled",
    );
    s.sub("quad_collapsed", "1e0 1e0 0\n", "1e0 0e0 0\n", "(Quad4) is");
    s.sub_ok("quad_clockwise", "9 2 3 6 5", "9 5 6 3 2", 6, 9);
    // header
    s.sub(
        "version_4_0",
        "4.1 0 8",
        "4 0 8",
        ":2: unsupported MSH version 4",
    );
    s.sub(
        "version_huge",
        "4.1 0 8",
        "1e999 0 8",
        ":2: unsupported MSH version 1e999",
    );
    s.sub(
        "binary_flag_ascii_body",
        "4.1 0 8\n",
        "4.1 1 8\n",
        "corrupt binary header: expected the integer 1 in binary",
    );
    s.sub(
        "binary_size_4",
        "4.1 0 8",
        "4.1 1 4",
        ":2: binary files with data size 4 are not supported",
    );
    s.sub(
        "end_mismatch",
        "$EndEntities",
        "$EndNodes",
        ":21: expected $EndEntities, found '$EndNodes'",
    );
    s.out
}
