//! Every command in README.md's code blocks runs as written.
//!
//! Each `rne …` line of a `sh` block is run with the `rne` binary this package builds, in a
//! scratch directory that holds the files the README names (`tests/` of the repository, the
//! data `rne identify` and `rne corpus` read); bracketed options (`[--json]`) are usage
//! notation, so each command runs once without them and once with all of them, alternatives
//! (`jit|compiled`) taken first, and every alternative must parse. The commands listed in
//! [`SKIPPED`] (too long for the tests, or needing Pinocchio) and every `cargo …` line (each a
//! build of its own) are checked at the `--help` level instead: the `rne` arguments parse, the
//! packages, binaries and examples exist.

use std::path::{Path, PathBuf};
use std::process::Command;

use clap::Parser;
use rne_cli::Cli;

/// What of a README command is not run.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Skip {
    /// The command: it only parses.
    Whole,
    /// The command with its bracketed options (which parse); without them it runs.
    Options,
}

/// README commands not run, by the start of their bare form: what is skipped, and why.
const SKIPPED: &[(&str, Skip, &str)] = &[
    (
        "rne verify",
        Skip::Whole,
        "CI runs it on its own (`./target/debug/rne verify`, .ci/run): every robot and kernel",
    ),
    (
        "rne stress --out",
        Skip::Whole,
        "the full stability report: minutes of work",
    ),
    (
        "rne bench --out",
        Skip::Whole,
        "the full benchmark: minutes of timing; its --pinocchio needs Pinocchio",
    ),
    (
        "rne bench ur5",
        Skip::Options,
        "--pinocchio needs Pinocchio and CppADCodeGen (tools/peers/setup.sh)",
    ),
];

/// The repository's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A word of a README command line, or an optional group's bracket.
#[derive(Clone, Debug, PartialEq)]
enum Token {
    Word(String),
    Open,
    Close,
}

/// The `rne …` and `cargo …` lines of README.md's `sh` code blocks, comments cut.
fn readme_commands() -> Vec<String> {
    let text = std::fs::read_to_string(root().join("README.md")).expect("README.md");
    let mut commands = Vec::new();
    let mut in_shell = None;
    for line in text.lines() {
        if let Some(info) = line.trim_start().strip_prefix("```") {
            in_shell = match in_shell {
                None => Some(matches!(info.trim(), "sh" | "bash" | "shell" | "")),
                Some(_) => None,
            };
            continue;
        }
        if in_shell == Some(true) {
            let command = without_comment(line).trim();
            if command.starts_with("rne ") || command.starts_with("cargo ") {
                commands.push(command.to_owned());
            }
        }
    }
    commands
}

/// `line` up to a `#` that starts a shell comment (after a blank, outside quotes).
fn without_comment(line: &str) -> &str {
    let mut quoted = false;
    let mut previous = ' ';
    for (i, c) in line.char_indices() {
        match c {
            '"' => quoted = !quoted,
            '#' if !quoted && previous.is_whitespace() => return &line[..i],
            _ => {}
        }
        previous = c;
    }
    line
}

/// The words of `command` as a shell splits them (double quotes removed), with `[` and `]`
/// outside quotes as the brackets of optional groups.
fn tokens(command: &str) -> Vec<Token> {
    let mut tokens = Vec::new();
    let mut word = String::new();
    let mut quoted = false;
    let mut in_word = false;
    let flush = |word: &mut String, in_word: &mut bool, tokens: &mut Vec<Token>| {
        if *in_word {
            tokens.push(Token::Word(std::mem::take(word)));
            *in_word = false;
        }
    };
    for c in command.chars() {
        match c {
            '"' => {
                quoted = !quoted;
                in_word = true;
            }
            '[' if !quoted && !in_word => tokens.push(Token::Open),
            ']' if !quoted => {
                flush(&mut word, &mut in_word, &mut tokens);
                tokens.push(Token::Close);
            }
            c if c.is_whitespace() && !quoted => flush(&mut word, &mut in_word, &mut tokens),
            c => {
                word.push(c);
                in_word = true;
            }
        }
    }
    flush(&mut word, &mut in_word, &mut tokens);
    assert!(
        !quoted,
        "unbalanced quotes in the README command `{command}`"
    );
    tokens
}

/// The words of a command: without its optional groups (`optional` false) or with every one,
/// each `a|b|c` as its alternative `alternative` (the last when it has fewer).
fn form(tokens: &[Token], optional: bool, alternative: usize) -> Vec<String> {
    let mut depth = 0usize;
    let mut words = Vec::new();
    for token in tokens {
        match token {
            Token::Open => depth += 1,
            Token::Close => depth = depth.checked_sub(1).expect("balanced brackets"),
            Token::Word(w) if depth == 0 || optional => {
                let choices: Vec<&str> = w.split('|').collect();
                words.push(choices[alternative.min(choices.len() - 1)].to_owned());
            }
            Token::Word(_) => {}
        }
    }
    assert_eq!(depth, 0, "unbalanced brackets in {tokens:?}");
    words
}

