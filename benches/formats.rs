//! Mesh reading and result writing (median and min of 20 runs): the reference meshes of
//! ../shared/ssnp154 as MSH and MED (when present, else built-in meshes written to both
//! formats), and the VTU of the SSNP154 B result (quadratic reference mesh).
//!
//! Run: `cargo bench --bench formats`

use std::path::{Path, PathBuf};
use std::time::Instant;
use tribo::case::{self, ssnp154};
use tribo::post::result_vtu::{write_state, Setting, State};

fn timed(mut f: impl FnMut()) -> (f64, f64) {
    let mut t: Vec<f64> = (0..20)
        .map(|_| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    (t[10], t[0])
}

fn main() {
    // as the `tribo` command does
    tribo::cli::keep_freed_memory();
    tribo::cli::on_worker_thread(time_formats);
}

fn time_formats() {
    let shared = Path::new("../shared/ssnp154");
    let tmp = std::env::temp_dir().join(format!("tribo-bench-formats-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let mut files: Vec<PathBuf> = vec![];
    if shared.exists() {
        for f in [
            "ssnp154a.msh",
            "ssnp154a.mmed",
            "ssnp154b.msh",
            "ssnp154b.mmed",
        ] {
            files.push(shared.join(f));
        }
    } else {
        for quadratic in [false, true] {
            let spec = ssnp154::builtin_mesh(quadratic, 1.5);
            let mesh = case::build_mesh(&spec, Path::new("")).unwrap();
            let stem = if quadratic { "builtin-b" } else { "builtin-a" };
            let (msh, med) = (
                tmp.join(format!("{stem}.msh")),
                tmp.join(format!("{stem}.med")),
            );
            tribo::mesh::gmsh_write::write(&msh, &mesh, tribo::mesh::gmsh_write::MshVersion::V41)
                .unwrap();
            tribo::mesh::med_write::write(&med, &mesh, stem).unwrap();
            files.extend([msh, med]);
        }
    }
    for f in &files {
        let (med, min) = timed(|| {
            tribo::mesh::read(f).unwrap();
        });
        println!(
            "read  {:<40} median {med:6.2} ms (min {min:6.2})",
            f.display()
        );
    }
    let quad = files
        .iter()
        .find(|f| f.display().to_string().contains("b.msh"))
        .unwrap();
    let mut spec = ssnp154::builtin_mesh(true, 1.5);
    spec.generator = None;
    // a mesh file takes no generator keys
    spec.size = None;
    spec.quadratic = false;
    spec.file = Some(quad.display().to_string());
    let mesh = case::build_mesh(&spec, Path::new("")).unwrap();
    let c = ssnp154::contact_case("B", spec, None);
    let out = case::run(&c, &mesh, false).unwrap();
    let materials: Vec<Option<String>> = c.material.iter().map(|m| m.group.clone()).collect();
    let setting = Setting {
        mesh: &mesh,
        material_groups: &materials,
    };
    let state = State {
        u: &out.u,
        reactions: &out.reactions,
        stress: &out.stress,
        pk2: out.pk2.as_deref(),
        contact: &out.contact,
        multipliers: &out.contact_multipliers,
    };
    let path = tmp.join("result.vtu");
    let (med, min) = timed(|| write_state(&path, &setting, &state).unwrap());
    let size = std::fs::metadata(&path).unwrap().len();
    println!(
        "write result.vtu of B ({} nodes, {:.1} MB)       median {med:6.2} ms (min {min:6.2})",
        mesh.num_nodes(),
        size as f64 / 1e6
    );
    let _ = std::fs::remove_dir_all(&tmp);
}
