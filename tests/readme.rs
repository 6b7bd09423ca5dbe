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
