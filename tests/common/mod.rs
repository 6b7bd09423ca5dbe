//! Shared helpers of the integration tests: solve an elastic problem with displacements
//! imposed node by node.
#![allow(dead_code)]

pub mod arctan;
pub mod patches;
pub mod ssnp154_a;

use tribo::assembly::dofs::DofMap;
use tribo::assembly::Assembler;
use tribo::fem::material::{Elastic, Modelisation};
use tribo::fem::solid::{Kinematics, SolidModel};
use tribo::mesh::Mesh;
use tribo::solver::linear::Method;
use tribo::solver::newton::{solve, NewtonSettings};
use tribo::solver::problem::SolidProblem;

pub fn model(m: Modelisation, young: f64, nu: f64) -> SolidModel {
    SolidModel {
        model: m,
        kinematics: Kinematics::Small,
        material: Elastic::new(young, nu, "test").unwrap(),
        thickness: 1.0,
    }
}

/// Solves with `fixed` (dof, value) imposed and external loads `fext`; returns the problem.
pub fn solve_elastic<'m>(
    mesh: &'m Mesh,
    sm: SolidModel,
    fixed: &[(usize, f64)],
    fext: Vec<f64>,
) -> SolidProblem<'m> {
    let cells: Vec<usize> = mesh.cells_of_dim(2).collect();
    let models = vec![sm; cells.len()];
    let mut used = vec![false; 2 * mesh.num_nodes()];
    for &c in &cells {
        for &n in mesh.cell_nodes(c) {
            used[2 * n] = true;
            used[2 * n + 1] = true;
        }
    }
    let dofs = DofMap::new(&used, fixed, &[]).unwrap();
    let asm = Assembler::new(mesh, cells, models, dofs, true).unwrap();
    let mut p = SolidProblem::new(mesh, asm, fext);
    solve(&mut p, &NewtonSettings::default(), Method::Cholesky).unwrap();
    p
}

/// Dofs of all nodes of the given groups, with values from `f(x, y)`.
pub fn impose(mesh: &Mesh, groups: &[&str], f: impl Fn([f64; 2]) -> [f64; 2]) -> Vec<(usize, f64)> {
    let mut out = vec![];
    for g in groups {
        for n in mesh.node_group(g).unwrap() {
            let v = f(mesh.coords[n]);
            out.push((2 * n, v[0]));
            out.push((2 * n + 1, v[1]));
        }
    }
    out
}

