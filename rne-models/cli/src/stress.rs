//! `rne stress [--quick] [--out DIR]`: the numerical stability report of the generated `f64`
//! kernels (docs/design.md §5), written as markdown with SVG and PNG figures.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;

use super::long_run::LongRun;
use super::CliError;
use rne_stress::{self as stress, Effort};

/// Arguments of `rne stress`.
#[derive(Debug, Args)]
pub struct StressArgs {
    /// Small samples and 10 s chaotic runs: a check in seconds instead of the full report.
    #[arg(long)]
    pub quick: bool,
    /// Directory for report.md and the figures (created if missing).
    #[arg(long, default_value = "out/stress")]
    pub out: PathBuf,
    /// No progress lines on stderr.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs every stress case, writes the report and prints it.
pub fn run(args: &StressArgs, out: &mut dyn Write) -> Result<(), CliError> {
    super::long_run::prepare_out(&args.out)?;
    let effort = if args.quick {
        Effort::Quick
    } else {
        Effort::Full
    };
    let run = LongRun::start(args.quiet);
    let report = stress::run(effort, |case| run.progress(case))?;
    let written = report.write(&args.out)?;
    run.finish(out, &report.markdown(), &written, &args.out)?;
    Ok(())
}
