//! The seeds: every robot file committed in the repository's robot and fixture folders, the
//! files `git ls-files '*.urdf' '*.toml'` lists there, found by walking the tree (sorted, so
//! runs replay on any checkout).

use std::path::{Path, PathBuf};

use rne_symbolic::spec::RobotFormat;

/// Folders whose robot files are seeds: the robots, the test fixtures, the UI specs and the
/// fuzzing regressions.
const SEED_FOLDERS: &[&str] = &[
    "robots",
    "fixtures",
    "specs",
    "urdf_fixtures",
    "fuzz_regressions",
];

/// Folders never walked: build output and version control.
const SKIPPED: &[&str] = &["target", ".git", "node_modules"];

/// A seed robot file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Seed {
    /// Its path relative to the repository.
    pub path: String,
    /// Its format, by extension.
    pub format: RobotFormat,
    /// Its text.
    pub text: String,
}

/// The seed files of `format` under `root`, sorted by path.
pub fn seeds(root: &Path, format: RobotFormat) -> std::io::Result<Vec<Seed>> {
    let mut paths = Vec::new();
    walk(root, &mut paths)?;
    paths.sort();
    let mut found = Vec::new();
    for path in paths {
        let relative = path.strip_prefix(root).unwrap_or(&path);
        let in_seed_folder = relative.components().any(|c| {
            SEED_FOLDERS
                .iter()
                .any(|f| c.as_os_str() == std::ffi::OsStr::new(f))
        });
        let is_format = RobotFormat::from_path(&path).ok() == Some(format);
        if in_seed_folder && is_format && path.file_name() != Some("Cargo.toml".as_ref()) {
            found.push(Seed {
                path: relative.display().to_string(),
                format,
                // A regression file may hold bytes that are not UTF-8 (what it tests): its
                // text is mutated with them replaced.
                text: String::from_utf8_lossy(&std::fs::read(&path)?).into_owned(),
            });
        }
    }
    Ok(found)
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let path = entry.path();
        let name = entry.file_name();
        if entry.file_type()?.is_dir() {
            let hidden = name.to_string_lossy().starts_with('.');
            if !hidden && !SKIPPED.iter().any(|s| name == std::ffi::OsStr::new(s)) {
                walk(&path, out)?;
            }
        } else {
            out.push(path);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_committed_fixtures_of_each_format() {
        let root = crate::repository_root();
        let urdf = seeds(&root, RobotFormat::Urdf).unwrap();
        let toml = seeds(&root, RobotFormat::Toml).unwrap();
        let has = |seeds: &[Seed], path: &str| seeds.iter().any(|s| s.path == path);
        assert!(has(&urdf, "rne-models/robots/panda.urdf"));
        assert!(has(&urdf, "rne-models/corpus/tests/fixtures/baxter.urdf"));
        assert!(has(&toml, "tests/fixtures/robots/hopper-floating.toml"));
        assert!(has(&toml, "tests/ui/specs/negative_mass.toml"));
        assert!(!toml.iter().any(|s| s.path.ends_with("Cargo.toml")));
        assert!(
            urdf.len() >= 30 && toml.len() >= 25,
            "{} {}",
            urdf.len(),
            toml.len()
        );
    }
}
