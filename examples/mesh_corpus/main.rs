//! Writes the malformed-mesh corpus: `cargo run --release --example mesh_corpus` (re)writes
//! `tests/corpus/meshes/` and its `expected.tsv` (see the README there). Each entry is one
//! defect applied to a small valid mesh (MSH 2.2, MSH 4.1 and VTU written here by hand, MED
//! by our writer), with the outcome `tribo mesh info FILE` must give: an error holding the
//! detail, or the node and cell counts of an accepted mesh. The files are committed; this
//! program documents how each was made and lets the set be extended.

mod med;
mod msh22;
mod msh41;
mod vtu;

use std::path::PathBuf;

/// One corpus file: its name, bytes, and `error` + message substring or `ok` + counts.
pub struct Entry {
    pub name: String,
    pub bytes: Vec<u8>,
    pub expect: &'static str,
    pub detail: String,
}

/// Collects the entries of one base file.
pub struct Set<'a> {
    pub base: &'a str,
    pub ext: &'static str,
    pub prefix: &'static str,
    pub out: Vec<Entry>,
}

impl Set<'_> {
    fn push(&mut self, name: &str, bytes: Vec<u8>, expect: &'static str, detail: &str) {
        self.out.push(Entry {
            name: format!("{}_{name}.{}", self.prefix, self.ext),
            bytes,
            expect,
            detail: detail.to_string(),
        });
    }
    /// The base with the first `from` replaced by `to` (which must be there).
    pub fn sub(&mut self, name: &str, from: &str, to: &str, detail: &str) {
        assert!(self.base.contains(from), "{name}: '{from}' not in the base");
        let t = self.base.replacen(from, to, 1);
        self.push(name, t.into_bytes(), "error", detail);
    }
    /// Same, but the result is a valid mesh with these counts.
    pub fn sub_ok(&mut self, name: &str, from: &str, to: &str, nodes: usize, cells: usize) {
        assert!(self.base.contains(from), "{name}: '{from}' not in the base");
        let t = self.base.replacen(from, to, 1);
        self.push(
            name,
            t.into_bytes(),
            "ok",
            &format!("{nodes} nodes, {cells} cells"),
        );
    }
    /// The base cut just after the first `after` (its end included).
    pub fn cut(&mut self, name: &str, after: &str, detail: &str) {
        let at = self.base.find(after).expect(after) + after.len();
        let t = self.base[..at].to_string();
        self.push(name, t.into_bytes(), "error", detail);
    }
    /// Any text, with the expected error.
    pub fn text(&mut self, name: &str, text: &str, detail: &str) {
        self.push(name, text.as_bytes().to_vec(), "error", detail);
    }
    pub fn bytes(&mut self, name: &str, bytes: Vec<u8>, detail: &str) {
        self.push(name, bytes, "error", detail);
    }
    pub fn ok(&mut self, name: &str, bytes: Vec<u8>, nodes: usize, cells: usize) {
        self.push(name, bytes, "ok", &format!("{nodes} nodes, {cells} cells"));
    }
}

fn main() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/meshes");
    let mut all: Vec<Entry> = vec![];
    all.extend(msh22::entries());
    all.extend(msh41::entries());
    all.extend(vtu::entries());
    all.extend(med::entries());
    let mut names: Vec<&str> = all.iter().map(|e| e.name.as_str()).collect();
    names.sort();
    let n = names.len();
    names.dedup();
    assert_eq!(n, names.len(), "two entries share a name");
    // the files are rewritten whole; the README stays
    let files = dir.join("files");
    if files.exists() {
        std::fs::remove_dir_all(&files).unwrap();
    }
    std::fs::create_dir_all(&files).unwrap();
    let mut table = String::from("file\texpect\tdetail\n");
    for e in &all {
        std::fs::write(files.join(&e.name), &e.bytes).unwrap();
        table.push_str(&format!("{}\t{}\t{}\n", e.name, e.expect, e.detail));
    }
    std::fs::write(dir.join("expected.tsv"), table).unwrap();
    let errors = all.iter().filter(|e| e.expect == "error").count();
    println!(
        "{} files in {}: {errors} error, {} ok",
        all.len(),
        dir.display(),
        all.len() - errors
    );
}
