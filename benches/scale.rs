//! How SSNP154 contact runs scale with the mesh (issue 23): the A set-up (linear,
//! frictionless) and the D set-up (quadratic, Coulomb 0.1), as `tribo validate` builds them
//! (`ssnp154::contact_case`), with point-to-segment, node-to-segment and mortar, on the
//! built-in meshes with the contact cell size halved every two rows (1.5 · 2^(-k/2) mm),
//! against one elastic solve of the same mesh (bodies glued at B–C: assembly, Cholesky,
//! solve, as `benches/elastic.rs`). At the end, the slope of log time against log unknowns
//! over the rows above FIT_FROM unknowns, per set-up and formulation.
//!
//! Each measurement runs in its own process (this binary run again with a hidden first
//! argument) so that its peak resident size (VmHWM) is its own, and a run that fails or
//! is killed (out of memory) is a row saying so, not the end of the bench.
//!
//! Run: `cargo bench --bench scale [-- MAX_UNKNOWNS] [A] [D] [point-to-segment]
//! [node-to-segment] [mortar]` (default: DEFAULT_MAX unknowns, both set-ups, every
//! formulation).

use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use tribo::case::{self, build_problem, ssnp154};
use tribo::fem::solid::Kinematics;
use tribo::mesh::generate::{ssnp154 as generate, Ssnp154Options};
use tribo::mesh::Mesh;
use tribo::solver::linear::{LinearSolver, Method};

/// Largest mesh of a default run (displacement unknowns): 7–8 minutes on the 2-core
/// machine, of which mortar A at 31k unknowns and mortar D at 34k take 140 and 200 s.
const DEFAULT_MAX: usize = 50_000;
/// The exponent is fitted over the rows from this many unknowns (smaller meshes are
/// dominated by set-up costs).
const FIT_FROM: usize = 15_000;
/// A measurement still running after this long is stopped and reported as such.
const TIME_LIMIT: Duration = Duration::from_secs(600);
/// A measurement whose resident size passes this fraction of the memory available when the
/// bench started is stopped (the machine is shared: mortar A at 98k unknowns passed 16 GB).
const MEMORY_SHARE: f64 = 0.5;
/// The generator's smallest contact cell size; finer meshes split every cell of a coarser
/// one in four (`global_refine`).
const MIN_GENERATED: f64 = 0.02;
/// First argument of a measurement process.
const CHILD: &str = "--scale-measurement";
const SETUPS: [(&str, bool); 2] = [("A", false), ("D", true)];
const FORMULATIONS: [&str; 3] = ["point-to-segment", "node-to-segment", "mortar"];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some(CHILD) {
        // as the `tribo` command does
        tribo::cli::keep_freed_memory();
        let line = tribo::cli::on_worker_thread(|| measure(&args[1..]));
        println!("{line}");
        return;
    }
    if let Err(e) = bench(&args) {
        eprintln!("scale: {e}");
        std::process::exit(2);
    }
}

/// The contact cell size of row k, and how it is made: the generator's size and the number
/// of global refinements after it.
fn size_of_row(k: usize) -> (f64, f64, usize) {
    let size = 1.5 * 0.5f64.powf(k as f64 / 2.0);
    let mut generated = size;
    let mut refine = 0;
    while generated < MIN_GENERATED {
        generated *= 2.0;
        refine += 1;
    }
    (size, generated, refine)
}

fn mesh_of(quadratic: bool, generated: f64, refine: usize) -> tribo::error::Result<Mesh> {
    generate(&Ssnp154Options {
        quadratic,
        size: generated,
        global_refine: refine,
    })
}

// ---------------------------------------------------------------- measurement process

