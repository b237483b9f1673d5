//! What `rne bench` and `rne stress` share around their runs: a progress line per step on
//! stderr and, once the report is written to its directory, the report and where it went.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::CliError;

/// Creates `dir` (`--out`) and checks that a file can be written in it, before any work: a
/// run of minutes must not end in "cannot write".
pub(crate) fn prepare_out(dir: &Path) -> Result<(), CliError> {
    let refuse = |e: std::io::Error| {
        CliError::Argument(format!(
            "--out {}: cannot write there ({e}); give a directory that can be created and written",
            dir.display()
        ))
    };
    std::fs::create_dir_all(dir).map_err(refuse)?;
    let probe = dir.join(".rne-write-check");
    std::fs::write(&probe, b"").map_err(refuse)?;
    std::fs::remove_file(&probe).map_err(refuse)
}

/// A run that reports its steps as it goes and its files at the end.
pub(crate) struct LongRun {
    start: Instant,
    quiet: bool,
}

impl LongRun {
    /// Starts the clock; `quiet` silences the progress lines.
    pub(crate) fn start(quiet: bool) -> LongRun {
        LongRun {
            start: Instant::now(),
            quiet,
        }
    }

    /// `[   12.3 s] step` on stderr, unless quiet.
    pub(crate) fn progress(&self, step: &str) {
        if !self.quiet {
            eprintln!("[{:7.1} s] {step}", self.start.elapsed().as_secs_f64());
        }
    }

    /// Prints the report's `markdown`, then `wrote N files to DIR in T s`.
    pub(crate) fn finish(
        &self,
        out: &mut dyn Write,
        markdown: &str,
        written: &[PathBuf],
        dir: &Path,
    ) -> std::io::Result<()> {
        write!(out, "{markdown}")?;
        writeln!(
            out,
            "\nwrote {} files to {} in {:.1} s",
            written.len(),
            dir.display(),
            self.start.elapsed().as_secs_f64()
        )
    }
}
