//! Binary MSH 4.1: little-endian fields, the end of a section header line before binary
//! data, and the 4.1 numbers (`size_t`, `int`, `double`) read in either encoding.

use super::{Parser, Pos};
use crate::error::Result;

fn le_u64(b: &[u8]) -> u64 {
    let mut a = [0u8; 8];
    a.copy_from_slice(b);
    u64::from_le_bytes(a)
}

pub(super) fn le_i32(b: &[u8]) -> i32 {
    let mut a = [0u8; 4];
    a.copy_from_slice(b);
    i32::from_le_bytes(a)
}

impl<'a> Parser<'a> {
    /// Reads the end of a section header line in a binary file: the binary data starts
    /// right after its newline.
    pub(super) fn end_header_line(&mut self) -> Result<()> {
        while let Some(&b) = self.data.get(self.pos) {
            match b {
                b' ' | b'\t' | b'\r' => self.pos += 1,
                b'\n' => {
                    self.pos += 1;
                    self.line += 1;
                    return Ok(());
                }
                _ => {
                    return Err(self.err(
                        self.here(),
                        format!("expected the end of the {} line", self.section),
                    ))
                }
            }
        }
        Err(self.eof("binary data"))
    }

    pub(super) fn take(&mut self, n: usize, what: &str) -> Result<(&'a [u8], Pos)> {
        let start = self.pos;
        match start.checked_add(n) {
            Some(end) if end <= self.data.len() => {
                self.pos = end;
                Ok((&self.data[start..end], self.here_at(start)))
            }
            _ => Err(self.eof(what)),
        }
    }

    fn here_at(&self, offset: usize) -> Pos {
        Pos {
            line: self.line,
            offset,
        }
    }

    /// A 4.1 `size_t`: 8 bytes in binary files.
    pub(super) fn size(&mut self, what: &str) -> Result<(u64, Pos)> {
        if self.binary {
            let (b, p) = self.take(8, what)?;
            Ok((le_u64(b), p))
        } else {
            self.ascii_num(what)
        }
    }

    /// A 4.1 `int`: 4 bytes in binary files.
    pub(super) fn int(&mut self, what: &str) -> Result<(i64, Pos)> {
        if self.binary {
            let (b, p) = self.take(4, what)?;
            Ok((le_i32(b) as i64, p))
        } else {
            self.ascii_num(what)
        }
    }

    /// A 4.1 `double`: 8 bytes in binary files.
    pub(super) fn real(&mut self, what: &str) -> Result<(f64, Pos)> {
        if self.binary {
            let (b, p) = self.take(8, what)?;
            Ok((f64::from_bits(le_u64(b)), p))
        } else {
            self.ascii_num(what)
        }
    }
}
