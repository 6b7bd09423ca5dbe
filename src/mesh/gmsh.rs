//! Gmsh MSH reader: format 4.1 (ASCII, and binary written on a little-endian machine with
//! 8-byte `size_t`) and format 2.2 (ASCII).
//!
//! Sections read: `$MeshFormat`, `$PhysicalNames`, `$Entities` (4.1), `$Nodes`,
//! `$Elements`; any other section (`$Periodic`, `$NodeData`, `$Comments`, ...) is skipped.
//!
//! - Element types: 15 (Point1), 1 (Seg2), 8 (Seg3), 2 (Tri3), 9 (Tri6), 3 (Quad4),
//!   16 (Quad8); Gmsh's node order is ours. Any other type is an error.
//! - Node tags may be sparse and in any order; nodes get dense indices in file order.
//! - z is dropped, but a node with |z| > 1e-12 × (bounding-box diagonal) is an error.
//! - Groups: each physical group of an element (4.1: the physical tags of its entity in
//!   `$Entities`; 2.2: its first tag) puts the cell in the cell group named in
//!   `$PhysicalNames`; a physical group without a name is an error. A 2.2 element
//!   repeated with the same number (Gmsh's way to put it in several groups) is one cell.
//!   When the file defines physical groups, elements outside all of them are dropped (as
//!   Gmsh does); their nodes stay. A file without any physical group keeps all its
//!   elements, in no group.
//! - Errors name the place: `file:line` in ASCII files, `file (byte N)` in binary ones,
//!   just `file` for problems of the whole file. Malformed input never panics; counts
//!   read from the file never size an allocation beyond what the remaining bytes can hold.

use super::{CellKind, Mesh, MeshBuilder};
use crate::error::{Error, Result};
use std::collections::HashMap;
use std::path::Path;

/// Reads a Gmsh MSH file; errors name the file.
pub fn read(path: &Path) -> Result<Mesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse(&bytes, &path.display().to_string())
}

/// Parses the bytes of a Gmsh MSH file; `source` names it in error messages.
pub fn parse(bytes: &[u8], source: &str) -> Result<Mesh> {
    Parser::new(bytes, source).run()
}

const SUPPORTED_VERSIONS: &str = "supported versions are 4.1 (ASCII or binary) and 2.2 (ASCII)";
const SUPPORTED_TYPES: &str =
    "15 (Point1), 1 (Seg2), 8 (Seg3), 2 (Tri3), 9 (Tri6), 3 (Quad4), 16 (Quad8)";

/// Our cell kind for a Gmsh element type number.
fn cell_kind(gmsh_type: i64) -> Option<CellKind> {
    Some(match gmsh_type {
        15 => CellKind::Point1,
        1 => CellKind::Seg2,
        8 => CellKind::Seg3,
        2 => CellKind::Tri3,
        9 => CellKind::Tri6,
        3 => CellKind::Quad4,
        16 => CellKind::Quad8,
        _ => return None,
    })
}

/// What a few unsupported Gmsh element types are, for error messages.
fn unsupported_type_name(gmsh_type: i64) -> Option<&'static str> {
    Some(match gmsh_type {
        4 => "4-node tetrahedron",
        5 => "8-node hexahedron",
        6 => "6-node prism",
        7 => "5-node pyramid",
        10 => "9-node quadrangle",
        11 => "10-node tetrahedron",
        12 => "27-node hexahedron",
        13 => "18-node prism",
        14 => "14-node pyramid",
        17 => "20-node hexahedron",
        18 => "15-node prism",
        19 => "13-node pyramid",
        20 => "9-node triangle",
        21 => "10-node triangle",
        26 => "4-node line",
        _ => return None,
    })
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Version {
    V22,
    V41,
}

/// Where a token or binary field starts: 1-based line and byte offset.
#[derive(Clone, Copy, Debug)]
struct Pos {
    line: usize,
    offset: usize,
}

/// A run of elements of one kind: a 4.1 entity block (`key` = entity tag, `dim` = entity
/// dimension) or consecutive 2.2 elements (`key` = physical tag, `dim` = cell dimension).
struct Block {
    kind: CellKind,
    dim: i64,
    key: i64,
    conn_start: usize,
    label_start: usize,
    count: usize,
}

const NO_NODE: usize = usize::MAX;

/// Node tag → dense index: a vector for small tags, a hash map for the others.
#[derive(Default)]
struct NodeMap {
    dense: Vec<usize>,
    dense_limit: u64,
    sparse: HashMap<u64, usize>,
}

impl NodeMap {
    /// Lets the dense part grow up to about twice the expected node count.
    fn expect(&mut self, nodes: usize) {
        let limit = (nodes as u64).saturating_mul(2).saturating_add(1024);
        self.dense_limit = self.dense_limit.max(limit);
    }

    /// Returns false if the tag is already there.
    fn insert(&mut self, tag: u64, index: usize) -> bool {
        if tag < self.dense_limit {
            let t = tag as usize;
            if t >= self.dense.len() {
                self.dense.resize(t + 1, NO_NODE);
            }
            if self.dense[t] != NO_NODE {
                return false;
            }
            self.dense[t] = index;
            true
        } else {
            self.sparse.insert(tag, index).is_none()
        }
    }

    fn get(&self, tag: u64) -> Option<usize> {
        if tag < self.dense_limit {
            match self.dense.get(tag as usize) {
                Some(&i) if i != NO_NODE => Some(i),
                _ => None,
            }
        } else {
            self.sparse.get(&tag).copied()
        }
    }
}

fn le_u64(b: &[u8]) -> u64 {
    let mut a = [0u8; 8];
    a.copy_from_slice(b);
    u64::from_le_bytes(a)
}

fn le_i32(b: &[u8]) -> i32 {
    let mut a = [0u8; 4];
    a.copy_from_slice(b);
    i32::from_le_bytes(a)
}

/// A token for an error message: at most 40 bytes, control characters escaped.
fn show(tok: &[u8]) -> String {
    let cut = &tok[..tok.len().min(40)];
    let mut s: String = String::from_utf8_lossy(cut).escape_debug().collect();
    if tok.len() > 40 {
        s.push_str("...");
    }
    s
}