/// The largest number of alternatives of a word of `tokens`.
fn alternatives(tokens: &[Token]) -> usize {
    tokens
        .iter()
        .map(|t| match t {
            Token::Word(w) => w.split('|').count(),
            _ => 1,
        })
        .max()
        .unwrap_or(1)
}

/// Parses `words` (starting with `rne`) as the command line would, without running them.
fn parses(words: &[String]) -> Result<(), String> {
    Cli::try_parse_from(words)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

/// A scratch directory holding what the README's commands read: `tests/` of the repository,
/// `values.json` and `DIR` for `rne corpus` (Pinocchio's committed values and their robots),
/// and an empty `docs/` for its table.
fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rne-readme-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("docs")).unwrap();
    std::fs::create_dir_all(dir.join("DIR")).unwrap();
    std::os::unix::fs::symlink(root().join("tests"), dir.join("tests")).unwrap();
    let corpus = root().join("rne-models/corpus/tests/fixtures");
    for entry in std::fs::read_dir(&corpus).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "urdf") {
            std::fs::copy(&path, dir.join("DIR").join(path.file_name().unwrap())).unwrap();
        }
    }
    std::fs::copy(corpus.join("pinocchio.json"), dir.join("values.json")).unwrap();
    dir
}

/// Files a command names that an earlier README command does not write: a second data set
/// to validate on, a copy of the first one's.
fn provide(words: &[String], dir: &Path) {
    if words.iter().any(|w| w == "fresh.csv") && !dir.join("fresh.csv").exists() {
        std::fs::copy(dir.join("excite.csv"), dir.join("fresh.csv"))
            .expect("excite.csv, written by the README's `rne identify … --excite` before");
    }
}

/// Runs `words` (starting with `rne`) with the binary in `dir`; the error says what failed.
fn run(words: &[String], dir: &Path) -> Result<(), String> {
    provide(words, dir);
    let start = std::time::Instant::now();
    let output = Command::new(env!("CARGO_BIN_EXE_rne"))
        .args(&words[1..])
        .current_dir(dir)
        .output()
        .map_err(|e| e.to_string())?;
    eprintln!(
        "{:>6.1} s  {}",
        start.elapsed().as_secs_f64(),
        words.join(" ")
    );
    if output.status.success() {
        Ok(())
    } else {
        Err(format!(
            "{:?}: {}",
            output.status,
            String::from_utf8_lossy(&output.stderr)
        ))
    }
}