/// One measurement: `elastic SETUP SIZE` or `contact SETUP FORMULATION SIZE`. Returns the
/// result line: `SCALE` and tab-separated key=value pairs, the failure reason last.
fn measure(args: &[String]) -> String {
    let fields = match measure_fields(args) {
        Ok(f) => f,
        Err(e) => vec![("status", "failed".into()), ("reason", e)],
    };
    let mut line = String::from("SCALE");
    for (k, v) in fields {
        let v = v.replace(['\t', '\n', '\r'], " ");
        line.push_str(&format!("\t{k}={v}"));
    }
    line
}

type Fields = Vec<(&'static str, String)>;

fn measure_fields(args: &[String]) -> Result<Fields, String> {
    let bad = || format!("bad measurement arguments {args:?}");
    let (kind, setup) = (args.first().ok_or_else(bad)?, args.get(1).ok_or_else(bad)?);
    let quadratic = SETUPS.iter().find(|s| s.0 == setup).ok_or_else(bad)?.1;
    let k: usize = args.last().and_then(|a| a.parse().ok()).ok_or_else(bad)?;
    let (_, generated, refine) = size_of_row(k);
    let mesh = mesh_of(quadratic, generated, refine).map_err(|e| e.to_string())?;
    let spec = ssnp154::builtin_mesh(quadratic, generated);
    match kind.as_str() {
        "elastic" => elastic(&mesh, spec),
        "contact" => {
            let formulation = args.get(2).ok_or_else(bad)?;
            contact(&mesh, spec, setup, formulation)
        }
        _ => Err(bad()),
    }
}

/// Assembly (with the pattern), Cholesky (analysis and numeric) and one solve of the
/// glued bodies.
fn elastic(mesh: &Mesh, spec: tribo::case::schema::MeshSpec) -> Result<Fields, String> {
    let mut case = ssnp154::glued_case(spec, Kinematics::Small);
    // (a Hertz plot needs a contact)
    case.output.hertz = None;
    let t = Instant::now();
    let solved = || -> tribo::error::Result<usize> {
        let mut p = build_problem(&case, mesh)?;
        let mut fint = vec![0.0; p.u.len()];
        let u = p.u.clone();
        p.asm.assemble(mesh, &u, &mut fint, true)?;
        let mut lin = LinearSolver::new(Method::Cholesky);
        lin.factor(&p.asm.matrix)?;
        let mut rhs = vec![0.0; p.num_free()];
        let mut fext = vec![0.0; p.u.len()];
        p.loading.forces_at(1.0, &mut fext);
        p.asm.dofs.reduce(&fext, &mut rhs);
        lin.solve(&p.asm.matrix, &mut rhs)?;
        Ok(p.num_free())
    };
    let unknowns = solved().map_err(|e| e.to_string())?;
    Ok(vec![
        ("status", "ok".into()),
        ("unknowns", unknowns.to_string()),
        ("time", t.elapsed().as_secs_f64().to_string()),
        ("peak", tribo::memory::peak_resident_mib().to_string()),
    ])
}

/// A contact run as `tribo run` does it (without writing files).
fn contact(
    mesh: &Mesh,
    spec: tribo::case::schema::MeshSpec,
    setup: &str,
    formulation: &str,
) -> Result<Fields, String> {
    if !FORMULATIONS.contains(&formulation) {
        return Err(format!("unknown formulation {formulation}"));
    }
    let c = ssnp154::contact_case(setup, spec, Some(formulation));
    let t = Instant::now();
    // SCALE_VERBOSE=1 prints the Newton iterations (on stderr, as `tribo run` does)
    let verbose = std::env::var_os("SCALE_VERBOSE").is_some_and(|v| v == "1");
    let outcome = case::run_keeping(&c, mesh, verbose);
    let time = t.elapsed().as_secs_f64().to_string();
    let (report, failure) = match &outcome {
        Ok(o) => (Some(&o.report), None),
        Err(f) => (f.report.as_deref(), Some(f.error.to_string())),
    };
    let mut fields: Fields = vec![
        (
            "status",
            if failure.is_none() { "ok" } else { "failed" }.into(),
        ),
        ("time", time),
        ("peak", tribo::memory::peak_resident_mib().to_string()),
    ];
    if let Some(r) = report {
        fields.push(("iterations", r.total_iterations.to_string()));
        fields.push(("factorisations", r.numeric_factorizations.to_string()));
        // where the Newton loop's time went (the rest: set-up, contact search, updates)
        fields.push(("evaluate_s", format!("{:.3}", r.time_evaluate_s)));
        fields.push(("factor_s", format!("{:.3}", r.time_factor_s)));
        fields.push(("solve_s", format!("{:.3}", r.time_solve_s)));
    }
    if let Some(reason) = failure {
        fields.push(("reason", reason));
    }
    Ok(fields)
}

// ---------------------------------------------------------------------- the bench

/// What a measurement process reported, or why it gave nothing.
struct Measured {
    fields: Vec<(String, String)>,
}

impl Measured {
    fn get(&self, key: &str) -> Option<&str> {
        self.fields
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
    fn num(&self, key: &str) -> Option<f64> {
        self.get(key).and_then(|v| v.parse().ok())
    }
    fn ok(&self) -> bool {
        self.get("status") == Some("ok")
    }
    /// Why it failed, for the table (no pipes or line breaks).
    fn why(&self) -> String {
        let reason = self.get("reason").unwrap_or("no reason given");
        let mut s = format!("failed: {}", reason.replace('|', "/"));
        if let (Some(it), Some(t)) = (self.get("iterations"), self.num("time")) {
            s.push_str(&format!(" (after {it} iterations, {t:.1} s)"));
        }
        s
    }
}

/// A /proc value in KiB, as MiB (`VmRSS:` of /proc/PID/status, `MemAvailable:` of
/// /proc/meminfo).
fn proc_mib(file: &str, key: &str) -> Option<f64> {
    let s = std::fs::read_to_string(file).ok()?;
    let line = s.lines().find(|l| l.starts_with(key))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

/// Runs this binary on one measurement and reads its result line; stops it past the time
/// limit or past `memory_limit` MiB resident.
fn run_child(args: &[String], memory_limit: Option<f64>) -> Measured {
    let failed = |reason: String| Measured {
        fields: vec![
            ("status".into(), "failed".into()),
            ("reason".into(), reason),
        ],
    };
    let exe = match std::env::current_exe() {
        Ok(e) => e,
        Err(e) => return failed(format!("cannot find the bench binary: {e}")),
    };
    let mut child = match Command::new(exe)
        .arg(CHILD)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
    {
        Ok(c) => c,
        Err(e) => return failed(format!("cannot start a measurement: {e}")),
    };
    // drained on threads, so that a chatty child never blocks on a full pipe
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            let _ = r.read_to_string(&mut s);
            s
        })
    };
    let out = drain(Box::new(child.stdout.take().expect("piped")));
    let err = drain(Box::new(child.stderr.take().expect("piped")));
    let start = Instant::now();
    let status_file = format!("/proc/{}/status", child.id());
    let status = loop {
        let stop = |child: &mut std::process::Child, why: String| {
            let _ = child.kill();
            let _ = child.wait();
            Err(why)
        };
        match child.try_wait() {
            Ok(Some(s)) => break Ok(s),
            Ok(None) if start.elapsed() > TIME_LIMIT => {
                break stop(
                    &mut child,
                    format!("stopped after {} s", TIME_LIMIT.as_secs()),
                );
            }
            Ok(None) => {
                let rss = proc_mib(&status_file, "VmRSS:");
                if let (Some(rss), Some(limit)) = (rss, memory_limit) {
                    if rss > limit {
                        let t = start.elapsed().as_secs_f64();
                        break stop(
                            &mut child,
                            format!(
                                "stopped at {rss:.0} MiB resident (limit {limit:.0}), {t:.0} s"
                            ),
                        );
                    }
                }
                std::thread::sleep(Duration::from_millis(20));
            }
            Err(e) => break Err(format!("lost the measurement: {e}")),
        }
    };
    let stdout = out.join().unwrap_or_default();
    let stderr = err.join().unwrap_or_default();
    let status = match status {
        Ok(s) => s,
        Err(reason) => return failed(reason),
    };
    if let Some(line) = stdout.lines().find(|l| l.starts_with("SCALE\t")) {
        let fields = line
            .split('\t')
            .skip(1)
            .filter_map(|kv| kv.split_once('='))
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        return Measured { fields };
    }
    // no result line: killed (out of memory) or a panic
    let last = stderr.lines().rev().find(|l| !l.trim().is_empty());
    failed(format!(
        "{}{}",
        exit_text(status),
        last.map(|l| format!(": {l}")).unwrap_or_default()
    ))
}

