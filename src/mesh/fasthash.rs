//! A fast hasher for the generators' maps keyed by integers (lattice points, node pairs).
//!
//! The standard SipHash guards against crafted keys, which these internal integer keys
//! never are, and it cost 17 % of `tribo mesh info` on a 525k-node SSNP154 mesh. This is
//! a folded multiply (the 128-bit product of state ^ word and an odd constant, high half
//! xor low half): every input bit reaches the low bits hashbrown picks buckets with, even
//! for lattice coordinates that are multiples of large powers of two. Hand-written (a
//! dozen lines) rather than a crate: none is in the dependency tree.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

#[derive(Default, Clone, Copy)]
pub struct FoldHasher(u64);

const K: u64 = 0x9e37_79b9_7f4a_7c15;

impl Hasher for FoldHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut w = [0u8; 8];
            w[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(w));
        }
    }

    fn write_u64(&mut self, x: u64) {
        let m = u128::from(self.0 ^ x).wrapping_mul(u128::from(K));
        self.0 = (m as u64) ^ ((m >> 64) as u64) ^ K;
    }

    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// HashMap with the folded-multiply hasher.
pub type FastMap<K, V> = HashMap<K, V, BuildHasherDefault<FoldHasher>>;

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::{BuildHasher, BuildHasherDefault};

    #[test]
    fn lattice_keys_spread_over_the_low_bits() {
        // points on a coarse lattice (multiples of 2^20): the low 12 bits of their hashes
        // (the bucket index of a 4096-bucket table) must take many values
        let b = BuildHasherDefault::<FoldHasher>::default();
        let mut seen = std::collections::HashSet::new();
        for i in 0..64u64 {
            for j in 0..64u64 {
                seen.insert(b.hash_one((i << 20, j << 20)) & 0xfff);
            }
        }
        assert!(seen.len() > 2000, "{} distinct buckets of 4096", seen.len());
    }
}
