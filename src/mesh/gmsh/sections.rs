//! The section loop, `$MeshFormat`, `$PhysicalNames`, skipped sections, and what the
//! `$Nodes` and `$Elements` sections of both versions share (node and element checks).

use super::binary::le_i32;
use super::{cell_kind, show, unsupported_type_name, Parser, Pos, Version};
use super::{CellKind, Mesh, SUPPORTED_TYPES, SUPPORTED_VERSIONS};
use crate::error::{Error, Result};

impl<'a> Parser<'a> {
    // ---------------------------------------------------------------- sections

    pub(super) fn run(mut self) -> Result<Mesh> {
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

    pub(super) fn duplicate(&self, p: Pos, name: &str) -> Error {
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

    pub(super) fn add_node(
        &mut self,
        tag: u64,
        tag_pos: Pos,
        x: [f64; 3],
        px: Pos,
        pz: Pos,
    ) -> Result<()> {
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

    pub(super) fn element_kind(&self, gmsh_type: i64, p: Pos) -> Result<CellKind> {
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
    pub(super) fn element_nodes(&mut self, n: usize, label: u64, p: Pos) -> Result<()> {
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
}
