//! Memory estimates, checked before big allocations whose size the user chooses (generated
//! meshes, `mesh refine --split`, the assembly and factorisation of a model): a request
//! beyond the memory available is an error naming the entry and the estimate, not an
//! allocation abort or minutes of swapping followed by a misleading solver failure.
//!
//! Available memory: the least of `MemAvailable` (/proc/meminfo), the room left under a
//! cgroup (v2) limit and the address-space limit (`ulimit -v`); the environment variable
//! `TRIBO_MEMORY_LIMIT` (bytes, or with a K, M or G suffix) replaces them all. Where none
//! can be read, nothing is checked.
//!
//! The per-unknown figures are peak resident sizes measured with `/usr/bin/time -v` on
//! `tribo run` (2-core machine, faer Cholesky / saddle-point LDLᵀ), rounded up:
//!
//! | model                                   | unknowns | peak RSS | per unknown |
//! |-----------------------------------------|---------:|---------:|------------:|
//! | rectangle 400×400 Tri3, elastic         |  321 602 |   528 MB |      1.6 KB |
//! | rectangle 400×400 Quad4, elastic        |  321 602 |   552 MB |      1.7 KB |
//! | rectangle 200×200 Quad8, elastic        |  241 602 |   538 MB |      2.2 KB |
//! | rectangle 400×400 Quad8, elastic        |  963 202 |  2340 MB |      2.4 KB |
//! | SSNP154 C, size 0.1 (point-to-segment, friction) | 30 610 | 404 MB |   13 KB |
//! | SSNP154 C, size 0.05                    |   97 684 |  1043 MB |       11 KB |
//! | SSNP154 A, size 0.1 (point-to-segment)  |   30 610 |   387 MB |       13 KB |
//! | SSNP154 E, size 0.1 (node-to-segment)   |   30 610 |   367 MB |       12 KB |
//! | SSNP154 C, size 0.1, mortar             |   30 610 |   257 MB |      8.4 KB |
//! | disc pair, size 0.02, mortar, small     |   42 744 |   174 MB |      4.1 KB |
//! | `mesh refine --split 8` to 960k nodes, 989k cells  | — | 315 MB | —      |

use crate::error::{Error, Result};

/// Resident size of the program before any model (binary, thread stacks, allocator).
const BASE: u64 = 40 << 20;
/// Bytes per unknown of an assembled and factorised model (see the table above).
const PER_DOF_LINEAR: u64 = 2_000;
const PER_DOF_QUADRATIC: u64 = 2_600;
const PER_DOF_CONTACT: u64 = 14_000;
const PER_DOF_MORTAR: u64 = 8_000;
/// Bytes per kept converged state and unknown (displacements, nodal stresses, history).
const PER_DOF_STATE: u64 = 48;

/// Contact in a model: mortar needs less than the pointwise formulations (measured).
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Contact {
    None,
    Mortar,
    Pointwise,
}

/// What a model to solve is made of, for its estimate.
pub struct Model {
    pub nodes: usize,
    pub quadratic: bool,
    pub contact: Contact,
    /// Converged states kept in memory for the output (1 without a history).
    pub kept_states: usize,
}

/// Estimated peak bytes of assembling and solving `m`.
pub fn solve_bytes(m: &Model) -> u64 {
    let dofs = 2 * m.nodes as u64;
    let per = match (m.contact, m.quadratic) {
        (Contact::Pointwise, _) => PER_DOF_CONTACT,
        (Contact::Mortar, _) => PER_DOF_MORTAR,
        (Contact::None, true) => PER_DOF_QUADRATIC,
        (Contact::None, false) => PER_DOF_LINEAR,
    };
    let states = (m.kept_states as u64).saturating_mul(PER_DOF_STATE);
    BASE.saturating_add(dofs.saturating_mul(per.saturating_add(states)))
}

/// Estimated peak bytes of making a mesh of `nodes` nodes and `cells` cells of up to
/// `nodes_per_cell` nodes (coordinates, connectivity, groups, the builders' maps).
pub fn mesh_bytes(nodes: u64, cells: u64, nodes_per_cell: usize) -> u64 {
    BASE.saturating_add(nodes.saturating_mul(180))
        .saturating_add(cells.saturating_mul(8 * nodes_per_cell as u64 + 120))
}

