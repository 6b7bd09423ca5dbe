//! Every truncation and a few thousand random mutations of the fixtures fail cleanly
//! (an error, never a panic).

use super::*;

/// xorshift64: a small deterministic generator for the mutation test.
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

fn parse_does_not_panic(bytes: &[u8]) -> Option<bool> {
    std::panic::catch_unwind(|| parse(bytes, "fuzz.msh").is_ok()).ok()
}

#[test]
fn truncations_and_mutations_never_panic() {
    let (binary, _) = base41_binary();
    let inputs: [(&str, Vec<u8>); 3] = [
        ("4.1 ASCII", BASE41.as_bytes().to_vec()),
        ("2.2 ASCII", BASE22.as_bytes().to_vec()),
        ("4.1 binary", binary),
    ];
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    for (name, data) in &inputs {
        assert_eq!(parse_does_not_panic(data), Some(true), "{name}");
        // Every truncation short of the final $End marker is an error.
        let full = data.len()
            - data
                .iter()
                .rev()
                .take_while(|b| b.is_ascii_whitespace())
                .count();
        for cut in 0..data.len() {
            match parse_does_not_panic(&data[..cut]) {
                None => panic!("{name}: panic when cut at byte {cut}"),
                Some(parsed) => assert!(cut >= full || !parsed, "{name}: cut at {cut} parsed"),
            }
        }
        let mut errors = 0;
        for i in 0..2000 {
            let mut m = data.clone();
            for _ in 0..1 + rng.below(3) {
                let at = rng.below(m.len());
                match rng.below(4) {
                    0 => m[at] = rng.next() as u8,
                    1 => m[at] = b"0123456789 -\n.e$"[rng.below(16)],
                    2 => {
                        let end = (at + 1 + rng.below(8)).min(m.len());
                        m.drain(at..end);
                    }
                    _ => {
                        let end = (at + 1 + rng.below(16)).min(m.len());
                        let piece = m[at..end].to_vec();
                        let to = rng.below(m.len());
                        m.splice(to..to, piece);
                    }
                }
                if m.is_empty() {
                    break;
                }
            }
            match parse_does_not_panic(&m) {
                None => panic!(
                    "{name}: panic on mutation {i}: {:?}",
                    String::from_utf8_lossy(&m)
                ),
                Some(false) => errors += 1,
                Some(true) => {}
            }
        }
        assert!(
            errors > 500,
            "{name}: only {errors} of 2000 mutations were rejected"
        );
    }
}