struct Parser<'a> {
    data: &'a [u8],
    pos: usize,
    /// 1-based line number at `pos`.
    line: usize,
    source: &'a str,
    /// Binary file: places are byte offsets, and 4.1 sections hold binary numbers.
    binary: bool,
    /// The section being read, for end-of-file messages.
    section: &'static str,
    version: Version,
    builder: MeshBuilder,
    nodes: NodeMap,
    /// (dim, physical tag) → name.
    names: HashMap<(i64, i64), String>,
    /// (dim, entity tag) → physical tags (4.1).
    entities: Option<HashMap<(i64, i64), Vec<i64>>>,
    conn: Vec<usize>,
    labels: Vec<u64>,
    blocks: Vec<Block>,
    lo: [f64; 3],
    hi: [f64; 3],
    /// The node with the largest |z|: (z, tag, where).
    zmax: Option<(f64, u64, Pos)>,
    has_names: bool,
    has_nodes: bool,
    has_elements: bool,
}

impl<'a> Parser<'a> {
    fn new(data: &'a [u8], source: &'a str) -> Self {
        Parser {
            data,
            pos: 0,
            line: 1,
            source,
            binary: false,
            section: "",
            version: Version::V41,
            builder: MeshBuilder::new(source),
            nodes: NodeMap::default(),
            names: HashMap::new(),
            entities: None,
            conn: Vec::new(),
            labels: Vec::new(),
            blocks: Vec::new(),
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
            zmax: None,
            has_names: false,
            has_nodes: false,
            has_elements: false,
        }
    }

    // ---------------------------------------------------------------- errors

    fn place(&self, p: Pos) -> String {
        if self.binary {
            format!("{} (byte {})", self.source, p.offset)
        } else {
            format!("{}:{}", self.source, p.line)
        }
    }

    fn err(&self, p: Pos, msg: impl Into<String>) -> Error {
        Error::parse(self.place(p), msg)
    }

    fn file_err(&self, msg: impl Into<String>) -> Error {
        Error::parse(self.source, msg)
    }

