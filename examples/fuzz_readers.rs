//! Mutation fuzzing of the mesh readers: `cargo run --release --example fuzz_readers -- SECONDS`
//! runs each reader (MSH 4.1 and 2.2 ASCII, VTU; MED for twice as long) for SECONDS
//! (default 10) on mutated copies of files our writers make, and reports the count of inputs tried, how many were
//! rejected with an error, and any panic (the input is saved to the temp folder).
//! MED runs in one thread, MSH then VTU in another (the machine has two cores); reader
//! names after SECONDS (med, msh, vtu) run only those.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::{Duration, Instant};
use tribo::mesh::generate::{ssnp154, Ssnp154Options};
use tribo::mesh::gmsh_write::{to_string, MshVersion};
use tribo::mesh::{gmsh, med, med_write, vtu_read};

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
}

fn mutate(seed: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut m = seed.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(m.len());
        match rng.below(6) {
            0 | 1 => m[at] = rng.next() as u8,
            2 => m[at] ^= 1 << rng.below(8),
            3 => {
                let end = (at + 1 + rng.below(16)).min(m.len());
                m.drain(at..end);
            }
            4 => {
                let end = (at + 1 + rng.below(32)).min(m.len());
                let piece = m[at..end].to_vec();
                let to = rng.below(m.len());
                m.splice(to..to, piece);
            }
            _ => m.truncate(at.max(1)),
        }
        if m.is_empty() {
            m.push(0);
        }
    }
    m
}

fn run(name: &str, seeds: Vec<Vec<u8>>, secs: f64, parse: impl Fn(Vec<u8>) -> bool) -> bool {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ name.len() as u64);
    let t0 = Instant::now();
    let (mut tried, mut rejected, mut panics) = (0u64, 0u64, 0u64);
    while t0.elapsed() < Duration::from_secs_f64(secs) {
        let seed = &seeds[rng.below(seeds.len())];
        let input = mutate(seed, &mut rng);
        tried += 1;
        match catch_unwind(AssertUnwindSafe(|| parse(input.clone()))) {
            Ok(true) => {}
            Ok(false) => rejected += 1,
            Err(_) => {
                panics += 1;
                let f = std::env::temp_dir().join(format!("fuzz-{name}-panic-{panics}.bin"));
                let _ = std::fs::write(&f, &input);
                eprintln!("{name}: PANIC, input saved to {}", f.display());
            }
        }
    }
    println!(
        "{name}: {tried} inputs in {:.0} s, {rejected} rejected with an error, {} read, {panics} panics",
        t0.elapsed().as_secs_f64(),
        tried - rejected - panics
    );
    panics == 0
}

fn main() {
    let secs: f64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(10.0);
    std::panic::set_hook(Box::new(|_| {})); // panics are counted, not printed
    let mesh = |quadratic| {
        ssnp154(&Ssnp154Options {
            quadratic,
            size: 6.0,
            global_refine: 0,
        })
        .unwrap()
    };
    let (lin, quad) = (mesh(false), mesh(true));
    let med_seeds = vec![
        med_write::to_bytes(&lin, "lin").unwrap(),
        med_write::to_bytes(&quad, "quad").unwrap(),
    ];
    let msh_seeds: Vec<Vec<u8>> = [MshVersion::V41, MshVersion::V22]
        .iter()
        .flat_map(|&v| {
            [
                to_string(&lin, v).into_bytes(),
                to_string(&quad, v).into_bytes(),
            ]
        })
        .collect();
    let dir = std::env::temp_dir();
    let vtu_seeds: Vec<Vec<u8>> = [(&lin, "lin"), (&quad, "quad")]
        .iter()
        .map(|(m, name)| {
            let p = dir.join(format!("fuzz-seed-{name}-{}.vtu", std::process::id()));
            tribo::post::vtu::write_mesh(&p, m).unwrap();
            let b = std::fs::read(&p).unwrap();
            let _ = std::fs::remove_file(&p);
            b
        })
        .collect();
    // Optional reader names after SECONDS restrict the run (e.g. `-- 600 vtu`).
    let only: Vec<String> = std::env::args().skip(2).map(|a| a.to_uppercase()).collect();
    let on = move |name: &str| only.is_empty() || only.iter().any(|o| o == name);
    let med_on = on("MED");
    let med_thread = std::thread::spawn(move || {
        !med_on
            || run("MED", med_seeds, 2.0 * secs, |b| {
                med::parse(b, "fuzz.med").is_ok()
            })
    });
    let msh_ok = !on("MSH")
        || run("MSH", msh_seeds, secs, |b| {
            gmsh::parse(&b, "fuzz.msh").is_ok()
        });
    let vtu_ok = !on("VTU")
        || run("VTU", vtu_seeds, secs, |b| {
            vtu_read::parse(&b, "fuzz.vtu").is_ok()
        });
    let med_ok = med_thread.join().unwrap_or(false);
    std::process::exit(if msh_ok && med_ok && vtu_ok { 0 } else { 1 });
}
