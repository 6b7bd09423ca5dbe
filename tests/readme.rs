//! The case-file example in the README is valid (every key it shows is accepted).

use tribo::case::schema::CaseFile;

#[test]
fn readme_case_example_parses() {
    let readme = include_str!("../README.md");
    let start = readme.find("```toml\n").expect("a toml example") + 8;
    let end = start + readme[start..].find("```").unwrap();
    let case: CaseFile = toml::from_str(&readme[start..end]).unwrap();
    assert_eq!(case.contact.len(), 1);
    assert_eq!(case.output.probe.len(), 1);
    assert!(case.output.hertz.is_some());
}

#[test]
fn readme_expression_example_compiles() {
    let readme = include_str!("../README.md");
    let at = readme
        .find("#### Values as expressions")
        .expect("the section");
    let start = at + readme[at..].find("```toml\n").expect("its example") + 8;
    let end = start + readme[start..].find("```").unwrap();
    let text = format!(
        "[mesh]\ngenerator = \"rectangle\"\nwidth = 1.0\nheight = 1.0\nnx = 1\nny = 1\n{}",
        &readme[start..end]
    );
    let case: CaseFile = toml::from_str(&text).unwrap();
    // every expression compiles (the checks compile them)
    tribo::case::checks::check(&case).unwrap();
    assert_eq!(case.displacement.len(), 1);
    assert_eq!(case.pressure.len(), 1);
    assert_eq!(case.relation.len(), 1);
}
