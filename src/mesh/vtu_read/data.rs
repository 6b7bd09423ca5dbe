//! The values of one VTU `<DataArray>`: inline ASCII, inline `binary` (base64 with its
//! UInt32/UInt64 size header, as VTK and meshio write by default) or appended raw, each
//! optionally zlib-compressed in blocks (`compressor="vtkZLibDataCompressor"`). Integer
//! arrays are read as integers, never through f64.
//!
//! Crates: `base64` and `flate2` (zlib through miniz_oxide, pure Rust), both maintained
//! and widely used; the block layout around them is VTK's.

use base64::Engine;
use std::collections::HashMap;
use std::io::Read;

/// One `<DataArray .../>` element: its attributes and, when inline, its text.
pub struct Array {
    pub attrs: HashMap<String, String>,
    pub text: String,
    pub section: &'static str,
}

impl Array {
    /// Its name, or its section's for an unnamed one (the points).
    pub fn name(&self) -> String {
        self.attrs
            .get("Name")
            .cloned()
            .unwrap_or_else(|| self.section.to_string())
    }
}

/// How the binary data of the file are laid out.
pub struct Layout<'a> {
    /// Block headers of UInt64 (else UInt32).
    pub header64: bool,
    /// Blocks compressed with zlib.
    pub zlib: bool,
    /// The raw appended data, after its '_' marker (empty without).
    pub appended: &'a [u8],
}

enum Data<'t> {
    Text(&'t str),
    Bytes(Vec<u8>),
}

/// The values of `a` as f64 (any numeric type); `expected` of them.
pub fn floats(a: &Array, layout: &Layout, expected: usize) -> Result<Vec<f64>, String> {
    let ty = a.attrs.get("type").map_or("", String::as_str);
    let v = match data(a, layout, expected)? {
        Data::Text(t) => t
            .split_ascii_whitespace()
            .map(|w| {
                w.parse::<f64>()
                    .map_err(|_| format!("array '{}': '{w}' is not a number", a.name()))
            })
            .collect::<Result<Vec<f64>, String>>()?,
        Data::Bytes(b) => decode(&b, ty, |v| Some(v as f64), |v| Some(v as f64), Some)
            .ok_or_else(|| unreadable(a, ty, b.len()))?,
    };
    count(a, v, expected)
}

/// The values of `a` as integers (an integer type); `expected` of them.
pub fn ints(a: &Array, layout: &Layout, expected: usize) -> Result<Vec<i64>, String> {
    let ty = a.attrs.get("type").map_or("", String::as_str);
    let v = match data(a, layout, expected)? {
        Data::Text(t) => t
            .split_ascii_whitespace()
            .map(|w| {
                w.parse::<i64>()
                    .map_err(|_| format!("array '{}': '{w}' is not an integer", a.name()))
            })
            .collect::<Result<Vec<i64>, String>>()?,
        Data::Bytes(b) => {
            if ty.starts_with("Float") {
                return Err(format!(
                    "array '{}': type {ty}, expected an integer type",
                    a.name()
                ));
            }
            decode(&b, ty, Some, |v| i64::try_from(v).ok(), |_| None).ok_or_else(|| {
                format!(
                    "array '{}': type '{ty}' with {} bytes is not readable as integers \
                     (or a value is beyond 2^63)",
                    a.name(),
                    b.len()
                )
            })?
        }
    };
    count(a, v, expected)
}

fn count<T>(a: &Array, v: Vec<T>, expected: usize) -> Result<Vec<T>, String> {
    if v.len() != expected {
        return Err(format!(
            "array '{}': {} values, expected {expected}",
            a.name(),
            v.len()
        ));
    }
    Ok(v)
}

fn unreadable(a: &Array, ty: &str, len: usize) -> String {
    format!(
        "array '{}': type '{ty}' with {len} bytes is not readable",
        a.name()
    )
}

fn data<'t>(a: &'t Array, layout: &Layout, expected: usize) -> Result<Data<'t>, String> {
    let name = a.name();
    match a.attrs.get("format").map(String::as_str) {
        Some("ascii") => Ok(Data::Text(&a.text)),
        Some("binary") => inline_binary(&a.text, layout.header64, layout.zlib, expected)
            .map(Data::Bytes)
            .map_err(|e| format!("array '{name}' (binary): {e}")),
        Some("appended") => {
            let off: usize = a
                .attrs
                .get("offset")
                .and_then(|o| o.parse().ok())
                .ok_or_else(|| format!("array '{name}': no valid offset"))?;
            let block = layout
                .appended
                .get(off..)
                .ok_or_else(|| format!("array '{name}': offset {off} beyond the data"))?;
            unpack(block, layout.header64, layout.zlib, expected)
                .map(Data::Bytes)
                .map_err(|e| format!("array '{name}' (appended at {off}): {e}"))
        }
        other => Err(format!(
            "array '{name}': format '{}' is not one of ascii, binary, appended",
            other.unwrap_or("")
        )),
    }
}

/// Characters of base64 for `n` bytes (with padding).
fn chars(n: usize) -> usize {
    n.div_ceil(3) * 4
}

fn b64(text: &[u8]) -> Result<Vec<u8>, String> {
    base64::engine::general_purpose::STANDARD
        .decode(text)
        .map_err(|e| format!("invalid base64: {e}"))
}