/// Bytes available to this process, and where the figure comes from.
pub fn available() -> Option<(u64, &'static str)> {
    if let Ok(v) = std::env::var("TRIBO_MEMORY_LIMIT") {
        return parse_size(&v).map(|b| (b, "TRIBO_MEMORY_LIMIT"));
    }
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok();
    let avail = meminfo.as_deref().and_then(|m| {
        m.lines()
            .find_map(|l| l.strip_prefix("MemAvailable:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .map(|kb| kb * 1024)
    });
    let read = |f: &str| -> Option<u64> {
        std::fs::read_to_string(format!("/sys/fs/cgroup/{f}"))
            .ok()?
            .trim()
            .parse()
            .ok()
    };
    // "max" (no limit) does not parse: no cgroup figure then
    let cgroup =
        read("memory.max").map(|max| max.saturating_sub(read("memory.current").unwrap_or(0)));
    [
        (avail, "MemAvailable"),
        (cgroup, "the cgroup memory limit"),
        (address_space(), "the address-space limit, ulimit -v"),
    ]
    .into_iter()
    .filter_map(|(v, source)| Some((v?, source)))
    .min_by_key(|&(v, _)| v)
}

/// The soft RLIMIT_AS, when there is one: past it every allocation fails (an abort).
fn address_space() -> Option<u64> {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        let mut lim = libc::rlimit {
            rlim_cur: 0,
            rlim_max: 0,
        };
        // SAFETY: getrlimit only writes the struct it is given.
        let ok = unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut lim) } == 0;
        (ok && lim.rlim_cur != libc::RLIM_INFINITY).then_some(lim.rlim_cur)
    }
    #[cfg(not(all(target_os = "linux", target_env = "gnu")))]
    None
}

/// "123", "512K", "1.5G" → bytes.
fn parse_size(s: &str) -> Option<u64> {
    let s = s.trim();
    let (num, mult) = match s.char_indices().last()? {
        (i, 'k' | 'K') => (&s[..i], 1u64 << 10),
        (i, 'm' | 'M') => (&s[..i], 1 << 20),
        (i, 'g' | 'G') => (&s[..i], 1 << 30),
        (i, 't' | 'T') => (&s[..i], 1 << 40),
        _ => (s, 1),
    };
    let v: f64 = num.trim().parse().ok()?;
    (v.is_finite() && v >= 0.0).then_some((v * mult as f64) as u64)
}

/// This process's peak resident size in MiB (VmHWM), NaN where /proc is not there (for
/// the benches' memory columns).
pub fn peak_resident_mib() -> f64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    s.lines()
        .find(|l| l.starts_with("VmHWM"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|v| v.parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// Bytes for people: "1.5 GB", "230 MB".
pub fn show(bytes: u64) -> String {
    let b = bytes as f64;
    if b >= (1u64 << 30) as f64 {
        format!("{:.1} GB", b / (1u64 << 30) as f64)
    } else {
        format!("{:.0} MB", (b / (1u64 << 20) as f64).ceil())
    }
}

/// An error if `bytes` exceed the memory available: `what` names the entry that asks for
/// them and what it makes, e.g. "[mesh] nx × ny = 3000 × 3000 (27 004 001 nodes)".
pub fn check(what: &str, bytes: u64) -> Result<()> {
    match available() {
        Some((avail, source)) if bytes > avail => Err(Error::Memory(format!(
            "{what} needs about {} of memory (estimate), more than the {} available \
             ({source}); use a coarser mesh or a machine with more memory",
            show(bytes),
            show(avail)
        ))),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_suffixes() {
        assert_eq!(parse_size("123"), Some(123));
        assert_eq!(parse_size("512K"), Some(512 << 10));
        assert_eq!(parse_size("1.5G"), Some(3 << 29));
        assert_eq!(parse_size("2 m"), Some(2 << 20));
        assert_eq!(parse_size("lots"), None);
        assert_eq!(parse_size("-1G"), None);
    }

    #[test]
    fn estimates_grow_with_the_model_and_saturate() {
        let m = |nodes, contact| Model {
            nodes,
            quadratic: false,
            contact,
            kept_states: 1,
        };
        // the measured 400×400 Quad4 rectangle: 552 MB
        let q4 = solve_bytes(&m(160_801, Contact::None));
        assert!((552 << 20..800 << 20).contains(&q4), "{}", show(q4));
        let c = |contact| solve_bytes(&m(15_305, contact));
        assert!(c(Contact::Pointwise) > c(Contact::Mortar));
        assert!(c(Contact::Mortar) > c(Contact::None));
        assert_eq!(solve_bytes(&m(usize::MAX, Contact::Pointwise)), u64::MAX);
        assert_eq!(show(3 << 29), "1.5 GB");
        assert_eq!(show(230 << 20), "230 MB");
    }
}
