//! The mimic error suggests `--mimic free` exactly when loading with it works: a URDF whose
//! mimic joint follows a joint the file does not have (as published hand descriptions do) is
//! refused with the suggestion and loads with `--mimic free`; a mimic error that `--mimic free`
//! does not cure (a loop of followers, strict validation of the dropped mimic) gets no
//! suggestion.

use std::process::{Command, Output};

fn fixture(name: &str) -> String {
    format!("{}/tests/fixtures/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn rne(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rne"))
        .args(args)
        .output()
        .expect("the rne binary runs")
}

/// The one line of stderr of a command that must fail with status 1.
fn error_line(args: &[&str]) -> String {
    let output = rne(args);
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
    assert_eq!(
        stderr.lines().count(),
        1,
        "{args:?}: one line, got {stderr}"
    );
    assert!(stderr.starts_with("error: "), "{stderr}");
    stderr
}

const SUGGESTION: &str = "(load it with `--mimic free` to treat mimic joints as independent)";

#[test]
fn a_mimic_of_a_missing_joint_suggests_mimic_free_which_loads_it() {
    let file = fixture("mimic-missing-leader.urdf");
    for command in [
        vec!["check", file.as_str()],
        vec!["show", file.as_str(), "--what", "g"],
        vec!["eval", file.as_str(), "--q", "0.1"],
    ] {
        let e = error_line(&command);
        assert!(e.contains("index_q1"), "names the missing leader: {e}");
        assert!(e.contains("index_q2"), "names the follower: {e}");
        assert!(e.trim_end().ends_with(SUGGESTION), "{command:?}: {e}");
    }
    let free = rne(&["check", &file, "--mimic", "free"]);
    let stdout = String::from_utf8_lossy(&free.stdout);
    assert!(
        free.status.success(),
        "{}",
        String::from_utf8_lossy(&free.stderr)
    );
    assert!(
        stdout.contains("index_q2"),
        "the follower is a joint: {stdout}"
    );
    let evaluated = rne(&[
        "eval", &file, "--mimic", "free", "--q", "0.1,0.2", "--what", "g",
    ]);
    assert!(
        evaluated.status.success(),
        "{}",
        String::from_utf8_lossy(&evaluated.stderr)
    );
}

#[test]
fn no_suggestion_where_mimic_free_would_not_load_the_file() {
    let missing = fixture("mimic-missing-leader.urdf");
    // Strict validation makes the dropped mimic's warning an error: free does not load it.
    let strict = error_line(&["check", &missing, "--strict"]);
    assert!(!strict.contains("--mimic free"), "{strict}");
    assert!(strict.contains("index_q1"), "{strict}");
    let free_strict = rne(&["check", &missing, "--strict", "--mimic", "free"]);
    assert_eq!(free_strict.status.code(), Some(1));
    // Followers that follow each other in a loop are refused with mimic joints free too.
    let looped = fixture("mimic-loop.urdf");
    let e = error_line(&["check", &looped]);
    assert!(e.contains("loop"), "{e}");
    assert!(!e.contains("--mimic free"), "{e}");
    assert_eq!(
        rne(&["check", &looped, "--mimic", "free"]).status.code(),
        Some(1)
    );
}