    /// Unexpected end of file while looking for `what`.
    fn eof(&self, what: &str) -> Error {
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
    fn cap(&self, count: u64, min_bytes_per_item: usize) -> usize {
        let remaining = (self.data.len() - self.pos.min(self.data.len())) / min_bytes_per_item;
        count.min(remaining as u64) as usize
    }

    /// Smallest number of bytes one number takes in the current encoding.
    fn min_number_bytes(&self) -> usize {
        if self.binary {
            4
        } else {
            2
        }
    }

    // ---------------------------------------------------------------- tokens

    fn here(&self) -> Pos {
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
    fn token(&mut self) -> Option<(&'a [u8], Pos)> {
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

    fn expect_token(&mut self, what: &str) -> Result<(&'a [u8], Pos)> {
        self.token().ok_or_else(|| self.eof(what))
    }

    fn ascii_num<T: std::str::FromStr>(&mut self, what: &str) -> Result<(T, Pos)> {
        let (tok, p) = self.expect_token(what)?;
        match std::str::from_utf8(tok).ok().and_then(|s| s.parse().ok()) {
            Some(v) => Ok((v, p)),
            None => Err(self.err(p, format!("expected {what}, found '{}'", show(tok)))),
        }
    }

    /// Reads the end of a section header line in a binary file: the binary data starts
    /// right after its newline.
    fn end_header_line(&mut self) -> Result<()> {
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

    fn take(&mut self, n: usize, what: &str) -> Result<(&'a [u8], Pos)> {
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
    fn size(&mut self, what: &str) -> Result<(u64, Pos)> {
        if self.binary {
            let (b, p) = self.take(8, what)?;
            Ok((le_u64(b), p))
        } else {
            self.ascii_num(what)
        }
    }

    /// A 4.1 `int`: 4 bytes in binary files.
    fn int(&mut self, what: &str) -> Result<(i64, Pos)> {
        if self.binary {
            let (b, p) = self.take(4, what)?;
            Ok((le_i32(b) as i64, p))
        } else {
            self.ascii_num(what)
        }
    }

    /// A 4.1 `double`: 8 bytes in binary files.
    fn real(&mut self, what: &str) -> Result<(f64, Pos)> {
        if self.binary {
            let (b, p) = self.take(8, what)?;
            Ok((f64::from_bits(le_u64(b)), p))
        } else {
            self.ascii_num(what)
        }
    }

    fn end_section(&mut self, end: &str) -> Result<()> {
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

    // ---------------------------------------------------------------- sections

    fn run(mut self) -> Result<Mesh> {
        self.mesh_format()?;
        while let Some((tok, p)) = self.token() {
            type Read<'b> = fn(&mut Parser<'b>, Pos) -> Result<()>;
            let (name, read): (&'static str, Read<'a>) = match tok {
                b"$PhysicalNames" => ("$PhysicalNames", Self::physical_names),
                b"$Entities" if self.version == Version::V41 => ("$Entities", Self::entities41),
                b"$Nodes" => ("$Nodes", Self::nodes),
                b"$Elements" => ("$Elements", Self::elements),
                b"$MeshFormat" => return Err(self.err(p, "second $MeshFormat section")),
                t if t.starts_with(b"$End") => {
                    return Err(self.err(p, format!("'{}' closes no open section", show(t))))
                }
                t if t.first() == Some(&b'$') => {
                    self.skip_section(t)?;
                    continue;
                }
                t => {
                    return Err(self.err(
                        p,
                        format!(
                            "expected a section header such as $Nodes, found '{}'",
                            show(t)
                        ),
                    ))
                }
            };
            self.section = name;
            read(&mut self, p)?;
            self.section = "";
        }
        self.finish()
    }

    fn duplicate(&self, p: Pos, name: &str) -> Error {
        self.err(p, format!("second {name} section (only one is supported)"))
    }

    fn mesh_format(&mut self) -> Result<()> {
        match self.token() {
            None => return Err(self.file_err("empty file: not a Gmsh MSH file")),
            Some((b"$MeshFormat", _)) => {}
            Some((t, p)) => {
                return Err(self.err(
                    p,
                    format!(
                        "not a Gmsh MSH file: expected $MeshFormat, found '{}'",
                        show(t)
                    ),
                ))
            }
        }
        self.section = "$MeshFormat";
        let (vtok, pv) = self.expect_token("version number")?;
        let v: Option<f64> = std::str::from_utf8(vtok).ok().and_then(|s| s.parse().ok());
        self.version = match v {
            Some(v) if (v - 4.1).abs() < 1e-9 => Version::V41,
            Some(v) if (v - 2.2).abs() < 1e-9 => Version::V22,
            Some(_) => {
                return Err(self.err(
                    pv,
                    format!(
                        "unsupported MSH version {}; {SUPPORTED_VERSIONS}",
                        show(vtok)
                    ),
                ))
            }
            None => {
                return Err(self.err(
                    pv,
                    format!("expected version number, found '{}'", show(vtok)),
                ))
            }
        };
        let (file_type, pf) = self.ascii_num::<u64>("file type (0: ASCII, 1: binary)")?;
        let (data_size, pd) = self.ascii_num::<u64>("data size")?;
        match file_type {
            0 => {}
            1 => {
                if self.version == Version::V22 {
                    return Err(self.err(
                        pf,
                        format!("binary MSH 2.2 files are not supported; {SUPPORTED_VERSIONS}"),
                    ));
                }
                if data_size != 8 {
                    return Err(self.err(
                        pd,
                        format!(
                            "binary files with data size {data_size} are not supported \
                             (size_t must take 8 bytes)"
                        ),
                    ));
                }
                self.binary = true;
                self.end_header_line()?;
                let (b, p) = self.take(4, "the integer 1 in binary")?;
                match le_i32(b) {
                    1 => {}
                    0x0100_0000 => {
                        return Err(self.err(p, "big-endian binary files are not supported"))
                    }
                    _ => {
                        return Err(
                            self.err(p, "corrupt binary header: expected the integer 1 in binary")
                        )
                    }
                }
            }
            _ => {
                return Err(self.err(
                    pf,
                    format!("file type must be 0 (ASCII) or 1 (binary), found {file_type}"),
                ))
            }
        }
        self.end_section("$EndMeshFormat")?;
        self.section = "";
        Ok(())
    }

    /// Skips an unknown section up to its `$End...` line.
    fn skip_section(&mut self, header: &[u8]) -> Result<()> {
        let mut end = b"$End".to_vec();
        end.extend_from_slice(&header[1..]);
        loop {
            match self.token() {
                None => return Err(self.eof(&show(&end))),
                Some((t, _)) if t == end.as_slice() => return Ok(()),
                Some(_) => {}
            }
        }
    }

    fn physical_names(&mut self, p: Pos) -> Result<()> {
        if self.has_names {
            return Err(self.duplicate(p, "$PhysicalNames"));
        }
        self.has_names = true;
        let (n, _) = self.ascii_num::<u64>("number of physical names")?;
        for _ in 0..n {
            let (dim, pd) = self.ascii_num::<i64>("physical group dimension")?;
            if !(0..=3).contains(&dim) {
                return Err(self.err(
                    pd,
                    format!("physical group dimension must be 0, 1, 2 or 3, found {dim}"),
                ));
            }
            let (tag, _) = self.ascii_num::<i64>("physical tag")?;
            let name = self.quoted_name()?;
            self.names.insert((dim, tag), name);
        }
        self.end_section("$EndPhysicalNames")
    }

    /// The rest of the line, which must be a name in double quotes (it may hold spaces).
    fn quoted_name(&mut self) -> Result<String> {
        while matches!(self.data.get(self.pos), Some(b' ' | b'\t')) {
            self.pos += 1;
        }
        let data = self.data;
        let p = self.here();
        let start = self.pos;
        let mut end = start;
        while end < data.len() && data[end] != b'\n' {
            end += 1;
        }
        let raw = data[start..end].trim_ascii_end();
        if raw.is_empty() && end >= data.len() {
            self.pos = end;
            return Err(self.eof("physical name"));
        }
        self.pos = end;
        if raw.len() < 2 || raw[0] != b'"' || raw[raw.len() - 1] != b'"' {
            return Err(self.err(
                p,
                format!(
                    "expected a physical name in double quotes, found '{}'",
                    show(raw)
                ),
            ));
        }
        match std::str::from_utf8(&raw[1..raw.len() - 1]) {
            Ok("") => Err(self.err(p, "empty physical name")),
            Ok(name) => Ok(name.to_string()),
            Err(_) => Err(self.err(p, "physical name is not valid UTF-8")),
        }
    }

    fn entity_dim(&mut self) -> Result<i64> {
        let (dim, p) = self.int("entity dimension")?;
        if !(0..=3).contains(&dim) {
            return Err(self.err(
                p,
                format!("entity dimension must be 0, 1, 2 or 3, found {dim}"),
            ));
        }
        Ok(dim)
    }

    fn entities41(&mut self, p: Pos) -> Result<()> {
        if self.entities.is_some() {
            return Err(self.duplicate(p, "$Entities"));
        }
        if self.binary {
            self.end_header_line()?;
        }
        let mut counts = [0u64; 4];
        for (c, what) in counts.iter_mut().zip([
            "number of points",
            "number of curves",
            "number of surfaces",
            "number of volumes",
        ]) {
            *c = self.size(what)?.0;
        }
        let mut map = HashMap::new();
        for (dim, &n) in counts.iter().enumerate() {
            for _ in 0..n {
                let (tag, _) = self.int("entity tag")?;
                let reals = if dim == 0 { 3 } else { 6 };
                for _ in 0..reals {
                    self.real("entity coordinate")?;
                }
                let (np, _) = self.size("number of physical tags")?;
                let mut phys = Vec::with_capacity(self.cap(np, self.min_number_bytes()));
                for _ in 0..np {
                    phys.push(self.int("physical tag")?.0);
                }
                if dim > 0 {
                    let (nb, _) = self.size("number of bounding entities")?;
                    for _ in 0..nb {
                        self.int("bounding entity tag")?;
                    }
                }
                map.insert((dim as i64, tag), phys);
            }
        }
        self.entities = Some(map);
        self.end_section("$EndEntities")
    }

    fn nodes(&mut self, p: Pos) -> Result<()> {
        if self.has_nodes {
            return Err(self.duplicate(p, "$Nodes"));
        }
        self.has_nodes = true;
        match self.version {
            Version::V41 => self.nodes41()?,
            Version::V22 => self.nodes22()?,
        }
        self.end_section("$EndNodes")
    }

    fn nodes41(&mut self) -> Result<()> {
        if self.binary {
            self.end_header_line()?;
        }
        let (nblocks, _) = self.size("number of entity blocks")?;
        let (nnodes, pn) = self.size("number of nodes")?;
        self.size("smallest node tag")?;
        self.size("largest node tag")?;
        self.nodes
            .expect(self.cap(nnodes, 4 * self.min_number_bytes()));
        let mut total: u64 = 0;
        let mut tags: Vec<(u64, Pos)> = Vec::new();
        for _ in 0..nblocks {
            let dim = self.entity_dim()?;
            self.int("entity tag")?;
            let (param, pp) = self.int("parametric flag")?;
            if param != 0 && param != 1 {
                return Err(self.err(pp, format!("parametric flag must be 0 or 1, found {param}")));
            }
            let (count, _) = self.size("number of nodes in the block")?;
            total = total.saturating_add(count);
            tags.clear();
            tags.reserve(self.cap(count, self.min_number_bytes()));
            // Per block: all the tags first, then all the coordinates.
            for _ in 0..count {
                tags.push(self.size("node tag")?);
            }
            let extra = if param == 1 { dim } else { 0 };
            for &(tag, tag_pos) in &tags {
                let (x, px) = self.real("x coordinate")?;
                let (y, _) = self.real("y coordinate")?;
                let (z, pz) = self.real("z coordinate")?;
                for _ in 0..extra {
                    self.real("parametric coordinate")?;
                }
                self.add_node(tag, tag_pos, [x, y, z], px, pz)?;
            }
        }
        if total != nnodes {
            return Err(self.err(
                pn,
                format!("the $Nodes header announces {nnodes} nodes but its blocks hold {total}"),
            ));
        }
        Ok(())
    }

    fn nodes22(&mut self) -> Result<()> {
        let (n, _) = self.ascii_num::<u64>("number of nodes")?;
        self.nodes.expect(self.cap(n, 8));
        for _ in 0..n {
            let (tag, tag_pos) = self.ascii_num::<u64>("node number")?;
            let (x, px) = self.ascii_num::<f64>("x coordinate")?;
            let (y, _) = self.ascii_num::<f64>("y coordinate")?;
            let (z, pz) = self.ascii_num::<f64>("z coordinate")?;
            self.add_node(tag, tag_pos, [x, y, z], px, pz)?;
        }
        Ok(())
    }

    fn add_node(&mut self, tag: u64, tag_pos: Pos, x: [f64; 3], px: Pos, pz: Pos) -> Result<()> {
        if !x.iter().all(|v| v.is_finite()) {
            return Err(self.err(px, format!("node {tag} has a non-finite coordinate")));
        }
        let index = self.builder.num_nodes();
        if !self.nodes.insert(tag, index) {
            return Err(self.err(tag_pos, format!("node tag {tag} appears twice in $Nodes")));
        }
        self.builder.add_node([x[0], x[1]]);
        for (d, &v) in x.iter().enumerate() {
            self.lo[d] = self.lo[d].min(v);
            self.hi[d] = self.hi[d].max(v);
        }
        if x[2] != 0.0 && self.zmax.is_none_or(|(z, _, _)| x[2].abs() > z.abs()) {
            self.zmax = Some((x[2], tag, pz));
        }
        Ok(())
    }

    fn elements(&mut self, p: Pos) -> Result<()> {
        if self.has_elements {
            return Err(self.duplicate(p, "$Elements"));
        }
        if !self.has_nodes {
            return Err(self.err(p, "$Elements comes before $Nodes"));
        }
        self.has_elements = true;
        match self.version {
            Version::V41 => self.elements41()?,
            Version::V22 => self.elements22()?,
        }
        self.end_section("$EndElements")
    }

    fn element_kind(&self, gmsh_type: i64, p: Pos) -> Result<CellKind> {
        cell_kind(gmsh_type).ok_or_else(|| {
            let what = unsupported_type_name(gmsh_type)
                .map(|n| format!(" ({n})"))
                .unwrap_or_default();
            self.err(
                p,
                format!(
                    "element type {gmsh_type}{what} is not supported; \
                     supported Gmsh element types are {SUPPORTED_TYPES}"
                ),
            )
        })
    }

    fn node_index(&self, tag: u64, p: Pos, element: u64) -> Result<usize> {
        self.nodes.get(tag).ok_or_else(|| {
            self.err(
                p,
                format!("element {element} refers to node {tag}, which is not in $Nodes"),
            )
        })
    }

    /// Reads the `n` node tags of element `label` (at `p`) into `conn`; a tag listed twice
    /// is an error (the cell would be degenerate).
    fn element_nodes(&mut self, n: usize, label: u64, p: Pos) -> Result<()> {
        let start = self.conn.len();
        let mut tags = [0u64; 8];
        for a in 0..n {
            let (tag, pt) = if self.version == Version::V22 {
                self.ascii_num::<u64>("node number")?
            } else {
                self.size("node tag")?
            };
            let index = self.node_index(tag, pt, label)?;
            if tags[..a].contains(&tag) {
                return Err(self.err(p, format!("element {label} lists node {tag} twice")));
            }
            tags[a.min(7)] = tag;
            self.conn.push(index);
        }
        debug_assert_eq!(self.conn.len(), start + n);
        Ok(())
    }

    fn elements41(&mut self) -> Result<()> {
        if self.binary {
            self.end_header_line()?;
        }
        let (nblocks, _) = self.size("number of entity blocks")?;
        let (nelems, pn) = self.size("number of elements")?;
        self.size("smallest element tag")?;
        self.size("largest element tag")?;
        let mut total: u64 = 0;
        let mut element_tags = std::collections::HashSet::new();
        for _ in 0..nblocks {
            let dim = self.entity_dim()?;
            let (entity, pe) = self.int("entity tag")?;
            if self
                .entities
                .as_ref()
                .is_some_and(|m| !m.contains_key(&(dim, entity)))
            {
                return Err(self.err(
                    pe,
                    format!(
                        "element block of entity {entity} (dim {dim}): \
                         the entity is not in $Entities"
                    ),
                ));
            }
            let (gmsh_type, pt) = self.int("element type")?;
            let kind = self.element_kind(gmsh_type, pt)?;
            let (count, _) = self.size("number of elements in the block")?;
            total = total.saturating_add(count);
            let n = kind.num_nodes();
            let reserve = self.cap(count, (n + 1) * self.min_number_bytes());
            self.labels.reserve(reserve);
            self.conn.reserve(reserve * n);
            let mut block = Block {
                kind,
                dim,
                key: entity,
                conn_start: self.conn.len(),
                label_start: self.labels.len(),
                count: 0,
            };
            for _ in 0..count {
                let (label, pl) = self.size("element tag")?;
                if !element_tags.insert(label) {
                    return Err(self.err(
                        pl,
                        format!("element tag {label} appears twice in $Elements"),
                    ));
                }
                self.element_nodes(n, label, pl)?;
                self.labels.push(label);
            }
            block.count = self.labels.len() - block.label_start;
            self.blocks.push(block);
        }
        if total != nelems {
            return Err(self.err(
                pn,
                format!(
                    "the $Elements header announces {nelems} elements but its blocks hold {total}"
                ),
            ));
        }
        Ok(())
    }

    fn elements22(&mut self) -> Result<()> {
        let (n, _) = self.ascii_num::<u64>("number of elements")?;
        for _ in 0..n {
            let (label, pl) = self.ascii_num::<u64>("element number")?;
            let (gmsh_type, pt) = self.ascii_num::<i64>("element type")?;
            let kind = self.element_kind(gmsh_type, pt)?;
            let (ntags, _) = self.ascii_num::<u64>("number of tags")?;
            let mut physical = 0;
            for i in 0..ntags {
                let (t, _) = self.ascii_num::<i64>("element tag")?;
                if i == 0 {
                    physical = t;
                }
            }
            let conn_start = self.conn.len();
            self.element_nodes(kind.num_nodes(), label, pl)?;
            let dim = kind.dim() as i64;
            match self.blocks.last_mut() {
                Some(b) if b.kind == kind && b.key == physical => b.count += 1,
                _ => self.blocks.push(Block {
                    kind,
                    dim,
                    key: physical,
                    conn_start,
                    label_start: self.labels.len(),
                    count: 1,
                }),
            }
            self.labels.push(label);
        }
        Ok(())
    }

    // ---------------------------------------------------------------- the mesh

    fn finish(self) -> Result<Mesh> {
        if !self.has_nodes {
            return Err(self.file_err("no $Nodes section"));
        }
        if !self.has_elements {
            return Err(self.file_err("no $Elements section"));
        }
        if let Some((z, tag, p)) = self.zmax {
            let diag = (0..3)
                .map(|d| (self.hi[d] - self.lo[d]).powi(2))
                .sum::<f64>()
                .sqrt();
            if z.abs() > 1e-12 * diag {
                return Err(self.err(
                    p,
                    format!(
                        "node {tag} has z = {z}: 3D meshes are not supported \
                         (all nodes must lie in the plane z = 0)"
                    ),
                ));
            }
        }
        let v41 = self.version == Version::V41;
        if v41 && self.entities.is_none() && !self.names.is_empty() {
            return Err(self.file_err(
                "$PhysicalNames but no $Entities section: \
                 the physical groups of the elements are unknown",
            ));
        }
        let has_physicals = !self.names.is_empty()
            || self
                .entities
                .as_ref()
                .is_some_and(|m| m.values().any(|p| !p.is_empty()))
            || (!v41 && self.blocks.iter().any(|b| b.key != 0));

        let Parser {
            source,
            mut builder,
            names,
            entities,
            conn,
            labels,
            blocks,
            ..
        } = self;
        let entities = entities.unwrap_or_default();
        let mut groups: Vec<&str> = Vec::new();
        let mut seen: HashMap<u64, usize> = HashMap::new();
        for b in &blocks {
            let physical: &[i64] = if v41 {
                entities.get(&(b.dim, b.key)).map_or(&[], |p| p.as_slice())
            } else if b.key != 0 {
                std::slice::from_ref(&b.key)
            } else {
                &[]
            };
            if physical.is_empty() && has_physicals {
                continue;
            }
            groups.clear();
            for &t in physical {
                match names.get(&(b.dim, t)) {
                    Some(name) => groups.push(name),
                    None => {
                        return Err(Error::parse(
                            source,
                            format!(
                                "physical group {t} (dim {}) of element {} has no name \
                                 in $PhysicalNames",
                                b.dim, labels[b.label_start]
                            ),
                        ))
                    }
                }
            }
            let n = b.kind.num_nodes();
            for i in 0..b.count {
                let s = b.conn_start + i * n;
                let label = labels[b.label_start + i];
                // MSH 2.2 repeats an element once per physical group, with one number.
                let c = match seen.get(&label) {
                    Some(&c) if !v41 => {
                        if builder.cell(c) != (b.kind, &conn[s..s + n]) {
                            return Err(Error::parse(
                                source,
                                format!("element {label} is defined twice with different nodes"),
                            ));
                        }
                        c
                    }
                    _ => {
                        let c = builder.add_cell(b.kind, &conn[s..s + n], label);
                        if !v41 {
                            seen.insert(label, c);
                        }
                        c
                    }
                };
                for g in &groups {
                    builder.add_to_cell_group(g, c);
                }
            }
        }
        builder.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Quad4 + Tri3 on a surface with two physical groups, Seg2 on a curve, points; a
    /// surface and a point without physical groups (their elements are dropped), a
    /// parametric node block, sparse node tags, a skipped section.
    const BASE41: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
4
0 3 "Corner"
1 4 "Bottom edge"
2 1 "Plate"
2 2 "All"
$EndPhysicalNames
$Entities
2 1 2 0
1 0 0 0 1 3
2 2 0 0 0
1 0 0 0 2 0 0 1 4 2 1 -2
1 0 0 0 2 1 0 2 1 2 1 1
2 1 0 0 2 1 0 0 1 1
$EndEntities
$Comments
skipped: $Nodes $Elements 1 2 3
$EndComments
$Nodes
3 6 10 60
0 1 0 1
10
0 0 0
1 1 1 1
20
1 0 0 0.5
2 1 0 4
30
40
50
60
1 1 0
0 1 0
2 0 0
2 1 0
$EndNodes
$Elements
6 7 1 7
0 1 15 1
1 10
0 2 15 1
2 50
1 1 1 2
3 10 20
4 20 50
2 1 3 1
5 10 20 30 40
2 1 2 1
6 20 50 30
2 2 2 1
7 50 60 30
$EndElements
"#;

    /// MSH 2.2: Point1, Seg3, a clockwise Quad8, Tri6; elements without a physical
    /// group; a skipped $NodeData section.
    const BASE22: &str = r#"$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
3
0 3 "Tip"
1 1 "Edge"
2 2 "Body"
$EndPhysicalNames
$Nodes
11
1 0 0 0
2 2 0 0
3 2 2 0
4 0 2 0
5 1 0 0
6 2 1 0
7 1 2 0
8 0 1 0
20 4 0 0
21 3 0 0
22 3 1 0
$EndNodes
$NodeData
1
"ignored view"
1
0.0
3
0
1
1
1 5.0
$EndNodeData
$Elements
6
1 15 2 3 1 1
2 8 2 1 1 1 2 5
3 16 2 2 1 1 4 3 2 8 7 6 5
4 9 2 2 2 2 20 3 21 22 6
5 1 0 1 2
6 1 2 0 1 3 4
$EndElements
"#;

    /// Test-only writer of the MSH 4.1 binary encoding (little-endian, 8-byte size_t).
    #[derive(Default)]
    struct Bin {
        buf: Vec<u8>,
    }

    impl Bin {
        fn text(&mut self, s: &str) -> &mut Self {
            self.buf.extend_from_slice(s.as_bytes());
            self
        }
        fn int(&mut self, v: i32) -> &mut Self {
            self.buf.extend_from_slice(&v.to_le_bytes());
            self
        }
        fn size(&mut self, v: u64) -> &mut Self {
            self.buf.extend_from_slice(&v.to_le_bytes());
            self
        }
        fn reals(&mut self, v: &[f64]) -> &mut Self {
            for x in v {
                self.buf.extend_from_slice(&x.to_le_bytes());
            }
            self
        }
        fn at(&self) -> usize {
            self.buf.len()
        }
    }

    /// Byte offsets of a few fields of the binary test mesh.
    struct Marks {
        /// The 4-byte integer 1 of $MeshFormat.
        one: usize,
        /// The tag of node 30 (in the third node block).
        node_tag_30: usize,
        /// Node 30 in the nodes of element 5 (the quad).
        quad_node_30: usize,
        /// The element type of the quad block.
        quad_type: usize,
    }

    /// BASE41 in the binary encoding.
    fn base41_binary() -> (Vec<u8>, Marks) {
        let mut w = Bin::default();
        w.text("$MeshFormat\n4.1 1 8\n");
        let one = w.at();
        w.int(1).text("\n$EndMeshFormat\n");
        w.text("$PhysicalNames\n4\n0 3 \"Corner\"\n1 4 \"Bottom edge\"\n");
        w.text("2 1 \"Plate\"\n2 2 \"All\"\n$EndPhysicalNames\n");
        w.text("$Entities\n").size(2).size(1).size(2).size(0);
        w.int(1).reals(&[0., 0., 0.]).size(1).int(3);
        w.int(2).reals(&[2., 0., 0.]).size(0);
        w.int(1).reals(&[0., 0., 0., 2., 0., 0.]).size(1).int(4);
        w.size(2).int(1).int(-2);
        w.int(1)
            .reals(&[0., 0., 0., 2., 1., 0.])
            .size(2)
            .int(1)
            .int(2);
        w.size(1).int(1);
        w.int(2)
            .reals(&[1., 0., 0., 2., 1., 0.])
            .size(0)
            .size(1)
            .int(1);
        w.text("\n$EndEntities\n");
        w.text("$Comments\nskipped: $Nodes $Elements 1 2 3\n$EndComments\n");
        w.text("$Nodes\n").size(3).size(6).size(10).size(60);
        w.int(0).int(1).int(0).size(1).size(10).reals(&[0., 0., 0.]);
        w.int(1)
            .int(1)
            .int(1)
            .size(1)
            .size(20)
            .reals(&[1., 0., 0., 0.5]);
        w.int(2).int(1).int(0).size(4);
        let node_tag_30 = w.at();
        w.size(30).size(40).size(50).size(60);
        w.reals(&[1., 1., 0., 0., 1., 0., 2., 0., 0., 2., 1., 0.]);
        w.text("\n$EndNodes\n");
        w.text("$Elements\n").size(6).size(7).size(1).size(7);
        w.int(0).int(1).int(15).size(1).size(1).size(10);
        w.int(0).int(2).int(15).size(1).size(2).size(50);
        w.int(1).int(1).int(1).size(2);
        w.size(3).size(10).size(20).size(4).size(20).size(50);
        w.int(2).int(1);
        let quad_type = w.at();
        w.int(3).size(1).size(5).size(10).size(20);
        let quad_node_30 = w.at();
        w.size(30).size(40);
        w.int(2)
            .int(1)
            .int(2)
            .size(1)
            .size(6)
            .size(20)
            .size(50)
            .size(30);
        w.int(2)
            .int(2)
            .int(2)
            .size(1)
            .size(7)
            .size(50)
            .size(60)
            .size(30);
        w.text("\n$EndElements\n");
        let marks = Marks {
            one,
            node_tag_30,
            quad_node_30,
            quad_type,
        };
        (w.buf, marks)
    }

    fn ok(text: &str) -> Mesh {
        parse(text.as_bytes(), "t.msh").unwrap()
    }

    fn err(bytes: &[u8]) -> String {
        match parse(bytes, "t.msh") {
            Ok(_) => panic!("parse succeeded"),
            Err(e) => e.to_string(),
        }
    }

    /// 1-based line of the first occurrence of `needle`.
    fn line_of(text: &str, needle: &str) -> usize {
        let i = text.find(needle).expect("needle not in text");
        text[..i].matches('\n').count() + 1
    }

    /// `text` up to and including the first occurrence of `needle`.
    fn cut_after<'t>(text: &'t str, needle: &str) -> &'t str {
        &text[..text.find(needle).expect("needle not in text") + needle.len()]
    }

    fn replace_once(text: &str, from: &str, to: &str) -> String {
        assert_eq!(text.matches(from).count(), 1, "'{from}' must occur once");
        text.replacen(from, to, 1)
    }

    fn groups(mesh: &Mesh) -> Vec<(&str, Vec<usize>)> {
        mesh.cell_groups
            .iter()
            .map(|(k, v)| (k.as_str(), v.clone()))
            .collect()
    }

    fn check_base41(mesh: &Mesh) {
        assert_eq!(
            mesh.coords,
            vec![[0., 0.], [1., 0.], [1., 1.], [0., 1.], [2., 0.], [2., 1.]]
        );
        let cells: Vec<(CellKind, Vec<usize>)> = (0..mesh.num_cells())
            .map(|c| (mesh.kind(c), mesh.cell_nodes(c).to_vec()))
            .collect();
        assert_eq!(
            cells,
            vec![
                (CellKind::Point1, vec![0]),
                (CellKind::Seg2, vec![0, 1]),
                (CellKind::Seg2, vec![1, 4]),
                (CellKind::Quad4, vec![0, 1, 2, 3]),
                (CellKind::Tri3, vec![1, 4, 2]),
            ]
        );
        assert_eq!(
            groups(mesh),
            vec![
                ("All", vec![3, 4]),
                ("Bottom edge", vec![1, 2]),
                ("Corner", vec![0]),
                ("Plate", vec![3, 4]),
            ]
        );
        assert!(mesh.node_groups.is_empty());
        assert_eq!(mesh.reoriented, 0);
        assert_eq!(mesh.single_node("Corner").unwrap(), 0);
        assert_eq!(mesh.group_dim("Bottom edge"), Some(1));
    }

    #[test]
    fn ascii_41() {
        check_base41(&ok(BASE41));
        // CRLF line ends and extra blank lines are fine.
        check_base41(&ok(&BASE41.replace('\n', "\r\n\r\n")));
    }

    #[test]
    fn binary_41() {
        let (bytes, _) = base41_binary();
        let mesh = parse(&bytes, "b.msh").unwrap();
        check_base41(&mesh);
    }

    #[test]
    fn ascii_22_with_quadratic_cells() {
        let mesh = ok(BASE22);
        assert_eq!(mesh.num_nodes(), 11);
        assert_eq!(mesh.coords[8], [4., 0.]);
        assert_eq!(mesh.coords[10], [3., 1.]);
        let cells: Vec<(CellKind, Vec<usize>)> = (0..mesh.num_cells())
            .map(|c| (mesh.kind(c), mesh.cell_nodes(c).to_vec()))
            .collect();
        assert_eq!(
            cells,
            vec![
                (CellKind::Point1, vec![0]),
                (CellKind::Seg3, vec![0, 1, 4]),
                // Given clockwise (0, 3, 2, 1, 7, 6, 5, 4), reordered.
                (CellKind::Quad8, vec![0, 1, 2, 3, 4, 5, 6, 7]),
                (CellKind::Tri6, vec![1, 8, 2, 9, 10, 5]),
            ]
        );
        assert_eq!(mesh.reoriented, 1);
        assert_eq!(
            groups(&mesh),
            vec![("Body", vec![2, 3]), ("Edge", vec![1]), ("Tip", vec![0]),]
        );
    }

    #[test]
    fn clockwise_quad_is_reoriented_and_no_groups_keep_all_cells() {
        let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n\
                    1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n\
                    $Elements\n1 1 1 1\n2 1 3 1\n1 1 4 3 2\n$EndElements\n";
        let mesh = ok(text);
        assert_eq!(mesh.num_cells(), 1);
        assert_eq!(mesh.kind(0), CellKind::Quad4);
        assert_eq!(mesh.cell_nodes(0), &[0, 1, 2, 3]);
        assert_eq!(mesh.reoriented, 1);
        // the cell is in no physical group: it forms the default group
        let groups: Vec<(&String, &Vec<usize>)> = mesh.cell_groups.iter().collect();
        assert_eq!(
            groups,
            [(&crate::mesh::DEFAULT_GROUP.to_string(), &vec![0])]
        );
    }

    #[test]
    fn tiny_z_is_ignored() {
        let text = replace_once(BASE41, "2 1 0\n$EndNodes", "2 1 1e-15\n$EndNodes");
        check_base41(&ok(&text));
    }

    #[test]
    fn truncated_ascii() {
        let t = cut_after(BASE41, "2 1 \"Plate\"\n");
        assert_eq!(
            err(t.as_bytes()),
            format!(
                "t.msh:{}: unexpected end of file in $PhysicalNames \
                 (expected physical group dimension)",
                line_of(BASE41, "2 1 \"Plate\"")
            )
        );
        let t = cut_after(BASE41, "10\n0 0");
        assert_eq!(
            err(t.as_bytes()),
            format!(
                "t.msh:{}: unexpected end of file in $Nodes (expected z coordinate)",
                line_of(BASE41, "10\n0 0") + 1
            )
        );
        let t = cut_after(BASE41, "5 10 20 30");
        assert_eq!(
            err(t.as_bytes()),
            format!(
                "t.msh:{}: unexpected end of file in $Elements (expected node tag)",
                line_of(BASE41, "5 10 20 30")
            )
        );
        let t = cut_after(BASE41, "7 50 60 30\n");
        assert_eq!(
            err(t.as_bytes()),
            format!(
                "t.msh:{}: unexpected end of file in $Elements (expected $EndElements)",
                line_of(BASE41, "7 50 60 30")
            )
        );
        let t = cut_after(BASE22, "4 0 2 0\n");
        assert_eq!(
            err(t.as_bytes()),
            format!(
                "t.msh:{}: unexpected end of file in $Nodes (expected node number)",
                line_of(BASE22, "4 0 2 0")
            )
        );
        let t = cut_after(BASE41, "$Comments\n");
        assert_eq!(
            err(t.as_bytes()),
            format!(
                "t.msh:{}: unexpected end of file (expected $EndComments)",
                line_of(BASE41, "$Comments")
            )
        );
        assert_eq!(err(b""), "t.msh: empty file: not a Gmsh MSH file");
        assert_eq!(
            err(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"),
            "t.msh: no $Nodes section"
        );
        let t = cut_after(BASE41, "$EndNodes\n");
        assert_eq!(err(t.as_bytes()), "t.msh: no $Elements section");
    }

    #[test]
    fn truncated_binary() {
        let (bytes, m) = base41_binary();
        assert_eq!(
            err(&bytes[..m.node_tag_30 + 3]),
            format!(
                "t.msh (byte {}): unexpected end of file in $Nodes (expected node tag)",
                m.node_tag_30
            )
        );
        assert_eq!(
            err(&bytes[..m.quad_node_30 + 9]),
            format!(
                "t.msh (byte {}): unexpected end of file in $Elements (expected node tag)",
                m.quad_node_30 + 8
            )
        );
        assert_eq!(
            err(&bytes[..m.one + 2]),
            format!(
                "t.msh (byte {}): unexpected end of file in $MeshFormat \
                 (expected the integer 1 in binary)",
                m.one
            )
        );
        let end = bytes.len() - "$EndElements\n".len();
        assert_eq!(
            err(&bytes[..end]),
            format!(
                "t.msh (byte {end}): unexpected end of file in $Elements (expected $EndElements)"
            )
        );
    }

    #[test]
    fn binary_errors() {
        let (bytes, m) = base41_binary();
        let mut b = bytes.clone();
        b[m.quad_node_30..m.quad_node_30 + 8].copy_from_slice(&99u64.to_le_bytes());
        assert_eq!(
            err(&b),
            format!(
                "t.msh (byte {}): element 5 refers to node 99, which is not in $Nodes",
                m.quad_node_30
            )
        );
        let mut b = bytes.clone();
        b[m.quad_type..m.quad_type + 4].copy_from_slice(&4i32.to_le_bytes());
        assert_eq!(
            err(&b),
            format!(
                "t.msh (byte {}): element type 4 (4-node tetrahedron) is not supported; \
                 supported Gmsh element types are {SUPPORTED_TYPES}",
                m.quad_type
            )
        );
        let mut b = bytes.clone();
        b[m.one..m.one + 4].copy_from_slice(&1i32.to_be_bytes());
        assert_eq!(
            err(&b),
            format!(
                "t.msh (byte {}): big-endian binary files are not supported",
                m.one
            )
        );
        // A huge count must fail cleanly, without a huge allocation.
        let mut b = bytes.clone();
        let count = m.node_tag_30 - 8;
        b[count..count + 8].copy_from_slice(&(u64::MAX / 2).to_le_bytes());
        assert!(err(&b).starts_with("t.msh (byte "));
    }

    #[test]
    fn non_numeric_coordinate() {
        let text = replace_once(BASE41, "1 1 0\n0 1 0\n", "1 1 0\n0 abc 0\n");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: expected y coordinate, found 'abc'",
                line_of(&text, "0 abc 0")
            )
        );
        let text = replace_once(BASE41, "1 1 0\n0 1 0\n", "1 1 0\n0 nan 0\n");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: node 40 has a non-finite coordinate",
                line_of(&text, "0 nan 0")
            )
        );
    }

    #[test]
    fn unsupported_element_type() {
        let text = replace_once(
            BASE41,
            "2 1 3 1\n5 10 20 30 40\n",
            "2 1 10 1\n5 10 20 30 40 50 60 10 20 30\n",
        );
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: element type 10 (9-node quadrangle) is not supported; supported \
                 Gmsh element types are 15 (Point1), 1 (Seg2), 8 (Seg3), 2 (Tri3), \
                 9 (Tri6), 3 (Quad4), 16 (Quad8)",
                line_of(&text, "2 1 10 1")
            )
        );
        let text = replace_once(BASE22, "5 1 0 1 2", "5 4 0 1 2 3 4");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: element type 4 (4-node tetrahedron) is not supported; \
                 supported Gmsh element types are {SUPPORTED_TYPES}",
                line_of(&text, "5 4 0 1 2 3 4")
            )
        );
        let text = replace_once(BASE22, "5 1 0 1 2", "5 99 0 1 2");
        assert!(err(text.as_bytes()).contains("element type 99 is not supported;"));
    }

    #[test]
    fn missing_physical_name() {
        let text = replace_once(BASE41, "4\n0 3 \"Corner\"\n", "3\n");
        assert_eq!(
            err(text.as_bytes()),
            "t.msh: physical group 3 (dim 0) of element 1 has no name in $PhysicalNames"
        );
        let text = replace_once(BASE22, "2 2 \"Body\"\n", "1 2 \"Body\"\n");
        assert_eq!(
            err(text.as_bytes()),
            "t.msh: physical group 2 (dim 2) of element 3 has no name in $PhysicalNames"
        );
        let text = replace_once(BASE41, "\"All\"", "All");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: expected a physical name in double quotes, found 'All'",
                line_of(&text, "2 2 All")
            )
        );
    }

    #[test]
    fn unknown_node_tag() {
        let text = replace_once(BASE41, "6 20 50 30", "6 20 55 30");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: element 6 refers to node 55, which is not in $Nodes",
                line_of(&text, "6 20 55 30")
            )
        );
        let text = replace_once(BASE22, "2 8 2 1 1 1 2 5", "2 8 2 1 1 1 2 9");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: element 2 refers to node 9, which is not in $Nodes",
                line_of(&text, "2 8 2 1 1 1 2 9")
            )
        );
    }

    #[test]
    fn unsupported_versions() {
        for v in ["3.0", "4.0", "2.1", "4"] {
            let text = replace_once(BASE41, "4.1 0 8", &format!("{v} 0 8"));
            assert_eq!(
                err(text.as_bytes()),
                format!(
                    "t.msh:2: unsupported MSH version {v}; supported versions are 4.1 \
                     (ASCII or binary) and 2.2 (ASCII)"
                )
            );
        }
        let text = replace_once(BASE22, "2.2 0 8", "2.2 1 8");
        assert_eq!(
            err(text.as_bytes()),
            "t.msh:2: binary MSH 2.2 files are not supported; supported versions are 4.1 \
             (ASCII or binary) and 2.2 (ASCII)"
        );
        assert_eq!(
            err(b"solid cube\nfacet normal 0 0 1\n"),
            "t.msh:1: not a Gmsh MSH file: expected $MeshFormat, found 'solid'"
        );
    }

    #[test]
    fn missing_or_wrong_end_marker() {
        let text = replace_once(BASE41, "$EndElements\n", "");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: unexpected end of file in $Elements (expected $EndElements)",
                line_of(&text, "7 50 60 30")
            )
        );
        let text = replace_once(BASE41, "$EndElements\n", "$EndElement\n");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: expected $EndElements, found '$EndElement'",
                line_of(&text, "$EndElement")
            )
        );
        // One more element than the count says.
        let text = replace_once(BASE22, "$Elements\n6\n", "$Elements\n5\n");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: expected $EndElements, found '6' \
                 (do the counts in the section match its data?)",
                line_of(&text, "6 1 2 0 1 3 4")
            )
        );
    }

    #[test]
    fn counts_that_do_not_match() {
        let text = replace_once(BASE41, "6 7 1 7", "6 8 1 8");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: the $Elements header announces 8 elements but its blocks hold 7",
                line_of(&text, "6 8 1 8")
            )
        );
        let text = replace_once(BASE41, "3 6 10 60", "3 5 10 60");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: the $Nodes header announces 5 nodes but its blocks hold 6",
                line_of(&text, "3 5 10 60")
            )
        );
    }

    #[test]
    fn other_errors() {
        let text = replace_once(BASE41, "2 1 0\n$EndNodes", "2 1 0.5\n$EndNodes");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: node 60 has z = 0.5: 3D meshes are not supported \
                 (all nodes must lie in the plane z = 0)",
                line_of(&text, "2 1 0.5")
            )
        );
        let text = replace_once(BASE22, "20 4 0 0", "2 4 0 0");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: node tag 2 appears twice in $Nodes",
                line_of(&text, "2 4 0 0")
            )
        );
        // A node listed twice in an element is refused where it is read.
        let text = replace_once(BASE41, "5 10 20 30 40", "5 10 20 20 40");
        assert_eq!(
            err(text.as_bytes()),
            format!(
                "t.msh:{}: element 5 lists node 20 twice",
                line_of(&text, "5 10 20 20 40")
            )
        );
        // A degenerate cell is rejected by the mesh builder, naming the element.
        let text = replace_once(BASE41, "5 10 20 30 40", "5 10 20 40 30");
        assert_eq!(
            err(text.as_bytes()),
            "t.msh: cell 5 (Quad4) is inverted or tangled (its Jacobian changes sign or vanishes)"
        );
        let text = replace_once(BASE41, "$Nodes\n", "$EndFoo\n");
        assert!(err(text.as_bytes()).contains("'$EndFoo' closes no open section"));
    }

    #[test]
    fn read_names_the_file() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/mesh/gmsh.rs");
        let e = read(Path::new(path)).unwrap_err().to_string();
        assert_eq!(
            e,
            format!("{path}:1: not a Gmsh MSH file: expected $MeshFormat, found '//!'")
        );
        let missing = concat!(env!("CARGO_MANIFEST_DIR"), "/no/such/file.msh");
        let e = read(Path::new(missing)).unwrap_err().to_string();
        assert!(e.starts_with(&format!("{missing}: ")), "{e}");
    }

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
}