fn exit_text(status: std::process::ExitStatus) -> String {
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(9) = status.signal() {
            return "killed (signal 9: out of memory?)".into();
        }
        if let Some(s) = status.signal() {
            return format!("killed by signal {s}");
        }
    }
    format!("exited with {status}")
}

struct Options {
    max_unknowns: usize,
    setups: Vec<(&'static str, bool)>,
    formulations: Vec<&'static str>,
}

fn options(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        max_unknowns: DEFAULT_MAX,
        setups: vec![],
        formulations: vec![],
    };
    for a in args {
        if a.starts_with('-') {
            continue; // cargo's --bench
        } else if let Ok(n) = a.parse() {
            o.max_unknowns = n;
        } else if let Some(s) = SETUPS.iter().find(|s| s.0.eq_ignore_ascii_case(a)) {
            o.setups.push(*s);
        } else if let Some(f) = FORMULATIONS.iter().find(|f| **f == a) {
            o.formulations.push(f);
        } else {
            return Err(format!(
                "unknown argument '{a}': expected MAX_UNKNOWNS, a set-up (A, D) or a \
                 formulation ({})",
                FORMULATIONS.join(", ")
            ));
        }
    }
    if o.setups.is_empty() {
        o.setups = SETUPS.to_vec();
    }
    if o.formulations.is_empty() {
        o.formulations = FORMULATIONS.to_vec();
    }
    Ok(o)
}

