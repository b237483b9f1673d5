//! The TOML examples of `robots/README.md` are valid links.

use rne_symbolic::spec::{self, LoadOptions};

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
        let model = spec::parse_str(&text, "example.toml", &LoadOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(model.dof(), 1);
    }
}
