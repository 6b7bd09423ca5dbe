//! The parser's reading of ASCII text: tokens and numbers, where they are (for error
//! messages), end-of-file errors and section end markers.

use super::{show, Parser, Pos};
use crate::error::{Error, Result};

impl<'a> Parser<'a> {
    // ---------------------------------------------------------------- errors

    fn place(&self, p: Pos) -> String {
        if self.binary {
            format!("{} (byte {})", self.source, p.offset)
        } else {
            format!("{}:{}", self.source, p.line)
        }
    }

    pub(super) fn err(&self, p: Pos, msg: impl Into<String>) -> Error {
        Error::parse(self.place(p), msg)
    }

    pub(super) fn file_err(&self, msg: impl Into<String>) -> Error {
        Error::parse(self.source, msg)
    }

    /// Unexpected end of file while looking for `what`.
    pub(super) fn eof(&self, what: &str) -> Error {
        let mut line = self.line;
        if self.pos >= self.data.len() && self.data.last() == Some(&b'\n') && line > 1 {
            line -= 1;
        }
        let p = Pos {
            line,
            offset: self.pos,
        };
        let msg = if self.section.is_empty() {
            format!("unexpected end of file (expected {what})")
        } else {
            format!(
                "unexpected end of file in {} (expected {what})",
                self.section
            )
        };
        self.err(p, msg)
    }

    /// At most `count` items, but no more than the remaining bytes can hold.
    pub(super) fn cap(&self, count: u64, min_bytes_per_item: usize) -> usize {
        let remaining = (self.data.len() - self.pos.min(self.data.len())) / min_bytes_per_item;
        count.min(remaining as u64) as usize
    }

    /// Smallest number of bytes one number takes in the current encoding.
    pub(super) fn min_number_bytes(&self) -> usize {
        if self.binary {
            4
        } else {
            2
        }
    }

    // ---------------------------------------------------------------- tokens

    pub(super) fn here(&self) -> Pos {
        Pos {
            line: self.line,
            offset: self.pos,
        }
    }

    fn skip_ws(&mut self) {
        while let Some(&b) = self.data.get(self.pos) {
            if b == b'\n' {
                self.line += 1;
            } else if !b.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
    }

    /// The next whitespace-separated token, or None at the end of the file.
    pub(super) fn token(&mut self) -> Option<(&'a [u8], Pos)> {
        self.skip_ws();
        let data = self.data;
        let start = self.pos;
        if start >= data.len() {
            return None;
        }
        let p = self.here();
        let mut end = start;
        while end < data.len() && !data[end].is_ascii_whitespace() {
            end += 1;
        }
        self.pos = end;
        Some((&data[start..end], p))
    }

    pub(super) fn expect_token(&mut self, what: &str) -> Result<(&'a [u8], Pos)> {
        self.token().ok_or_else(|| self.eof(what))
    }

    pub(super) fn ascii_num<T: std::str::FromStr>(&mut self, what: &str) -> Result<(T, Pos)> {
        let (tok, p) = self.expect_token(what)?;
        match std::str::from_utf8(tok).ok().and_then(|s| s.parse().ok()) {
            Some(v) => Ok((v, p)),
            None => Err(self.err(p, format!("expected {what}, found '{}'", show(tok)))),
        }
    }

    pub(super) fn end_section(&mut self, end: &str) -> Result<()> {
        match self.token() {
            None => Err(self.eof(end)),
            Some((tok, _)) if tok == end.as_bytes() => Ok(()),
            Some((tok, p)) => {
                let hint = if tok
                    .first()
                    .is_some_and(|b| b.is_ascii_digit() || *b == b'-')
                {
                    " (do the counts in the section match its data?)"
                } else {
                    ""
                };
                Err(self.err(p, format!("expected {end}, found '{}'{hint}", show(tok))))
            }
        }
    }
}
