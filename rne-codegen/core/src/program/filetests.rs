//! The optimiser's golden files: `tests/filetests/*.test`, each a small input and the text the
//! passes make of it, in the manner of Cranelift's filetests.
//!
//! A file is a header, a line `; expected`, and the expected text:
//!
//! ```text
//! ; What the case shows (comment lines start with `;`).
//! test distribute
//! joints x y z
//! (* 2 (+ x (* 3 y)))
//! ; expected
//! t0 = mul q[1] 6.0
//! …
//! ```
//!
//! `test` names the passes: `lower` (always done: [`Program::lower`]), `distribute`
//! ([`distribute_constants`] before lowering), `fma` ([`Program::fuse_multiply_add`] after it),
//! `order` ([`Program::in_register_order`] after those) and `split part_len=N` (the program is followed by its split plan, in parts of N
//! instructions — the plan of a kernel above [`SPLIT_ABOVE`](crate::SPLIT_ABOVE) instructions,
//! in parts of [`PART_LEN`](crate::PART_LEN), scaled down to a readable size). `joints` and
//! `parameters` name the symbols (default `joints x y z`: q[0], q[1], q[2], and their
//! velocities `Dx`, accelerations `DDx` and forces `tau_x`); each other line is an
//! s-expression ([`ExprGraph::parse_sexpr`]), one output of the program. The expected text is
//! the program's text form (`program/text.rs`).
//!
//! A file whose output differs fails the test with a line diff; `UPDATE_FILETESTS=1 cargo test
//! -p rne-codegen-core filetests` rewrites the expected text of every file instead.

use std::path::{Path, PathBuf};

use rne_symbolic::{ExprGraph, SymbolTable};

use super::Program;
use crate::emit::Bindings;
use crate::linear::distribute_constants;
use crate::split::plan_parts;

/// The line between a file's input and its expected output.
const EXPECTED: &str = "; expected";

/// A golden file's input.
#[derive(Debug, Default)]
struct Case {
    distribute: bool,
    fma: bool,
    /// `order`: [`Program::in_register_order`] after the other passes.
    order: bool,
    /// `split part_len=N`.
    split: Option<usize>,
    joints: Vec<String>,
    parameters: Vec<String>,
    outputs: Vec<String>,
}

impl Case {
    /// Reads the header (the lines before [`EXPECTED`]).
    fn parse(header: &str) -> Result<Case, String> {
        let mut case = Case {
            joints: ["x", "y", "z"].map(String::from).to_vec(),
            ..Case::default()
        };
        let mut tested = false;
        for line in header.lines().map(str::trim) {
            let mut words = line.split_whitespace();
            match words.next() {
                None => {}
                Some(comment) if comment.starts_with(';') => {}
                Some("test") => {
                    tested = true;
                    for pass in words {
                        case.pass(pass)?;
                    }
                }
                Some("joints") => case.joints = words.map(String::from).collect(),
                Some("parameters") => case.parameters = words.map(String::from).collect(),
                Some(_) => case.outputs.push(line.to_owned()),
            }
        }
        if !tested || case.outputs.is_empty() {
            return Err("a case needs a `test` line and at least one s-expression".into());
        }
        Ok(case)
    }

    fn pass(&mut self, pass: &str) -> Result<(), String> {
        match pass {
            "lower" => {}
            "distribute" => self.distribute = true,
            "fma" => self.fma = true,
            "order" => self.order = true,
            _ => match pass.strip_prefix("part_len=").map(str::parse) {
                Some(Ok(len)) if len > 0 => self.split = Some(len),
                _ if pass == "split" => self.split = self.split.or(Some(4)),
                _ => return Err(format!("unknown pass or option `{pass}`")),
            },
        }
        Ok(())
    }