/// Least-squares slope of log(err) against log(h).
pub fn fitted_rate(h: &[f64], err: &[f64]) -> f64 {
    let n = h.len() as f64;
    let lx: Vec<f64> = h.iter().map(|v| v.ln()).collect();
    let ly: Vec<f64> = err.iter().map(|v| v.ln()).collect();
    let mx = lx.iter().sum::<f64>() / n;
    let my = ly.iter().sum::<f64>() / n;
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

/// The head of a case file whose mesh the test builds itself (`case::run` takes the mesh
/// apart from the case): a placeholder [mesh] table and one [[material]] per
/// (group, E, nu).
pub fn case_head(materials: &[(&str, f64, f64)]) -> String {
    let mut s = String::from(
        "[mesh]\ngenerator = \"rectangle\"\nwidth = 1.0\nheight = 1.0\nnx = 1\nny = 1\n",
    );
    for (g, e, nu) in materials {
        s.push_str(&format!(
            "[[material]]\ngroup = \"{g}\"\nE = {e:?}\nnu = {nu:?}\n"
        ));
    }
    s
}

/// The tail of a two-body case: the lower body held at its bottom, the upper body's bottom
/// (slave) in contact with the lower body's top (master); more keys of the pair may follow.
pub const HELD_BELOW_CONTACT_ABOVE: &str = r#"
[[displacement]]
group = "LowerBottom"
dx = 0.0
dy = 0.0
[[contact]]
slave = "UpperBottom"
master = "LowerTop"
"#;

/// Bodies side by side in one mesh, their groups prefixed with the given names.
pub fn bodies(parts: &[(&str, &Mesh)]) -> Mesh {
    let mut b = tribo::mesh::MeshBuilder::new("bodies");
    for (prefix, m) in parts {
        b.append(m, |g| format!("{prefix}{g}"));
    }
    b.finish().unwrap()
}

/// A 1 × 0.5 block (5 × 3 Quad4, groups `Upper…`) standing on a foundation `length` long
/// and 1 deep from x = −1 (`nx` × 2 Quad4, groups `Lower…`), both E = 1000, ν = 0.3: the
/// mesh and the head of its case file.
pub fn block_on_foundation(length: f64, nx: usize) -> (Mesh, String) {
    use tribo::mesh::generate::rectangle;
    use tribo::mesh::CellKind;
    let lower = rectangle([-1.0, -1.0], length, 1.0, nx, 2, CellKind::Quad4, 0.0).unwrap();
    let upper = rectangle([0.0, 0.0], 1.0, 0.5, 5, 3, CellKind::Quad4, 0.0).unwrap();
    let mesh = bodies(&[("Lower", &lower), ("Upper", &upper)]);
    let head = case_head(&[("LowerBody", 1000.0, 0.3), ("UpperBody", 1000.0, 0.3)]);
    (mesh, head)
}

/// The block's bottom on the foundation's top with Coulomb friction μ = 0.3 in the given
/// formulation, every point closed at the start (point-to-segment: nodal integration).
pub fn block_contact(formulation: &str) -> String {
    let integration = if formulation == "mortar" {
        ""
    } else {
        "integration = \"nodal\"\n"
    };
    format!(
        "[[contact]]\nslave = \"UpperBottom\"\nmaster = \"LowerTop\"\nformulation = \"{formulation}\"\n\
         initial = \"all\"\nfriction = 0.3\n{integration}"
    )
}

/// Σ over the nodes of `group` of a full-dof vector (reactions, say): (x, y).
pub fn group_sum(mesh: &Mesh, group: &str, values: &[f64]) -> (f64, f64) {
    mesh.node_group(group)
        .unwrap()
        .iter()
        .fold((0.0, 0.0), |(x, y), &n| {
            (x + values[2 * n], y + values[2 * n + 1])
        })
}

/// Bodies in one mesh as `bodies` makes them, but joined at one point: the nodes of the
/// parts at `at` (within 1e-9) become one node, so the mesh is one connected body (cut
/// along the parts' common boundary but for that point).
pub fn bodies_joined_at(parts: &[(&str, &Mesh)], at: [f64; 2]) -> Mesh {
    let mut b = tribo::mesh::MeshBuilder::new("joined bodies");
    let mut joint: Option<usize> = None;
    for (prefix, m) in parts {
        let ids: Vec<usize> = m
            .coords
            .iter()
            .map(|&x| {
                if (x[0] - at[0]).hypot(x[1] - at[1]) <= 1e-9 {
                    *joint.get_or_insert_with(|| b.add_node(x))
                } else {
                    b.add_node(x)
                }
            })
            .collect();
        let first = b.num_cells();
        for c in 0..m.num_cells() {
            let nodes: Vec<usize> = m.cell_nodes(c).iter().map(|&n| ids[n]).collect();
            b.add_cell(m.kind(c), &nodes, (first + c + 1) as u64);
        }
        for (name, cells) in &m.cell_groups {
            for &c in cells {
                b.add_to_cell_group(&format!("{prefix}{name}"), first + c);
            }
        }
        for (name, nodes) in &m.node_groups {
            for &n in nodes {
                b.add_to_node_group(&format!("{prefix}{name}"), ids[n]);
            }
        }
    }
    b.finish().unwrap()
}

/// The slave nodes of contact pair `pair` in a run's outcome as (x, pressure, shear),
/// sorted by x, with the pair's friction coefficient.
pub fn slave_rows(
    mesh: &Mesh,
    out: &tribo::case::Outcome,
    pair: usize,
) -> (f64, Vec<(f64, f64, f64)>) {
    let pressure: std::collections::HashMap<usize, f64> =
        out.contact_pressure[pair].iter().copied().collect();
    let (mu, shear) = &out.contact_shear[pair];
    let mut rows: Vec<(f64, f64, f64)> = shear
        .iter()
        .map(|&(n, t)| (mesh.coords[n][0], pressure[&n], t))
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    (*mu, rows)
}
