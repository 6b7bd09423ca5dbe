//! Mutation fuzzing of case files: `cargo run --release --example fuzz_cases -- SECONDS`
//! mutates the valid cases (`cases/**/*.toml` and the `ok` rows of `tests/corpus`) — a
//! number made NaN, inf, huge, negative or 0, a key deleted or duplicated, a value of
//! another type, an unknown key, a line from another case, a truncation — and runs each
//! mutant as `tribo run CASE -o DIR` does (load, checks, mesh, solve, output) in a child
//! process: one thread, 2 GiB of address space, `--limit` seconds (default 5). A child
//! that panics (status 101) or dies of a signal is a finding: its input is saved to the
//! temp folder. A child over its time is killed and counted as slow, not as a finding
//! (the first 20 are saved as `fuzz-case-slow-N.toml`).
//! The report: inputs tried, accepted, refused with an error, slow, and panics/signals.

use std::io::Write;
use std::os::unix::process::{CommandExt, ExitStatusExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, v: &'a [T]) -> &'a T {
        &v[self.below(v.len())]
    }
}

/// Values that break numbers: non-finite, extreme, negative, zero, wrong type.
const NUMBERS: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "1e9",
    "1e18",
    "-1",
    "-1.5",
    "0",
    "0.0",
    "-0.0",
    "1e-308",
    "5e-324",
    "18446744073709551615",
    "9223372036854775807",
    "4294967297",
    "0.5",
    "2147483648",
    "100000",
    "1e6",
    "3",
    "-3",
];
/// Values of another type than the one a key expects.
const OTHERS: &[&str] = &[
    "\"x\"",
    "\"\"",
    "true",
    "[]",
    "[1, 2]",
    "[1, 2, 3]",
    "[nan, nan]",
    "{}",
    "{ a = 1 }",
    "\"../../x\"",
    "\"/tmp\"",
    "[[0, 0], [1, nan]]",
    "[[0, 0]]",
    "1979-05-27",
];
const UNKNOWN_KEYS: &[&str] = &[
    "foo = 1",
    "nx = 3",
    "size = 0.1",
    "thickness = 2.0",
    "friction = 0.1",
    "penalty = 1e3",
    "function = \"f\"",
    "group = \"Body\"",
    "dx = 0.0",
    "[extra]",
    "[[contact]]",
    "[[material]]",
    "[solver]",
    "steps = 1e9",
    "[output.hertz]",
];

fn is_number_start(b: u8) -> bool {
    b.is_ascii_digit() || b == b'-' || b == b'+' || b == b'.'
}

/// Spans (start, end) of the number-like tokens of a line's value part.
fn numbers(line: &str) -> Vec<(usize, usize)> {
    let Some(eq) = line.find('=') else {
        return vec![];
    };
    let b = line.as_bytes();
    let mut out = vec![];
    let mut i = eq + 1;
    let mut in_str = false;
    while i < b.len() {
        if b[i] == b'"' {
            in_str = !in_str;
        } else if !in_str && is_number_start(b[i]) && (i == 0 || !b[i - 1].is_ascii_alphabetic()) {
            let s = i;
            while i < b.len()
                && (b[i].is_ascii_alphanumeric() || matches!(b[i], b'.' | b'-' | b'+' | b'_'))
            {
                i += 1;
            }
            out.push((s, i));
            continue;
        } else if b[i] == b'#' && !in_str {
            break;
        }
        i += 1;
    }
    out
}

fn mutate(seed: &str, all: &[String], rng: &mut Rng) -> String {
    let mut lines: Vec<String> = seed.lines().map(str::to_string).collect();
    for _ in 0..1 + rng.below(3) {
        if lines.is_empty() {
            lines.push(String::new());
        }
        let at = rng.below(lines.len());
        match rng.below(10) {
            // a number replaced (the most fruitful: three chances in ten)
            0..=2 => {
                let spans: Vec<(usize, usize, usize)> = (0..lines.len())
                    .flat_map(|l| numbers(&lines[l]).into_iter().map(move |(s, e)| (l, s, e)))
                    .collect();
                if !spans.is_empty() {
                    let (l, s, e) = *rng.pick(&spans);
                    let v = *rng.pick(NUMBERS);
                    lines[l].replace_range(s..e, v);
                }
            }
            // a key's value of another type
            3 => {
                if let Some(eq) = lines[at].find('=') {
                    let v = rng.pick(OTHERS);
                    lines[at].replace_range(eq + 1.., &format!(" {v}"));
                }
            }
            4 => {
                lines.remove(at);
            }
            5 => {
                let l = lines[at].clone();
                lines.insert(at, l);
            }
            6 => lines.insert(at, rng.pick(UNKNOWN_KEYS).to_string()),
            // a line of another case (its keys, tables and group names)
            7 => {
                let other: Vec<&str> = rng.pick(all).lines().collect();
                if !other.is_empty() {
                    lines.insert(at, rng.pick(&other).to_string());
                }
            }
            // a table block repeated
            8 => {
                let start = (0..=at).rev().find(|&i| lines[i].starts_with('['));
                if let Some(s) = start {
                    let end = (s + 1..lines.len())
                        .find(|&i| lines[i].starts_with('['))
                        .unwrap_or(lines.len());
                    let block: Vec<String> = lines[s..end].to_vec();
                    let to = rng.below(lines.len() + 1);
                    lines.splice(to..to, block);
                }
            }
            _ => {
                let text = lines.join("\n");
                let cut = rng.below(text.len() + 1);
                let cut = (0..=cut).rev().find(|&c| text.is_char_boundary(c)).unwrap();
                lines = text[..cut].lines().map(str::to_string).collect();
            }
        }
    }
    lines.join("\n") + "\n"
}

