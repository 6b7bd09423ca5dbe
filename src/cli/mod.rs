//! Command-line interface: one file per subcommand.
//!
//! | file | what |
//! |---|---|
//! | `run/` | `tribo run CASE.toml [-o DIR]`: the outputs, written whole or not at all |
//! | `mesh.rs` | `tribo mesh info`, `mesh convert`, `mesh compare` |
//! | `validate.rs` | `tribo validate`: the SSNP154 stages on built-in or given meshes |
//! | `report.rs` | `tribo validate --report DIR`: report.html with inline SVG plots |
//! | `study.rs` | `tribo study hertz`: SSNP154 refined against Hertz |
//! | `study_refine.rs` | `tribo study refine CASE`: refinement study of any case, Richardson |

mod mesh;
pub mod report;
pub mod run;
pub mod study;
pub mod study_refine;
pub mod validate;

use crate::error::Result;
use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "tribo",
    version,
    about = "Finite-element solver for frictional contact between elastic bodies (2D)"
)]
struct Cli {
    /// Print nothing but errors (no results on stdout, no status line).
    #[arg(short, long, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a case file; writes results.json and result.vtu in the output folder.
    Run {
        case: PathBuf,
        /// Output folder (default: next to the case file, named after it).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Print every load step ("load step k of N") and Newton iteration on stderr.
        #[arg(short, long)]
        verbose: bool,
    },
    /// Mesh tools.
    Mesh {
        #[command(subcommand)]
        command: MeshCommand,
    },
    /// Run the SSNP154 validation.
    Validate {
        /// Folder holding ssnp154a and ssnp154b as .msh or MED .mmed/.med (default:
        /// built-in meshes).
        #[arg(long)]
        meshes: Option<PathBuf>,
        /// With --meshes: read the "msh" or the "med" files (default: .msh if present).
        #[arg(long)]
        mesh_format: Option<String>,
        /// Write report.html (and each plot as SVG + CSV) in this folder.
        #[arg(long)]
        report: Option<PathBuf>,
        /// Write the table as JSON.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Run the modelisations with this contact formulation instead of the reference's.
        #[arg(long)]
        formulation: Option<String>,
        #[arg(short, long)]
        verbose: bool,
    },
    /// Refinement studies.
    Study {
        #[command(subcommand)]
        command: StudyCommand,
    },
}

#[derive(Subcommand)]
enum StudyCommand {
    /// Refinement study of any case: the element size halved per level (a generator's size
    /// or cell counts; a mesh file's cells split 2^k x 2^k); per level every probe and per
    /// contact pair its resultants; observed order, Richardson extrapolation and its error.
    Refine {
        case: PathBuf,
        /// Number of levels (at least 3; a mesh file: at most 5).
        #[arg(long, default_value_t = 3)]
        levels: usize,
        /// Write DIR/refine.json, refine.csv, refine.html and a plot (SVG + CSV) per
        /// quantity (also shown by `validate --report DIR`).
        #[arg(long)]
        report: Option<PathBuf>,
    },
    /// SSNP154 on built-in meshes refined level by level, against the Hertz solution.
    Hertz {
        /// Number of levels (element size at the contact 3 mm, halved at each level).
        #[arg(long, default_value_t = 5)]
        levels: usize,
        /// Contact formulation.
        #[arg(long, default_value = "mortar")]
        formulation: String,
        /// Linear cells (default: quadratic).
        #[arg(long)]
        linear: bool,
        /// "small", "large" or "both".
        #[arg(long, default_value = "both")]
        kinematics: String,
        /// Write the results as JSON.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Write the levels as CSV.
        #[arg(long)]
        csv: Option<PathBuf>,
        /// Write DIR/study.json, DIR/study.csv and log-log plots DIR/study_K.svg (shown by
        /// `validate --report DIR`).
        #[arg(long)]
        report: Option<PathBuf>,
    },
}

#[derive(Subcommand)]
enum MeshCommand {
    /// Counts per cell kind, groups, bounding box, orientation fixes and quality
    /// (FILE: a .msh or .med mesh, or a .toml case whose [mesh] is shown).
    Info {
        file: PathBuf,
        #[arg(long)]
        json: bool,
    },
    /// Converts a mesh between Gmsh MSH 4.1 / 2.2, MED and VTU, keeping its groups.
    Convert {
        input: PathBuf,
        output: PathBuf,
        /// msh41, msh22, med or vtu (default: from the extension of OUTPUT).
        #[arg(long)]
        format: Option<String>,
    },
    /// Splits every cell of a mesh n × n (a triangle into n², a segment into n), keeping
    /// its groups; new nodes follow curved quadratic edges. Output format as for convert.
    Refine {
        input: PathBuf,
        output: PathBuf,
        /// Refinement factor n (1 to 16).
        #[arg(long)]
        split: usize,
        /// msh41, msh22, med or vtu (default: from the extension of OUTPUT).
        #[arg(long)]
        format: Option<String>,
    },
    /// Compares two meshes (any readable format): nodes, cells and groups.
    /// Exit status 0 when they are the same.
    Compare {
        first: PathBuf,
        second: PathBuf,
        /// Node distance tolerance, relative to the bounding-box diagonal.
        #[arg(long, default_value_t = 1e-12)]
        tol: f64,
    },
}

