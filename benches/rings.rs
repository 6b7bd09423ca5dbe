//! Two concentric quarter rings in contact (a few hundred nodes, non-matching: 24 and 32
//! cells around), the outer one under external pressure in 21 load steps, large
//! kinematics: wall time of each formulation, median of 7 rounds (issue 19: mortar within 1.5× of
//! point-to-segment). Prints the Lamé pressure error too, so a fast wrong answer shows.
//!
//! Run: `cargo bench --bench rings`

use std::time::Instant;
use tribo::case::{run, schema::CaseFile};
use tribo::mesh::generate::ring;
use tribo::mesh::{CellKind, Mesh, MeshBuilder};

const A: f64 = 1.0;
const B: f64 = 1.5;
const C: f64 = 2.0;
const Q: f64 = 2000.0;

fn main() {
    tribo::cli::keep_freed_memory();
    tribo::cli::on_worker_thread(time_rings);
}

fn mesh() -> Mesh {
    let inner = ring(A, B, 3, 24, 90.0, CellKind::Quad4).unwrap();
    let outer = ring(B, C, 3, 32, 90.0, CellKind::Quad4).unwrap();
    let mut b = MeshBuilder::new("rings");
    b.append(&inner, |g| format!("In{g}"));
    b.append(&outer, |g| format!("Out{g}"));
    b.finish().unwrap()
}

fn case(formulation: &str) -> CaseFile {
    let integration = if formulation == "point-to-segment" {
        "integration = \"gauss\"\n"
    } else {
        ""
    };
    let text = format!(
        r#"[mesh]
generator = "unused"
[model]
modelisation = "plane_strain"
kinematics = "large"
[[material]]
group = "InBody"
E = 200000.0
nu = 0.3
[[material]]
group = "OutBody"
E = 200000.0
nu = 0.3
[[displacement]]
group = "InStart"
dy = 0.0
[[displacement]]
group = "OutStart"
dy = 0.0
[[displacement]]
group = "InEnd"
dx = 0.0
[[displacement]]
group = "OutEnd"
dx = 0.0
[[pressure]]
group = "OutOuter"
p = {Q}
[[contact]]
slave = "InOuter"
master = "OutInner"
formulation = "{formulation}"
{integration}[solver]
steps = 21
"#
    );
    toml::from_str(&text).unwrap()
}

/// Contact pressure of rings a–b and b–c of one material under external pressure q with a
/// free bore (plane strain): the thick ring a–c, σ_rr(b).
fn lame() -> f64 {
    let s = Q * C * C / (C * C - A * A);
    s * (1.0 - A * A / (B * B))
}

fn time_rings() {
    let mesh = mesh();
    println!(
        "rings: {} nodes, 21 load steps, large kinematics",
        mesh.num_nodes()
    );
    // (a formulation named on the command line alone: for profiling)
    let only: Option<String> = std::env::args().nth(1).filter(|a| !a.starts_with('-'));
    let formulations: Vec<&str> = ["point-to-segment", "node-to-segment", "mortar"]
        .into_iter()
        .filter(|f| only.as_deref().is_none_or(|o| o == *f))
        .collect();
    let cases: Vec<CaseFile> = formulations.iter().map(|f| case(f)).collect();
    // rounds of one run per formulation, so that the machine's noise falls on all alike
    let mut times: Vec<Vec<f64>> = vec![vec![]; cases.len()];
    let mut outs = vec![];
    for round in 0..7 {
        for (k, c) in cases.iter().enumerate() {
            let t = Instant::now();
            let out = run(c, &mesh, false).unwrap_or_else(|e| panic!("{}: {e}", formulations[k]));
            times[k].push(t.elapsed().as_secs_f64());
            if round == 0 {
                outs.push(out);
            }
        }
    }
    let p = lame();
    let mut base: Option<f64> = None;
    for (k, formulation) in formulations.iter().enumerate() {
        times[k].sort_by(f64::total_cmp);
        let median = times[k][3];
        let out = &outs[k];
        let worst = out.contact_pressure[0]
            .iter()
            .map(|&(_, v)| (v / p - 1.0).abs())
            .fold(0.0f64, f64::max);
        let ratio = base.map_or(1.0, |b| median / b);
        base.get_or_insert(median);
        println!(
            "{formulation:>17}: {median:.3} s (median of 7 rounds; {ratio:.2}× point-to-segment), {} \
             iterations, worst pressure {:.2} % from Lamé",
            out.report.total_iterations,
            100.0 * worst
        );
    }
}