#[test]
fn every_rne_command_of_the_readme_runs_as_written() {
    let dir = scratch();
    let commands = readme_commands();
    assert!(commands.len() > 20, "the README's commands: {commands:?}");
    let mut failures = Vec::new();
    let mut skips_used = vec![false; SKIPPED.len()];
    for command in commands.iter().filter(|c| c.starts_with("rne ")) {
        let groups = tokens(command);
        for alternative in 0..alternatives(&groups) {
            for optional in [false, true] {
                if let Err(e) = parses(&form(&groups, optional, alternative)) {
                    failures.push(format!("`{command}` does not parse: {e}"));
                }
            }
        }
        let bare = form(&groups, false, 0).join(" ");
        let skip = SKIPPED.iter().position(|(s, _, _)| bare.starts_with(s));
        if let Some(i) = skip {
            skips_used[i] = true;
            let (_, what, why) = SKIPPED[i];
            eprintln!("not run ({what:?}): `{command}`: {why}");
        }
        let forms: &[bool] = match skip.map(|i| SKIPPED[i].1) {
            Some(Skip::Whole) => &[],
            Some(Skip::Options) => &[false],
            None => &[false, true],
        };
        for &optional in forms {
            let words = form(&groups, optional, 0);
            if let Err(e) = run(&words, &dir) {
                failures.push(format!("`{}` fails: {e}", words.join(" ")));
            }
        }
    }
    for ((start, _, _), used) in SKIPPED.iter().zip(skips_used) {
        assert!(used, "`{start}` is skipped but no README command starts so");
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The workspace's members and each one's `Cargo.toml` text.
fn workspace_members() -> Vec<(PathBuf, String)> {
    let manifest = std::fs::read_to_string(root().join("Cargo.toml")).unwrap();
    let list = manifest
        .split_once("members = [")
        .and_then(|(_, rest)| rest.split_once(']'))
        .expect("the workspace's members")
        .0;
    list.split(',')
        .map(|m| m.trim().trim_matches('"'))
        .filter(|m| !m.is_empty())
        .map(|m| {
            let dir = root().join(m);
            let text = std::fs::read_to_string(dir.join("Cargo.toml")).unwrap();
            (dir, text)
        })
        .collect()
}

/// Checks a `cargo …` line without building: `-p` names a workspace package, `--bin` one of
/// its binaries, `--example` one of its examples, and the arguments after `--` of the `rne`
/// binary parse.
fn check_cargo(words: &[String]) -> Result<(), String> {
    let members = workspace_members();
    let value = |flag: &str| {
        words
            .iter()
            .position(|w| w == flag)
            .map(|i| words.get(i + 1).cloned().unwrap_or_default())
    };
    let (args, rest) = match words.iter().position(|w| w == "--") {
        Some(i) => (&words[..i], &words[i + 1..]),
        None => (words, &[][..]),
    };
    match args.get(1).map(String::as_str) {
        Some("run" | "test" | "build") => {}
        Some("install") => {
            let path = value("--path").ok_or("`cargo install` without --path")?;
            let dir = root()
                .join(&path)
                .canonicalize()
                .map_err(|e| format!("{path}: {e}"))?;
            let member = members
                .iter()
                .find(|(m, _)| m.canonicalize().ok().as_ref() == Some(&dir));
            return match member {
                Some((m, text)) if text.contains("[[bin]]") || m.join("src/main.rs").exists() => {
                    Ok(())
                }
                Some(_) => Err(format!("{path} has no binary to install")),
                None => Err(format!("{path} is not a workspace package")),
            };
        }
        _ => return Err(format!("unknown cargo subcommand in {args:?}")),
    }
    let Some(package) = value("-p") else {
        return Ok(());
    };
    let name = format!("name = \"{package}\"");
    let (dir, manifest) = members
        .iter()
        .find(|(_, text)| text.contains(&name))
        .ok_or_else(|| format!("no workspace package `{package}`"))?;
    if let Some(bin) = value("--bin") {
        if !manifest.contains(&format!("name = \"{bin}\"")) {
            return Err(format!("`{package}` has no binary `{bin}`"));
        }
        if bin == "rne" {
            let rne: Vec<String> = std::iter::once("rne".to_owned())
                .chain(rest.iter().cloned())
                .collect();
            parses(&rne)?;
        }
    }
    if let Some(example) = value("--example") {
        let file = dir.join("examples").join(format!("{example}.rs"));
        if !file.exists() {
            return Err(format!("`{package}` has no example `{example}`"));
        }
    }
    Ok(())
}

#[test]
fn every_cargo_command_of_the_readme_names_what_exists() {
    let commands = readme_commands();
    let cargo: Vec<&String> = commands
        .iter()
        .filter(|c| c.starts_with("cargo "))
        .collect();
    assert!(cargo.len() >= 5, "{cargo:?}");
    let failures: Vec<String> = cargo
        .iter()
        .filter_map(|command| {
            let words = form(&tokens(command), false, 0);
            check_cargo(&words)
                .err()
                .map(|e| format!("`{command}`: {e}"))
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_readme_parser_splits_words_options_and_comments_as_a_reader_does() {
    let line = r#"rne show panda --what M [--max-size 300K] [--entry "M[2,3]"]   # a note"#;
    let command = without_comment(line).trim();
    assert_eq!(
        command,
        r#"rne show panda --what M [--max-size 300K] [--entry "M[2,3]"]"#
    );
    let groups = tokens(command);
    assert_eq!(
        form(&groups, false, 0),
        ["rne", "show", "panda", "--what", "M"]
    );
    assert_eq!(
        form(&groups, true, 0),
        [
            "rne",
            "show",
            "panda",
            "--what",
            "M",
            "--max-size",
            "300K",
            "--entry",
            "M[2,3]"
        ]
    );
    let nested = tokens("rne bench --out o [--pinocchio [RUN_SH]] [--engine jit|compiled]");
    assert_eq!(form(&nested, false, 1), ["rne", "bench", "--out", "o"]);
    assert_eq!(
        form(&nested, true, 1),
        [
            "rne",
            "bench",
            "--out",
            "o",
            "--pinocchio",
            "RUN_SH",
            "--engine",
            "compiled"
        ]
    );
    assert_eq!(alternatives(&nested), 2);
}

#[test]
fn the_cargo_check_refuses_names_that_do_not_exist() {
    let check = |command: &str| check_cargo(&form(&tokens(command), false, 0));
    assert_eq!(
        check("cargo run --release -p rne-cli --bin rne -- verify"),
        Ok(())
    );
    assert_eq!(check("cargo install --path rne-models/cli"), Ok(()));
    assert_eq!(
        check("cargo run -p rne-examples --example first_steps"),
        Ok(())
    );
    for wrong in [
        "cargo run -p rne-cli --bin rne -- verifyy",
        "cargo run -p rne-cli --bin rne -- verify --samples",
        "cargo run -p rne-cli --bin rnee -- verify",
        "cargo run -p rne-clii --bin rne -- verify",
        "cargo run -p rne-examples --example no_such_example",
        "cargo install --path rne-models",
        "cargo install --path no/such/dir",
        "cargo bench-everything",
    ] {
        assert!(check(wrong).is_err(), "{wrong}");
    }
}