    /// The text the passes make of the input.
    fn run(&self) -> Result<String, String> {
        let mut symbols = SymbolTable::with_joints(self.joints.iter().cloned());
        for parameter in &self.parameters {
            symbols.push_parameter(parameter.clone());
        }
        let mut graph = ExprGraph::new(symbols);
        let mut roots = Vec::new();
        for output in &self.outputs {
            let root = graph
                .parse_sexpr(output)
                .map_err(|e| format!("`{output}`: {e}"))?;
            roots.push(root);
        }
        if self.distribute {
            roots = distribute_constants(&mut graph, &roots);
        }
        let mut program = Program::lower(&graph, &roots);
        if self.fma {
            program = program.fuse_multiply_add();
        }
        if self.order {
            program = program.in_register_order();
        }
        let mut text = program.to_string();
        if let Some(part_len) = self.split {
            let bindings = Bindings::of(&program);
            let named: Vec<bool> = bindings.names.iter().map(Option::is_some).collect();
            let plan = plan_parts(&program, &named, &bindings.prologue, part_len);
            text.push('\n');
            text.push_str(&plan.to_string());
        }
        Ok(text)
    }
}

/// The differing lines of `expected` and `actual`, `-` expected and `+` actual, with the
/// common lines between them (a longest common subsequence: the files are small).
fn diff(expected: &str, actual: &str) -> String {
    let (a, b): (Vec<&str>, Vec<&str>) = (expected.lines().collect(), actual.lines().collect());
    // common[i][j]: the longest common subsequence of a[i..] and b[j..].
    let mut common = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for i in (0..a.len()).rev() {
        for j in (0..b.len()).rev() {
            common[i][j] = if a[i] == b[j] {
                common[i + 1][j + 1] + 1
            } else {
                common[i + 1][j].max(common[i][j + 1])
            };
        }
    }
    let (mut i, mut j, mut out) = (0, 0, String::new());
    while i < a.len() || j < b.len() {
        if i < a.len() && j < b.len() && a[i] == b[j] {
            out += &format!("  {}\n", a[i]);
            (i, j) = (i + 1, j + 1);
        } else if i < a.len() && (j == b.len() || common[i + 1][j] >= common[i][j + 1]) {
            out += &format!("- {}\n", a[i]);
            i += 1;
        } else {
            out += &format!("+ {}\n", b[j]);
            j += 1;
        }
    }
    out
}

/// Checks one file, or rewrites its expected text when `update`; the failure's report.
fn check(path: &Path, update: bool) -> Result<(), String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read: {e}"))?;
    let (header, expected) = match text.split_once(&format!("\n{EXPECTED}\n")) {
        Some((header, expected)) => (header, expected),
        None => (text.trim_end_matches(EXPECTED), ""),
    };
    let actual = Case::parse(header)?.run()?;
    if expected.trim_end() == actual.trim_end() {
        return Ok(());
    }
    if update {
        let rewritten = format!("{}\n{EXPECTED}\n{actual}", header.trim_end());
        return std::fs::write(path, rewritten).map_err(|e| format!("cannot write: {e}"));
    }
    Err(format!(
        "the output differs (- expected, + actual; UPDATE_FILETESTS=1 rewrites it):\n{}",
        diff(expected, &actual)
    ))
}

/// The golden files, in name order.
fn files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/filetests");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "test"))
        .collect();
    files.sort();
    files
}

#[test]
fn filetests() {
    let update = std::env::var_os("UPDATE_FILETESTS").is_some_and(|v| v == "1");
    let files = files();
    assert!(!files.is_empty(), "no golden files");
    let failures: Vec<String> = files
        .iter()
        .filter_map(|path| {
            check(path, update)
                .err()
                .map(|why| format!("{}: {why}", path.display()))
        })
        .collect();
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

#[test]
fn the_diff_marks_removed_and_added_lines() {
    assert_eq!(diff("a\nb\nc\n", "a\nc\nd\n"), "  a\n- b\n  c\n+ d\n");
    assert_eq!(diff("a\nb\nc\n", "a\nx\nc\n"), "  a\n- b\n+ x\n  c\n");
}
