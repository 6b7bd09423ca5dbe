//! SSNP154 set-ups A–F on the built-in meshes refined by splitting every cell n × n
//! (`tribo mesh refine --split n`), with the reference's formulation of each row and with
//! mortar (A–D): every run converges, and DY_B stays within 0.3 % of the reference value
//! (the reference's own mesh is coarser than any of these, so the finer meshes move DY_B
//! by their discretisation error, not by more).

use std::path::Path;
use tribo::case::{self, ssnp154};
use tribo::mesh::refine::split;

fn check(n: usize) {
    let mut worst: f64 = 0.0;
    for &(id, quadratic, dy_ref, _) in &ssnp154::REFERENCES {
        let spec = ssnp154::builtin_mesh(quadratic, 1.5);
        let base = case::build_mesh(&spec, Path::new("")).unwrap();
        let mesh = split(&base, n).unwrap();
        let (_, nts) = ssnp154::row_kind(id);
        let formulations: &[Option<&str>] = if nts {
            &[None]
        } else {
            &[None, Some("mortar")]
        };
        for &f in formulations {
            let c = ssnp154::contact_case(id, spec.clone(), f);
            let out =
                case::run(&c, &mesh, false).unwrap_or_else(|e| panic!("{id} {f:?} split {n}: {e}"));
            let dy = out.probes.iter().find(|p| p.0 == "DY_B").unwrap().1;
            let e = (dy / dy_ref - 1.0).abs();
            println!(
                "split {n} {id} {}: {} nodes, DY_B {dy:.7} ({:.4} %), {} iterations",
                c.contact[0].formulation,
                mesh.num_nodes(),
                100.0 * e,
                out.report.total_iterations
            );
            assert!(out.report.steps.iter().all(|s| s.converged));
            assert!(e < 3e-3, "{id} {f:?} split {n}: DY_B {dy} vs {dy_ref}");
            worst = worst.max(e);
        }
    }
    println!(
        "split {n}: DY_B at most {:.4} % from the reference",
        100.0 * worst
    );
}

#[test]
fn ssnp154_on_meshes_split_2x2() {
    check(2);
}

#[test]
fn ssnp154_on_meshes_split_3x3() {
    check(3);
}

#[test]
fn ssnp154_on_meshes_split_4x4() {
    check(4);
}
