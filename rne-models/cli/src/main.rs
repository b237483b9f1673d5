//! The `rne` command (docs/design.md §5).

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = rne_cli::Cli::parse();
    rne_cli::quiet_panics();
    match rne_cli::guarded(|| rne_cli::run(cli, &mut std::io::stdout().lock())) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}
