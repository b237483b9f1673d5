//! A user crate with generated modules links the runtime and nothing of the generator.

use std::process::Command;

#[test]
fn the_no_std_crate_links_only_rne_codegen_and_the_runtime() {
    let workspace = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let output = Command::new(env!("CARGO"))
        .args([
            "tree",
            "--offline",
            "-e",
            "normal,no-proc-macro",
            "-p",
            "rne-no-std-check",
            "--prefix",
            "none",
            "--format",
            "{p}",
        ])
        .current_dir(workspace)
        .output()
        .expect("cargo runs");
    assert!(
        output.status.success(),
        "cargo tree failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let tree = String::from_utf8(output.stdout).expect("UTF-8");
    let mut crates: Vec<&str> = tree
        .lines()
        .filter_map(|line| line.split_whitespace().next())
        .collect();
    crates.sort_unstable();
    crates.dedup();
    assert_eq!(
        crates,
        ["rne-codegen", "rne-no-std-check", "rne-runtime"],
        "the no_std crate links more than the runtime:\n{tree}"
    );
}
