//! The robot files kept in several places stay copies of one another.
//!
//! A crate's tests read their robot files from inside the crate (a crate must build and test
//! from its own directory), so the fixture robots are copied: `planar-elbow.toml` into eight
//! crates, the UR5 and PUMA 560 into four or five. Files of the same name are copies: this test
//! finds every robot file of the repository (`.toml` other than `Cargo.toml`, `.urdf`), groups
//! them by name and requires each group to be byte-identical, but for the files listed in
//! [`DIFFERENT`]. A change to one copy must be made to all.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Files that share a name with copies but differ from them on purpose, with why.
const DIFFERENT: [(&str, &str); 1] = [(
    "rne-models/robots/planar-elbow.toml",
    "the built-in elbow carries the viscous friction of the thesis's damped double pendulum \
     (figure 6.10); the fixtures are chapter 4's model, without it",
)];

/// Directories no robot file of the repository is in.
const SKIPPED: [&str; 3] = ["target", ".git", "node_modules"];

fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ is inside the repository")
        .to_path_buf()
}

/// Every robot file under `dir`, relative to `root`.
fn robot_files(root: &Path, dir: &Path, found: &mut Vec<PathBuf>) {
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for entry in entries {
        let path = entry.expect("a directory entry").path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default();
        if path.is_dir() {
            if !SKIPPED.contains(&name) {
                robot_files(root, &path, found);
            }
        } else if (name.ends_with(".toml") && name != "Cargo.toml") || name.ends_with(".urdf") {
            found.push(
                path.strip_prefix(root)
                    .expect("under the root")
                    .to_path_buf(),
            );
        }
    }
}

/// The groups of two or more files of the same name, each sorted.
fn same_names(files: Vec<PathBuf>) -> BTreeMap<String, Vec<PathBuf>> {
    let mut groups: BTreeMap<String, Vec<PathBuf>> = BTreeMap::new();
    for file in files {
        let name = file
            .file_name()
            .expect("a file")
            .to_string_lossy()
            .into_owned();
        groups.entry(name).or_default().push(file);
    }
    groups.retain(|_, files| files.len() > 1);
    groups.values_mut().for_each(|files| files.sort());
    groups
}

#[test]
fn copies_of_a_robot_file_are_identical() {
    let root = repository();
    let mut files = Vec::new();
    robot_files(&root, &root, &mut files);
    let groups = same_names(files);
    assert!(
        groups.contains_key("planar-elbow.toml") && groups.contains_key("ur5.urdf"),
        "the known copies are found: {groups:?}"
    );
    let different = |file: &Path| DIFFERENT.iter().any(|(path, _)| Path::new(path) == file);
    let mut mismatches = Vec::new();
    for (name, group) in &groups {
        let copies: Vec<&PathBuf> = group.iter().filter(|f| !different(f)).collect();
        let read = |file: &Path| std::fs::read(root.join(file)).expect("a readable file");
        let first = read(copies[0]);
        for copy in &copies[1..] {
            if read(copy) != first {
                let (a, b) = (copies[0].display(), copy.display());
                mismatches.push(format!("{name}: {a} and {b} differ"));
            }
        }
    }
    assert!(
        mismatches.is_empty(),
        "copies of a robot file differ (make the same change to every copy):\n{}",
        mismatches.join("\n")
    );
}

/// Every file let differ still exists and still has copies, so that the list stays true.
#[test]
fn the_files_let_differ_have_copies() {
    let root = repository();
    let mut files = Vec::new();
    robot_files(&root, &root, &mut files);
    let groups = same_names(files);
    for (path, why) in DIFFERENT {
        let path = Path::new(path);
        let name = path.file_name().unwrap().to_string_lossy();
        let group = groups.get(name.as_ref());
        assert!(
            group.is_some_and(|g| g.iter().any(|f| f == path) && g.len() > 1),
            "{} ({why}) is listed as differing from its copies but has none",
            path.display()
        );
    }
}
