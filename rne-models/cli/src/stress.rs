//! `rne stress [--quick] [--out DIR] [--engine jit|interpreted]`: the numerical stability report of the generated `f64`
//! kernels (docs/design.md §5), written as markdown with SVG and PNG figures.

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};

use super::long_run::LongRun;
use super::CliError;
use rne_stress::{self as stress, Effort, Engine, Settings};

/// What computes the stress robots' `f64` values.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum StressEngine {
    /// The programs compiled in memory (the interpreter where this processor has no JIT
    /// backend, with a warning).
    #[default]
    Jit,
    /// The programs evaluated operation by operation (the same bits, more slowly).
    Interpreted,
}

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
    /// What computes the kernels' `f64` values: the report is the same either way.
    #[arg(long, value_enum, default_value_t = StressEngine::Jit)]
    pub engine: StressEngine,
}

/// Runs every stress case, writes the report and prints it.
pub fn run(args: &StressArgs, out: &mut dyn Write) -> Result<(), CliError> {
    super::long_run::prepare_out(&args.out)?;
    let effort = if args.quick {
        Effort::Quick
    } else {
        Effort::Full
    };
    let engine = match args.engine {
        StressEngine::Interpreted => Engine::Interpreted,
        StressEngine::Jit => match rne_jit::host_support() {
            Ok(()) => Engine::Jit,
            Err(why) => {
                eprintln!("warning: {why}; the interpreter computes the kernels");
                Engine::Interpreted
            }
        },
    };
    let run = LongRun::start(args.quiet);
    let report = stress::run(Settings { effort, engine }, |case| run.progress(case))?;
    let written = report.write(&args.out)?;
    run.finish(out, &report.markdown(), &written, &args.out)?;
    Ok(())
}
