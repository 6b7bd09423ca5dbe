//! Unit tests of the reader: fixtures (BASE41, BASE22 and BASE41 in binary), the meshes
//! they read to.

use super::*;

mod errors;
mod fuzz;

/// Quad4 + Tri3 on a surface with two physical groups, Seg2 on a curve, points; a
/// surface and a point without physical groups (their elements are dropped), a
/// parametric node block, sparse node tags, a skipped section.
const BASE41: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
4
0 3 "Corner"
1 4 "Bottom edge"
2 1 "Plate"
2 2 "All"
$EndPhysicalNames
$Entities
2 1 2 0
1 0 0 0 1 3
2 2 0 0 0
1 0 0 0 2 0 0 1 4 2 1 -2
1 0 0 0 2 1 0 2 1 2 1 1
2 1 0 0 2 1 0 0 1 1
$EndEntities
$Comments
skipped: $Nodes $Elements 1 2 3
$EndComments
$Nodes
3 6 10 60
0 1 0 1
10
0 0 0
1 1 1 1
20
1 0 0 0.5
2 1 0 4
30
40
50
60
1 1 0
0 1 0
2 0 0
2 1 0
$EndNodes
$Elements
6 7 1 7
0 1 15 1
1 10
0 2 15 1
2 50
1 1 1 2
3 10 20
4 20 50
2 1 3 1
5 10 20 30 40
2 1 2 1
6 20 50 30
2 2 2 1
7 50 60 30
$EndElements
"#;

/// MSH 2.2: Point1, Seg3, a clockwise Quad8, Tri6; elements without a physical
/// group; a skipped $NodeData section.
const BASE22: &str = r#"$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
3
0 3 "Tip"
1 1 "Edge"
2 2 "Body"
$EndPhysicalNames
$Nodes
11
1 0 0 0
2 2 0 0
3 2 2 0
4 0 2 0
5 1 0 0
6 2 1 0
7 1 2 0
8 0 1 0
20 4 0 0
21 3 0 0
22 3 1 0
$EndNodes
$NodeData
1
"ignored view"
1
0.0
3
0
1
1
1 5.0
$EndNodeData
$Elements
6
1 15 2 3 1 1
2 8 2 1 1 1 2 5
3 16 2 2 1 1 4 3 2 8 7 6 5
4 9 2 2 2 2 20 3 21 22 6
5 1 0 1 2
6 1 2 0 1 3 4
$EndElements
"#;

/// Test-only writer of the MSH 4.1 binary encoding (little-endian, 8-byte size_t).
#[derive(Default)]
struct Bin {
    buf: Vec<u8>,
}

impl Bin {
    fn text(&mut self, s: &str) -> &mut Self {
        self.buf.extend_from_slice(s.as_bytes());
        self
    }
    fn int(&mut self, v: i32) -> &mut Self {
        self.buf.extend_from_slice(&v.to_le_bytes());
        self
    }
    fn size(&mut self, v: u64) -> &mut Self {
        self.buf.extend_from_slice(&v.to_le_bytes());
        self
    }
    fn reals(&mut self, v: &[f64]) -> &mut Self {
        for x in v {
            self.buf.extend_from_slice(&x.to_le_bytes());
        }
        self
    }
    fn at(&self) -> usize {
        self.buf.len()
    }
}

/// Byte offsets of a few fields of the binary test mesh.
struct Marks {
    /// The 4-byte integer 1 of $MeshFormat.
    one: usize,
    /// The tag of node 30 (in the third node block).
    node_tag_30: usize,
    /// Node 30 in the nodes of element 5 (the quad).
    quad_node_30: usize,
    /// The element type of the quad block.
    quad_type: usize,
}

/// BASE41 in the binary encoding.
fn base41_binary() -> (Vec<u8>, Marks) {
    let mut w = Bin::default();
    w.text("$MeshFormat\n4.1 1 8\n");
    let one = w.at();
    w.int(1).text("\n$EndMeshFormat\n");
    w.text("$PhysicalNames\n4\n0 3 \"Corner\"\n1 4 \"Bottom edge\"\n");
    w.text("2 1 \"Plate\"\n2 2 \"All\"\n$EndPhysicalNames\n");
    w.text("$Entities\n").size(2).size(1).size(2).size(0);
    w.int(1).reals(&[0., 0., 0.]).size(1).int(3);
    w.int(2).reals(&[2., 0., 0.]).size(0);
    w.int(1).reals(&[0., 0., 0., 2., 0., 0.]).size(1).int(4);
    w.size(2).int(1).int(-2);
    w.int(1)
        .reals(&[0., 0., 0., 2., 1., 0.])
        .size(2)
        .int(1)
        .int(2);
    w.size(1).int(1);
    w.int(2)
        .reals(&[1., 0., 0., 2., 1., 0.])
        .size(0)
        .size(1)
        .int(1);
    w.text("\n$EndEntities\n");
    w.text("$Comments\nskipped: $Nodes $Elements 1 2 3\n$EndComments\n");
    w.text("$Nodes\n").size(3).size(6).size(10).size(60);
    w.int(0).int(1).int(0).size(1).size(10).reals(&[0., 0., 0.]);
    w.int(1)
        .int(1)
        .int(1)
        .size(1)
        .size(20)
        .reals(&[1., 0., 0., 0.5]);
    w.int(2).int(1).int(0).size(4);
    let node_tag_30 = w.at();
    w.size(30).size(40).size(50).size(60);
    w.reals(&[1., 1., 0., 0., 1., 0., 2., 0., 0., 2., 1., 0.]);
    w.text("\n$EndNodes\n");
    w.text("$Elements\n").size(6).size(7).size(1).size(7);
    w.int(0).int(1).int(15).size(1).size(1).size(10);
    w.int(0).int(2).int(15).size(1).size(2).size(50);
    w.int(1).int(1).int(1).size(2);
    w.size(3).size(10).size(20).size(4).size(20).size(50);
    w.int(2).int(1);
    let quad_type = w.at();
    w.int(3).size(1).size(5).size(10).size(20);
    let quad_node_30 = w.at();
    w.size(30).size(40);
    w.int(2)
        .int(1)
        .int(2)
        .size(1)
        .size(6)
        .size(20)
        .size(50)
        .size(30);
    w.int(2)
        .int(2)
        .int(2)
        .size(1)
        .size(7)
        .size(50)
        .size(60)
        .size(30);
    w.text("\n$EndElements\n");
    let marks = Marks {
        one,
        node_tag_30,
        quad_node_30,
        quad_type,
    };
    (w.buf, marks)
}

