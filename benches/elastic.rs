//! Elastic solve of the built-in SSNP154 geometry, bodies glued at B–C, at growing sizes:
//! time of assembly, symbolic + numeric Cholesky, numeric refactorisation, solve, and the
//! process peak memory. Also times reading the reference meshes when ../shared is present.
//!
//! Run: `cargo bench --bench elastic [-- MAX_DOFS]` (default up to ~1.4M dofs).

use std::path::Path;
use std::time::Instant;
use tribo::case::{build_problem, ssnp154};
use tribo::fem::solid::Kinematics;
use tribo::mesh::generate::{ssnp154 as generate, Ssnp154Options};
use tribo::solver::linear::{LinearSolver, Method};

fn main() {
    // as the `tribo` command does
    tribo::cli::keep_freed_memory();
    tribo::cli::on_worker_thread(time_elastic_solves);
}

fn time_elastic_solves() {
    let max_dofs: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(1_500_000);
    for file in ["ssnp154a.msh", "ssnp154b.msh"] {
        let p = Path::new("../shared/ssnp154").join(file);
        if p.exists() {
            let mut best = f64::MAX;
            for _ in 0..10 {
                let t = Instant::now();
                let m = tribo::mesh::read(&p).unwrap();
                best = best.min(t.elapsed().as_secs_f64());
                assert!(m.num_nodes() > 0);
            }
            println!("read {file}: {:.2} ms (best of 10)", best * 1e3);
        }
    }
    println!(
        "{:>9} {:>10} {:>9} {:>10} {:>10} {:>10} {:>9} {:>10} {:>10}",
        "dofs",
        "nnz",
        "mesh s",
        "assembly s",
        "factor s",
        "refactor s",
        "solve s",
        "total s",
        "peak MiB"
    );
    for (size, refine) in [
        (1.5, 0),
        (1.5, 1),
        (1.5, 2),
        (1.5, 3),
        (1.5, 4),
        (6.0, 5),
        (3.0, 5),
        (2.0, 5),
        (1.5, 5),
    ] {
        let t = Instant::now();
        let mesh = generate(&Ssnp154Options {
            quadratic: false,
            size,
            global_refine: refine,
        })
        .unwrap();
        let t_mesh = t.elapsed().as_secs_f64();
        if 2 * mesh.num_nodes() > max_dofs {
            continue;
        }
        let mut case = ssnp154::glued_case(ssnp154::builtin_mesh(false, size), Kinematics::Small);
        // (a Hertz plot needs a contact: the check of the case refuses one without)
        case.output.hertz = None;
        let t0 = Instant::now();
        let mut p = build_problem(&case, &mesh).unwrap();
        let mut fint = vec![0.0; p.u.len()];
        let u = p.u.clone();
        p.asm.assemble(&mesh, &u, &mut fint, true).unwrap();
        let t_asm = t0.elapsed().as_secs_f64();
        let mut lin = LinearSolver::new(Method::Cholesky);
        let t1 = Instant::now();
        lin.factor(&p.asm.matrix).unwrap();
        let t_fac = t1.elapsed().as_secs_f64();
        let t2 = Instant::now();
        lin.factor(&p.asm.matrix).unwrap();
        let t_refac = t2.elapsed().as_secs_f64();
        let mut rhs = vec![0.0; p.num_free()];
        let mut fext = vec![0.0; p.u.len()];
        p.loading.forces_at(1.0, &mut fext);
        p.asm.dofs.reduce(&fext, &mut rhs);
        let t3 = Instant::now();
        lin.solve(&p.asm.matrix, &mut rhs).unwrap();
        let t_solve = t3.elapsed().as_secs_f64();
        println!(
            "{:>9} {:>10} {:>9.3} {:>10.3} {:>10.3} {:>10.3} {:>9.3} {:>10.3} {:>10.0}",
            p.num_free(),
            p.asm.matrix.nnz(),
            t_mesh,
            t_asm,
            t_fac,
            t_refac,
            t_solve,
            t_asm + t_fac + t_solve,
            tribo::memory::peak_resident_mib()
        );
    }
}
