//! Functions stay short: none in rne-codegen-core, the macro, the simulator (rne-sim) or the
//! stress cases (rne-stress) is longer than [`LIMIT`] lines, so that each stage of the
//! pipeline, each integrator and each report reads top to bottom on one screen.

use std::path::{Path, PathBuf};

/// The most lines a function may span, its signature and closing brace included.
const LIMIT: usize = 80;

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

#[test]
fn no_function_of_the_covered_crates_is_longer_than_the_limit() {
    let core = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in [
        "src",
        "../macros/src",
        "../../rne-models/sim/src",
        "../../rne-models/stress/src",
    ] {
        let before = files.len();
        sources(&core.join(dir), &mut files);
        assert!(files.len() > before, "the sources of {dir} are found");
    }
    assert!(files.len() > 40, "the sources are found: {files:?}");
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