/// Keeps freed memory in the process for reuse. glibc gives the top of its heaps back to the
/// system and serves blocks over 128 KB by fresh mappings, so the buffers of every Newton
/// iteration and every validation row are page-faulted in again, at 3.5 µs per 4 KB page on
/// the benchmark machine (`tribo validate`: 81 000 faults, 25 000 with this). The price: the
/// resident size stays at its peak until exit. One arena for all threads: with one per
/// thread, what a worker thread frees (a body's factor, refactorised on the other core the
/// next time) is kept for that thread alone, and each arena stays at its own peak (SSNP154
/// A set-up at 98k unknowns: 803 MiB resident against 619 with one arena, and as fast).
pub fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets allocator parameters; called before any threads start.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 32 << 20);
        libc::mallopt(libc::M_TRIM_THRESHOLD, i32::MAX);
        libc::mallopt(libc::M_ARENA_MAX, 1);
    }
}

/// Runs `work` on a thread of a pool of one thread per core, so that the caller's thread
/// is not a third one on two cores and each parallel section (dozens per Newton
/// iteration) starts on the spot instead of waking a worker and putting the caller to
/// sleep: SSNP154 rows about 10–20 % faster on the 2-core machine. Without a pool (it
/// could not be started), `work` runs on the caller's thread. The threads get the main
/// thread's usual 8 MiB stack (reserved, not touched).
pub fn on_worker_thread<T: Send>(work: impl FnOnce() -> T + Send) -> T {
    match rayon::ThreadPoolBuilder::new().stack_size(8 << 20).build() {
        Ok(pool) => pool.install(work),
        Err(_) => work(),
    }
}

/// Runs the command line; returns the process exit code.
pub fn main() -> Result<i32> {
    let cli = Cli::parse();
    crate::progress::set_quiet(cli.quiet);
    // (the status line stands in for verbose output: not both)
    let _display = match &cli.command {
        Command::Run { verbose: true, .. } | Command::Validate { verbose: true, .. } => None,
        Command::Run { .. } | Command::Validate { .. } | Command::Study { .. } => {
            Some(crate::progress::start())
        }
        Command::Mesh { .. } => None,
    };
    let quiet = cli.quiet;
    match cli.command {
        Command::Run {
            case,
            output,
            verbose,
        } => run::run(&case, output.as_deref(), verbose && !quiet),
        Command::Mesh {
            command: MeshCommand::Info { file, json },
        } => mesh::info(&file, json),
        Command::Mesh {
            command:
                MeshCommand::Convert {
                    input,
                    output,
                    format,
                },
        } => mesh::convert(&input, &output, format.as_deref()),
        Command::Mesh {
            command:
                MeshCommand::Refine {
                    input,
                    output,
                    split,
                    format,
                },
        } => mesh::refine(&input, &output, split, format.as_deref()),
        Command::Mesh {
            command: MeshCommand::Compare { first, second, tol },
        } => mesh::compare(&first, &second, tol),
        Command::Validate {
            meshes,
            json,
            formulation,
            mesh_format,
            report,
            verbose,
        } => validate::validate(
            meshes.as_deref(),
            json.as_deref(),
            formulation.as_deref(),
            mesh_format.as_deref(),
            report.as_deref(),
            verbose && !quiet,
        ),
        Command::Study {
            command:
                StudyCommand::Refine {
                    case,
                    levels,
                    report,
                },
        } => study_refine::refine(&case, levels, report.as_deref()),
        Command::Study {
            command:
                StudyCommand::Hertz {
                    levels,
                    formulation,
                    linear,
                    kinematics,
                    json,
                    csv,
                    report,
                },
        } => {
            let json = json.or_else(|| report.as_ref().map(|d| d.join("study.json")));
            let csv = csv.or_else(|| report.as_ref().map(|d| d.join("study.csv")));
            use crate::fem::solid::Kinematics;
            let kinematics = match kinematics.as_str() {
                "small" => vec![Kinematics::Small],
                "large" => vec![Kinematics::Large],
                "both" => vec![Kinematics::Small, Kinematics::Large],
                other => {
                    return Err(crate::error::Error::model(format!(
                        "study hertz: --kinematics '{other}' is not one of small, large, both"
                    )))
                }
            };
            study::hertz(&study::Options {
                levels,
                formulation: &formulation,
                quadratic: !linear,
                kinematics,
                json: json.as_deref(),
                csv: csv.as_deref(),
                svg_dir: report.as_deref(),
            })
        }
    }
}