/// The child: runs one case as `tribo run` does; status 0 (ran), 2 (refused), 101 (panic).
fn child(case: &Path, out: &Path) -> ! {
    std::panic::set_hook(Box::new(|info| eprintln!("PANIC: {info}")));
    let code = match tribo::cli::run::run(case, Some(out), false) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            2
        }
    };
    std::process::exit(code);
}

fn seeds(root: &Path) -> Vec<String> {
    let mut files: Vec<PathBuf> = vec![];
    for sub in ["cases/examples", "cases/ssnp154"] {
        if let Ok(d) = std::fs::read_dir(root.join(sub)) {
            files.extend(d.flatten().map(|e| e.path()));
        }
    }
    let corpus = root.join("tests/corpus");
    let table = std::fs::read_to_string(corpus.join("expected.tsv")).unwrap_or_default();
    for l in table.lines() {
        let f: Vec<&str> = l.split('\t').collect();
        if f.len() >= 2 && f[1] == "ok" {
            files.push(corpus.join("cases").join(f[0]));
        }
    }
    files.sort();
    files
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .filter_map(|p| std::fs::read_to_string(p).ok())
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(String::as_str) == Some("--one") {
        child(Path::new(&args[2]), Path::new(&args[3]));
    }
    let secs: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10.0);
    let limit: f64 = args
        .iter()
        .position(|a| a == "--limit")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse().ok())
        .unwrap_or(5.0);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let seeds = seeds(&root);
    assert!(!seeds.is_empty(), "no seed cases under {}", root.display());
    // The mutants run beside copies of the corpus's mesh files (they name them relatively).
    let work = std::env::temp_dir().join(format!("fuzz-cases-{}", std::process::id()));
    std::fs::create_dir_all(&work).unwrap();
    for e in std::fs::read_dir(root.join("tests/corpus/cases"))
        .unwrap()
        .flatten()
    {
        if e.path().extension().is_none_or(|x| x != "toml") {
            std::fs::copy(e.path(), work.join(e.file_name())).unwrap();
        }
    }
    let exe = std::env::current_exe().unwrap();
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let t0 = Instant::now();
    let (mut tried, mut ran, mut refused, mut slow, mut findings) = (0u64, 0u64, 0u64, 0u64, 0u64);
    let case = work.join("case.toml");
    let out = work.join("out");
    while t0.elapsed() < Duration::from_secs_f64(secs) {
        let seed: &String = rng.pick(&seeds);
        let text = mutate(seed, &seeds, &mut rng);
        std::fs::write(&case, &text).unwrap();
        let _ = std::fs::remove_dir_all(&out);
        tried += 1;
        let mut cmd = Command::new(&exe);
        cmd.arg("--one")
            .arg(&case)
            .arg(&out)
            .env("RAYON_NUM_THREADS", "1")
            .stdout(Stdio::null())
            .stderr(Stdio::piped());
        // SAFETY: setrlimit is async-signal-safe; it only limits the child.
        unsafe {
            cmd.pre_exec(|| {
                let lim = libc::rlimit {
                    rlim_cur: 2 << 30,
                    rlim_max: 2 << 30,
                };
                libc::setrlimit(libc::RLIMIT_AS, &lim);
                Ok(())
            });
        }
        let mut ch = cmd.spawn().expect("cannot start the child");
        let started = Instant::now();
        let status = loop {
            if let Some(s) = ch.try_wait().unwrap() {
                break Some(s);
            }
            if started.elapsed().as_secs_f64() > limit {
                let _ = ch.kill();
                let _ = ch.wait();
                break None;
            }
            std::thread::sleep(Duration::from_millis(2));
        };
        let mut stderr = String::new();
        if let Some(mut e) = ch.stderr.take() {
            use std::io::Read;
            let _ = e.read_to_string(&mut stderr);
        }
        match status {
            None => {
                slow += 1;
                // kept for a look (a slow input is no finding, but may show a missing check)
                if slow <= 20 {
                    let f = std::env::temp_dir().join(format!("fuzz-case-slow-{slow}.toml"));
                    let _ = std::fs::write(&f, &text);
                }
            }
            Some(s) if s.code() == Some(0) => ran += 1,
            Some(s) if s.code() == Some(2) => refused += 1,
            Some(s) => {
                findings += 1;
                let f = std::env::temp_dir().join(format!("fuzz-case-finding-{findings}.toml"));
                let _ = std::fs::write(&f, &text);
                let what = match (s.code(), s.signal()) {
                    (Some(c), _) => format!("status {c}"),
                    (_, Some(sig)) => format!("signal {sig}"),
                    _ => "?".into(),
                };
                let last = stderr.lines().rev().take(3).collect::<Vec<_>>().join(" | ");
                eprintln!("FINDING ({what}): input saved to {}: {last}", f.display());
            }
        }
        if tried % 500 == 0 {
            print!(".");
            let _ = std::io::stdout().flush();
        }
    }
    let _ = std::fs::remove_dir_all(&work);
    let mins = t0.elapsed().as_secs_f64() / 60.0;
    println!(
        "\ncases: {tried} inputs in {:.1} min ({:.0}/min): {ran} ran, {refused} refused with an \
         error, {slow} over {limit} s, {findings} panics or signals",
        mins,
        tried as f64 / mins
    );
    std::process::exit(if findings == 0 { 0 } else { 1 });
}
