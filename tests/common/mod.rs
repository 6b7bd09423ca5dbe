//! Shared helpers of the integration tests: solve an elastic problem with displacements
//! imposed node by node.
#![allow(dead_code)]

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

/// Bodies side by side in one mesh, their groups prefixed with the given names.
pub fn bodies(parts: &[(&str, &Mesh)]) -> Mesh {
    let mut b = tribo::mesh::MeshBuilder::new("bodies");
    for (prefix, m) in parts {
        b.append(m, |g| format!("{prefix}{g}"));
    }
    b.finish().unwrap()
}