/// One finished contact row, for the fit.
struct Point {
    setup: &'static str,
    formulation: &'static str,
    unknowns: f64,
    time: f64,
}

fn bench(args: &[String]) -> Result<(), String> {
    let o = options(args)?;
    let start = Instant::now();
    let memory_limit = proc_mib("/proc/meminfo", "MemAvailable:").map(|m| MEMORY_SHARE * m);
    println!(
        "SSNP154 contact runs against one elastic solve of the same mesh, up to {} \
         displacement unknowns; each measurement in its own process, peak = its VmHWM; \
         a measurement is stopped after {} s or at {} MiB resident",
        o.max_unknowns,
        TIME_LIMIT.as_secs(),
        memory_limit.map_or("(unknown)".into(), |m| format!("{m:.0}"))
    );
    println!();
    println!(
        "| set-up | formulation | size mm | unknowns | contact s | Newton it. | num. fact. | \
         elastic s | time ratio | contact MiB | elastic MiB | memory ratio |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut points = vec![];
    for &(setup, quadratic) in &o.setups {
        for k in 0.. {
            let (size, generated, refine) = size_of_row(k);
            // counted in this process (the mesh is dropped before the measurements)
            let nodes = mesh_of(quadratic, generated, refine)
                .map_err(|e| format!("{setup} size {size}: {e}"))?
                .num_nodes();
            if 2 * nodes > o.max_unknowns {
                break;
            }
            let row = k.to_string();
            let el = run_child(&["elastic".into(), setup.into(), row.clone()], memory_limit);
            let unknowns = el.num("unknowns").unwrap_or(2.0 * nodes as f64);
            let size_text = if refine > 0 {
                format!("{size:.4} ({generated:.4} split {refine}×)")
            } else {
                format!("{size:.4}")
            };
            for &formulation in &o.formulations {
                let c = run_child(
                    &[
                        "contact".into(),
                        setup.into(),
                        formulation.into(),
                        row.clone(),
                    ],
                    memory_limit,
                );
                println!(
                    "| {setup} | {formulation} | {size_text} | {unknowns:.0} | {} |",
                    cells(&c, &el)
                );
                if let (true, Some(time)) = (c.ok(), c.num("time")) {
                    points.push(Point {
                        setup,
                        formulation,
                        unknowns,
                        time,
                    });
                }
            }
            if el.ok() {
                if let Some(time) = el.num("time") {
                    points.push(Point {
                        setup,
                        formulation: "elastic",
                        unknowns,
                        time,
                    });
                }
            }
        }
    }
    println!();
    println!("Time exponent (least-squares slope of log time against log unknowns, rows from {FIT_FROM} unknowns):");
    println!();
    println!("| set-up | run | exponent | rows | unknowns |");
    println!("|---|---|---:|---:|---|");
    for &(setup, _) in &o.setups {
        for formulation in o.formulations.iter().copied().chain(["elastic"]) {
            let fit: Vec<(f64, f64)> = points
                .iter()
                .filter(|p| p.setup == setup && p.formulation == formulation)
                .filter(|p| p.unknowns >= FIT_FROM as f64)
                .map(|p| (p.unknowns.ln(), p.time.ln()))
                .collect();
            let slope = slope(&fit).map_or("too few rows".into(), |s| format!("{s:.2}"));
            let range = match (fit.first(), fit.last()) {
                (Some(a), Some(b)) => format!("{:.0}–{:.0}", a.0.exp(), b.0.exp()),
                _ => "–".into(),
            };
            println!(
                "| {setup} | {formulation} | {slope} | {} | {range} |",
                fit.len()
            );
        }
    }
    println!();
    println!("bench wall time {:.0} s", start.elapsed().as_secs_f64());
    Ok(())
}

/// The table cells after `unknowns` of a contact row and its mesh's elastic solve.
fn cells(c: &Measured, el: &Measured) -> String {
    let f = |m: &Measured, key: &str, digits: usize| {
        m.num(key)
            .filter(|v| v.is_finite())
            .map_or("–".into(), |v| format!("{v:.digits$}"))
    };
    let ratio = |key: &str, digits: usize| match (c.ok() && el.ok(), c.num(key), el.num(key)) {
        (true, Some(a), Some(b)) if b > 0.0 => format!("{:.digits$}", a / b),
        _ => "–".into(),
    };
    let contact = if c.ok() {
        [
            f(c, "time", 3),
            f(c, "iterations", 0),
            f(c, "factorisations", 0),
        ]
        .join(" | ")
    } else {
        format!("{} | – | –", c.why())
    };
    let elastic_time = if el.ok() { f(el, "time", 3) } else { el.why() };
    let contact_peak = if c.ok() {
        f(c, "peak", 0)
    } else {
        "–".into()
    };
    [
        contact,
        elastic_time,
        ratio("time", 1),
        contact_peak,
        f(el, "peak", 0),
        ratio("peak", 1),
    ]
    .join(" | ")
}

/// Least-squares slope of y against x, None under two distinct x.
fn slope(p: &[(f64, f64)]) -> Option<f64> {
    let n = p.len() as f64;
    let mx = p.iter().map(|q| q.0).sum::<f64>() / n;
    let my = p.iter().map(|q| q.1).sum::<f64>() / n;
    let sxx: f64 = p.iter().map(|q| (q.0 - mx).powi(2)).sum();
    let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    (p.len() >= 2 && sxx > 1e-12).then(|| sxy / sxx)
}
