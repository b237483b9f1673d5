//! The TOML examples of `robots/README.md` are valid links.

use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};

#[test]
fn readme_examples_parse() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/robots/README.md");
    let readme = std::fs::read_to_string(path).unwrap();
    let blocks: Vec<&str> = readme
        .split("```toml\n")
        .skip(1)
        .filter_map(|b| b.split("```").next())
        .collect();
    assert_eq!(blocks.len(), 3);
    for block in blocks {
        let text = format!("name = \"example\"\n{block}");
        let model = read_robot(
            Description::toml(&text, "example.toml"),
            &LoadOptions::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(model.dof(), 1);
    }
}
