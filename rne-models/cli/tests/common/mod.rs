//! What the command-line tests share: running `rne` in the test's process.

use clap::Parser;
use rne_cli::{run, Cli};

/// Runs `rne ARGS` in this process: its standard output, or its error as `rne` prints it (a
/// usage error from clap or the command's own).
pub fn rne(args: &[&str]) -> Result<String, String> {
    let cli = Cli::try_parse_from(std::iter::once("rne").chain(args.iter().copied()))
        .map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    run(cli, &mut out).map_err(|e| e.to_string())?;
    Ok(String::from_utf8(out).expect("utf-8 output"))
}
