//! The `rne` command (docs/design.md §5).

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = rne_cli::Cli::parse();
    rne_cli::quiet_panics();
    match rne_cli::guarded(|| rne_cli::run(cli, &mut std::io::stdout().lock())) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader went away (`rne show panda | head`): what it wanted was written.
        Err(error) if error.is_broken_pipe() => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}
