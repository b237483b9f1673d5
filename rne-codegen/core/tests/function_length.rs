//! Functions stay short: no function of the workspace's sources is longer than [`LIMIT`]
//! lines, so that each stage of the pipeline, each pass of a recursion, each integrator and
//! each report reads top to bottom on one screen.
//!
//! Covered: every member crate of the workspace (read from the root `Cargo.toml`, so a new
//! crate is covered when it joins) — its library and binary sources (`src/`), its `build.rs`,
//! its benchmarks (`benches/`) and its examples (`examples/`). Not covered: integration tests
//! (`tests/` directories), whose table-like checks may run longer.

use std::path::{Path, PathBuf};

/// The most lines a function may span, its signature and closing brace included.
const LIMIT: usize = 80;

/// The directories of a member crate whose Rust files are covered.
const COVERED_DIRECTORIES: [&str; 3] = ["src", "benches", "examples"];

/// The Rust files under `dir`.
fn sources(dir: &Path, found: &mut Vec<PathBuf>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            sources(&path, found);
        } else if path.extension().is_some_and(|e| e == "rs") {
            found.push(path);
        }
    }
}

/// `line` without its string and character literals and its `//` comment, so that the braces
/// left are the code's.
fn code(line: &str) -> String {
    let mut out = String::new();
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' => {
                while let Some(c) = chars.next() {
                    match c {
                        '\\' => {
                            chars.next();
                        }
                        '"' => break,
                        _ => {}
                    }
                }
            }
            // A character literal ('{', '\n'); a lifetime ('a) has no closing quote.
            '\'' if matches!(chars.clone().nth(1), Some('\'')) => {
                chars.nth(1);
            }
            '\'' if chars.peek() == Some(&'\\') => {
                chars.nth(1); // the backslash and the escaped character
                chars.find(|&c| c == '\'');
            }
            '/' if chars.peek() == Some(&'/') => break,
            c => out.push(c),
        }
    }
    out
}

/// Whether `line` starts a function item (`fn`, `pub fn`, `pub(crate) const fn`, ...).
fn starts_function(line: &str) -> Option<&str> {
    let mut words = line.split_whitespace();
    let mut word = words.next()?;
    while word.starts_with("pub") || ["const", "async", "unsafe", "extern"].contains(&word) {
        word = words.next()?;
    }
    let name = words.next()?;
    (word == "fn").then(|| name.split(['(', '<']).next().unwrap_or(name))
}

/// (lines, name, first line) of every function of `text` longer than [`LIMIT`].
fn long_functions(text: &str) -> Vec<(usize, String, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut long = Vec::new();
    for (start, line) in lines.iter().enumerate() {
        let Some(name) = starts_function(line) else {
            continue;
        };
        let mut depth = 0i64;
        let mut opened = false;
        for (end, line) in lines.iter().enumerate().skip(start) {
            let code = code(line);
            if !opened && code.contains(';') && !code.contains('{') {
                break; // a declaration without a body
            }
            depth += code.matches('{').count() as i64 - code.matches('}').count() as i64;
            opened |= code.contains('{');
            if opened && depth <= 0 {
                if end - start + 1 > LIMIT {
                    long.push((end - start + 1, name.to_owned(), start + 1));
                }
                break;
            }
        }
    }
    long
}

/// The paths of the workspace's member crates, relative to its root, as the `members` list of
/// its manifest `manifest` names them.
fn members(manifest: &str) -> Vec<String> {
    let Some(start) = manifest.find("members = [") else {
        return Vec::new();
    };
    let list = &manifest[start + "members = [".len()..];
    let list = &list[..list.find(']').unwrap_or(list.len())];
    list.split(',')
        .map(|entry| entry.trim().trim_matches('"').to_owned())
        .filter(|entry| !entry.is_empty())
        .collect()
}

/// The covered Rust files of every member crate of the workspace at `root`.
fn covered_sources(root: &Path) -> Vec<PathBuf> {
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).expect("the root manifest");
    let members = members(&manifest);
    assert!(members.len() > 20, "the members are found: {members:?}");
    let mut files = Vec::new();
    for member in &members {
        let crate_dir = root.join(member);
        assert!(
            crate_dir.join("src").is_dir(),
            "{member} has its sources in src/"
        );
        for dir in COVERED_DIRECTORIES {
            if crate_dir.join(dir).is_dir() {
                sources(&crate_dir.join(dir), &mut files);
            }
        }
        if crate_dir.join("build.rs").is_file() {
            files.push(crate_dir.join("build.rs"));
        }
    }
    files
}

#[test]
fn no_function_of_the_covered_crates_is_longer_than_the_limit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let files = covered_sources(&root);
    assert!(files.len() > 300, "the sources are found: {}", files.len());
    for (member, file) in [
        ("rne-codegen/core", "src/module.rs"),
        ("rne-symbolic", "src/newton_euler.rs"),
        ("rne-models/cli", "src/stats.rs"),
        ("examples", "examples/ilqr_swing_up.rs"),
        ("rne-codegen/jit", "src/model.rs"),
    ] {
        let path = root.join(member).join(file);
        assert!(files.contains(&path), "{} is covered", path.display());
    }
    let mut report = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).expect("a readable source");
        for (lines, name, at) in long_functions(&text) {
            report.push(format!("{}:{at} `{name}`: {lines} lines", file.display()));
        }
    }
    assert!(
        report.is_empty(),
        "functions longer than {LIMIT} lines (split them into named steps):\n{}",
        report.join("\n")
    );
}

/// The member list is read from the manifest, entry by entry.
#[test]
fn the_members_are_read_from_the_manifest() {
    let manifest = "[workspace]\nresolver = \"2\"\nmembers = [\n    \"a\",\n    \"b/c\",\n]\n\n[x]\ny = [\"z\"]\n";
    assert_eq!(members(manifest), vec!["a".to_owned(), "b/c".to_owned()]);
    assert!(members("[package]\nname = \"p\"\n").is_empty());
}

/// The scanner measures a function from its signature to its closing brace, past braces in
/// strings, characters and comments.
#[test]
fn the_scanner_measures_functions() {
    let body = "    let s = \"}}\"; // }\n    let c = ('}', '\\'', '\\n');\n".repeat(40);
    let text = format!("pub(crate) fn long<'a>(x: &'a str) {{\n{body}}}\nfn short() {{}}\n");
    assert_eq!(long_functions(&text), vec![(82, "long".to_owned(), 1)]);
    let declaration = format!("    fn required(&self);\n{}", "\n".repeat(100));
    assert!(long_functions(&declaration).is_empty());
}