fn ok(text: &str) -> Mesh {
    parse(text.as_bytes(), "t.msh").unwrap()
}

fn err(bytes: &[u8]) -> String {
    match parse(bytes, "t.msh") {
        Ok(_) => panic!("parse succeeded"),
        Err(e) => e.to_string(),
    }
}

/// 1-based line of the first occurrence of `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    let i = text.find(needle).expect("needle not in text");
    text[..i].matches('\n').count() + 1
}

/// `text` up to and including the first occurrence of `needle`.
fn cut_after<'t>(text: &'t str, needle: &str) -> &'t str {
    &text[..text.find(needle).expect("needle not in text") + needle.len()]
}

fn replace_once(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "'{from}' must occur once");
    text.replacen(from, to, 1)
}

fn groups(mesh: &Mesh) -> Vec<(&str, Vec<usize>)> {
    mesh.cell_groups
        .iter()
        .map(|(k, v)| (k.as_str(), v.clone()))
        .collect()
}

fn check_base41(mesh: &Mesh) {
    assert_eq!(
        mesh.coords,
        vec![[0., 0.], [1., 0.], [1., 1.], [0., 1.], [2., 0.], [2., 1.]]
    );
    let cells: Vec<(CellKind, Vec<usize>)> = (0..mesh.num_cells())
        .map(|c| (mesh.kind(c), mesh.cell_nodes(c).to_vec()))
        .collect();
    assert_eq!(
        cells,
        vec![
            (CellKind::Point1, vec![0]),
            (CellKind::Seg2, vec![0, 1]),
            (CellKind::Seg2, vec![1, 4]),
            (CellKind::Quad4, vec![0, 1, 2, 3]),
            (CellKind::Tri3, vec![1, 4, 2]),
        ]
    );
    assert_eq!(
        groups(mesh),
        vec![
            ("All", vec![3, 4]),
            ("Bottom edge", vec![1, 2]),
            ("Corner", vec![0]),
            ("Plate", vec![3, 4]),
        ]
    );
    assert!(mesh.node_groups.is_empty());
    assert_eq!(mesh.reoriented, 0);
    assert_eq!(mesh.single_node("Corner").unwrap(), 0);
    assert_eq!(mesh.group_dim("Bottom edge"), Some(1));
}

#[test]
fn ascii_41() {
    check_base41(&ok(BASE41));
    // CRLF line ends and extra blank lines are fine.
    check_base41(&ok(&BASE41.replace('\n', "\r\n\r\n")));
}

#[test]
fn binary_41() {
    let (bytes, _) = base41_binary();
    let mesh = parse(&bytes, "b.msh").unwrap();
    check_base41(&mesh);
}

#[test]
fn ascii_22_with_quadratic_cells() {
    let mesh = ok(BASE22);
    assert_eq!(mesh.num_nodes(), 11);
    assert_eq!(mesh.coords[8], [4., 0.]);
    assert_eq!(mesh.coords[10], [3., 1.]);
    let cells: Vec<(CellKind, Vec<usize>)> = (0..mesh.num_cells())
        .map(|c| (mesh.kind(c), mesh.cell_nodes(c).to_vec()))
        .collect();
    assert_eq!(
        cells,
        vec![
            (CellKind::Point1, vec![0]),
            (CellKind::Seg3, vec![0, 1, 4]),
            // Given clockwise (0, 3, 2, 1, 7, 6, 5, 4), reordered.
            (CellKind::Quad8, vec![0, 1, 2, 3, 4, 5, 6, 7]),
            (CellKind::Tri6, vec![1, 8, 2, 9, 10, 5]),
        ]
    );
    assert_eq!(mesh.reoriented, 1);
    assert_eq!(
        groups(&mesh),
        vec![("Body", vec![2, 3]), ("Edge", vec![1]), ("Tip", vec![0]),]
    );
}

#[test]
fn clockwise_quad_is_reoriented_and_no_groups_keep_all_cells() {
    let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n\
                1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n\
                $Elements\n1 1 1 1\n2 1 3 1\n1 1 4 3 2\n$EndElements\n";
    let mesh = ok(text);
    assert_eq!(mesh.num_cells(), 1);
    assert_eq!(mesh.kind(0), CellKind::Quad4);
    assert_eq!(mesh.cell_nodes(0), &[0, 1, 2, 3]);
    assert_eq!(mesh.reoriented, 1);
    // the cell is in no physical group: it forms the default group
    let groups: Vec<(&String, &Vec<usize>)> = mesh.cell_groups.iter().collect();
    assert_eq!(
        groups,
        [(&crate::mesh::DEFAULT_GROUP.to_string(), &vec![0])]
    );
}

#[test]
fn tiny_z_is_ignored() {
    let text = replace_once(BASE41, "2 1 0\n$EndNodes", "2 1 1e-15\n$EndNodes");
    check_base41(&ok(&text));
}