/// Inline binary data: the header and the data base64-encoded as one stream (meshio,
/// uncompressed) or apart (VTK; meshio compressed).
fn inline_binary(
    text: &str,
    header64: bool,
    zlib: bool,
    expected: usize,
) -> Result<Vec<u8>, String> {
    let t: Vec<u8> = text.bytes().filter(|c| !c.is_ascii_whitespace()).collect();
    // one stream: base64 padding only at its end
    let whole = b64(&t).and_then(|all| unpack(&all, header64, zlib, expected));
    if whole.is_ok() {
        return whole;
    }
    let hl: usize = if header64 { 8 } else { 4 };
    let first = b64(t.get(..chars(hl)).ok_or("shorter than its header")?)?;
    let header_len = if zlib {
        let blocks = word(&first, 0, header64).ok_or("shorter than its header")?;
        usize::try_from(blocks)
            .ok()
            .and_then(|b| b.checked_add(3)?.checked_mul(hl))
            .ok_or_else(|| format!("{blocks} blocks"))?
    } else {
        hl
    };
    let hc = chars(header_len);
    let head = t.get(..hc).ok_or("shorter than its header")?;
    let mut buf = b64(head)?;
    buf.truncate(header_len);
    buf.extend(b64(&t[hc..])?);
    unpack(&buf, header64, zlib, expected)
}

/// Header word `i` (UInt32 or UInt64) of `buf`.
fn word(buf: &[u8], i: usize, header64: bool) -> Option<u64> {
    if header64 {
        let b = buf.get(8 * i..8 * i + 8)?;
        Some(u64::from_le_bytes(b.try_into().ok()?))
    } else {
        let b = buf.get(4 * i..4 * i + 4)?;
        Some(u32::from_le_bytes(b.try_into().ok()?) as u64)
    }
}

/// The data of a block sequence: a size header and the bytes, or with zlib
/// [blocks, block size, last block size, compressed sizes...] and the compressed blocks.
/// Compressed data announcing more than 8 bytes for each of the `expected` values is
/// refused before it is inflated (a zip bomb).
fn unpack(buf: &[u8], header64: bool, zlib: bool, expected: usize) -> Result<Vec<u8>, String> {
    let hl: usize = if header64 { 8 } else { 4 };
    let w = |i: usize| word(buf, i, header64).ok_or_else(|| "truncated header".to_string());
    let size = |v: u64| usize::try_from(v).map_err(|_| format!("size {v} too large"));
    if !zlib {
        let n = size(w(0)?)?;
        return buf
            .get(hl..hl.saturating_add(n))
            .map(<[u8]>::to_vec)
            .ok_or_else(|| format!("{n} bytes announced, {} present", buf.len() - hl));
    }
    let blocks = size(w(0)?)?;
    let (block, last) = (size(w(1)?)?, size(w(2)?)?);
    let mut pos = blocks
        .checked_add(3)
        .and_then(|b| b.checked_mul(hl))
        .filter(|&p| p <= buf.len())
        .ok_or_else(|| format!("header of {blocks} blocks longer than the data"))?;
    let announced = match blocks {
        0 => 0,
        b => (b as u64 - 1)
            .saturating_mul(block as u64)
            .saturating_add(if last != 0 { last } else { block } as u64),
    };
    if announced > (expected as u64).saturating_mul(8) {
        return Err(format!("{announced} bytes announced for {expected} values"));
    }
    let mut out = vec![];
    for i in 0..blocks {
        let c = size(w(3 + i)?)?;
        let chunk = buf
            .get(pos..pos.saturating_add(c))
            .ok_or_else(|| format!("block {} truncated", i + 1))?;
        let want = if i + 1 == blocks && last != 0 {
            last
        } else {
            block
        };
        let before = out.len();
        // at most one byte more than announced: a larger block is an error, not a bomb
        flate2::read::ZlibDecoder::new(chunk)
            .take((want as u64).saturating_add(1))
            .read_to_end(&mut out)
            .map_err(|e| format!("block {}: zlib: {e}", i + 1))?;
        if out.len() - before != want {
            return Err(format!(
                "block {}: {} bytes after decompression, expected {want}",
                i + 1,
                out.len() - before
            ));
        }
        pos += c;
    }
    Ok(out)
}

/// Little-endian values of a VTK scalar type through `int` (signed), `uint` (unsigned) and
/// `float`; None for an unknown type, a length that is not a whole number of values or a
/// value a conversion refuses.
fn decode<T>(
    data: &[u8],
    ty: &str,
    int: impl Fn(i64) -> Option<T>,
    uint: impl Fn(u64) -> Option<T>,
    float: impl Fn(f64) -> Option<T>,
) -> Option<Vec<T>> {
    macro_rules! read {
        ($t:ty, $via:ty, $f:expr) => {{
            let n = std::mem::size_of::<$t>();
            if data.len() % n != 0 {
                return None;
            }
            data.chunks(n)
                .map(|c| $f(<$t>::from_le_bytes(c.try_into().ok()?) as $via))
                .collect()
        }};
    }
    match ty {
        "Float64" => read!(f64, f64, float),
        "Float32" => read!(f32, f64, float),
        "Int64" => read!(i64, i64, int),
        "Int32" => read!(i32, i64, int),
        "Int16" => read!(i16, i64, int),
        "Int8" => read!(i8, i64, int),
        "UInt64" => read!(u64, u64, uint),
        "UInt32" => read!(u32, u64, uint),
        "UInt16" => read!(u16, u64, uint),
        "UInt8" => read!(u8, u64, uint),
        _ => None,
    }
}
