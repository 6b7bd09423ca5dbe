//! 2D cells in no group (issue 21 item 5): every reader (MSH 4.1, MSH 2.2, MED, VTU) puts
//! them in the group `ungrouped`, the name `mesh convert --format msh22` writes; a single
//! [[material]] without `group` covers the whole mesh; a mesh group already named
//! `ungrouped` beside such cells is an error naming the file.

use tribo::case::{run, schema::CaseFile};
use tribo::mesh::generate::rectangle;
use tribo::mesh::{med, med_write, CellKind, Mesh, MeshBuilder, DEFAULT_GROUP};

/// Two triangles on the unit square, no physical group at all.
const MSH22: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n\
3 1 1 0\n4 0 1 0\n$EndNodes\n$Elements\n2\n1 2 2 0 1 1 2 3\n2 2 2 0 1 1 3 4\n$EndElements\n";

/// The same in MSH 4.1: one surface entity without physical tags.
const MSH41: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 1 0\n\
1 0 0 0 1 1 0 0 0\n$EndEntities\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n\
0 1 0\n$EndNodes\n$Elements\n1 2 1 2\n2 1 2 2\n1 1 2 3\n2 1 3 4\n$EndElements\n";

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("tribo-ungrouped-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// A 4 × 2 Quad4 rectangle 2 × 1 whose 2D cells lost their group (edge groups kept).
fn bare_rectangle() -> Mesh {
    let mut m = rectangle([0.0, 0.0], 2.0, 1.0, 4, 2, CellKind::Quad4, 0.0).unwrap();
    assert!(m.cell_groups.remove("Body").is_some());
    m
}

fn assert_default_group(m: &Mesh, what: &str) {
    let all: Vec<usize> = m.cells_of_dim(2).collect();
    assert!(!all.is_empty(), "{what}");
    assert_eq!(m.cell_groups.get(DEFAULT_GROUP), Some(&all), "{what}");
}

#[test]
fn every_reader_puts_ungrouped_cells_in_the_default_group() {
    assert_eq!(DEFAULT_GROUP, tribo::mesh::gmsh_write::UNGROUPED);
    let m = tribo::mesh::gmsh::parse(MSH22.as_bytes(), "t22.msh").unwrap();
    assert_default_group(&m, "MSH 2.2");
    let m = tribo::mesh::gmsh::parse(MSH41.as_bytes(), "t41.msh").unwrap();
    assert_default_group(&m, "MSH 4.1");
    let bare = bare_rectangle();
    let back = med::parse(med_write::to_bytes(&bare, "m").unwrap(), "t.med").unwrap();
    assert_default_group(&back, "MED");
    assert!(
        back.cell_groups.contains_key("Right"),
        "MED keeps the edge groups"
    );
    let p = tmp("bare.vtu");
    tribo::post::vtu::write_mesh(&p, &bare).unwrap();
    let back = tribo::mesh::read(&p).unwrap();
    assert_default_group(&back, "VTU");
    // cells that do have a group are left alone: no default group
    let whole = rectangle([0.0, 0.0], 2.0, 1.0, 4, 2, CellKind::Quad4, 0.0).unwrap();
    assert!(!whole.cell_groups.contains_key(DEFAULT_GROUP));
}

#[test]
fn one_material_without_group_covers_the_whole_mesh() {
    // a MED file whose cells have no group, pulled by a traction: uniform stress, exact
    let p = tmp("pull.med");
    med_write::write(&p, &bare_rectangle(), "m").unwrap();
    let (e, nu, s) = (1000.0, 0.3, 10.0);
    let text = format!(
        r#"
[mesh]
file = "{}"
[[material]]
E = {e:?}
nu = {nu:?}
[[displacement]]
group = "Left"
dx = 0.0
[[displacement]]
group = "BottomLeft"
dy = 0.0
[[traction]]
group = "Right"
tx = {s:?}
"#,
        p.display()
    );
    let case: CaseFile = toml::from_str(&text).unwrap();
    assert!(case.material[0].group.is_none());
    let mesh = tribo::case::build_mesh(&case.mesh, std::path::Path::new("")).unwrap();
    let out = run(&case, &mesh, false).unwrap();
    // plane strain, σxx = s, σyy = 0: u = (1 − ν²) s x / E, v = −ν (1 + ν) s y / E
    let (exx, eyy) = ((1.0 - nu * nu) * s / e, -nu * (1.0 + nu) * s / e);
    let mut worst = 0.0f64;
    for (n, x) in mesh.coords.iter().enumerate() {
        worst = worst
            .max((out.u[2 * n] - exx * x[0]).abs())
            .max((out.u[2 * n + 1] - eyy * x[1]).abs());
    }
    assert!(worst <= 1e-12 * exx * 2.0, "displacement off by {worst}");
    for st in &out.stress {
        assert!(
            (st[0] - s).abs() <= 1e-9 * s && st[1].abs() <= 1e-9 * s,
            "{st:?}"
        );
    }
    // two materials, one without group: refused
    let two = text.replace(
        "[[material]]\n",
        "[[material]]\ngroup = \"ungrouped\"\nE = 1.0\nnu = 0.3\n[[material]]\n",
    );
    let case: CaseFile = toml::from_str(&two).unwrap();
    let err = run(&case, &mesh, false).err().unwrap().to_string();
    assert_eq!(
        err,
        "[[material]] 2 has no group: a material without a group covers the whole mesh, so it \
         must be the only one; give each of the 2 materials its group"
    );
    // and the default group is a group like any other
    let named = text.replace("[[material]]\n", "[[material]]\ngroup = \"ungrouped\"\n");
    let case: CaseFile = toml::from_str(&named).unwrap();
    let again = run(&case, &mesh, false).unwrap();
    assert_eq!(again.u, out.u);
}

#[test]
fn a_mesh_group_named_like_the_default_group_is_a_clash() {
    let mut b = MeshBuilder::new("clash.msh");
    let r = rectangle([0.0, 0.0], 1.0, 1.0, 2, 1, CellKind::Quad4, 0.0).unwrap();
    b.append(&r, |g| {
        if g == "Bottom" {
            DEFAULT_GROUP.into()
        } else {
            g.into()
        }
    });
    // the appended cells keep their group Body: no clash yet
    assert!(b.finish().is_ok());
    let mut bare = bare_rectangle();
    let bottom = bare.cell_groups.remove("Bottom").unwrap();
    bare.cell_groups.insert(DEFAULT_GROUP.into(), bottom);
    let p = tmp("clash.vtu");
    tribo::post::vtu::write_mesh(&p, &bare).unwrap();
    let e = tribo::mesh::read(&p).err().unwrap().to_string();
    assert!(
        e.ends_with(
            "8 2D cells (cell 1 first) are in no group and would form the default group \
             'ungrouped', but the mesh already has a group named 'ungrouped'; put those cells \
             in a group or rename that group"
        ),
        "{e}"
    );
    assert!(e.contains("clash.vtu"), "{e}");
}
