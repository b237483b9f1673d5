//! `rne bench [--quick] [--out DIR] [--pinocchio RUN_SH]`: run time against error for the kernels and the
//! integrators (DESIGN.md §5), written as markdown with SVG and PNG figures.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;

use super::CliError;
use rne_bench::{self as bench, Effort, PinocchioScript};

/// Arguments of `rne bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Few states, short batches and short runs: a check in seconds instead of the report.
    #[arg(long)]
    pub quick: bool,
    /// Directory for bench-report.md and the figures (created if missing).
    #[arg(long, default_value = "out/bench")]
    pub out: PathBuf,
    /// Pinocchio's timing script (`../shared/tools/pinocchio/run.sh`, after its `setup.sh`):
    /// time Pinocchio on the URDF robots during the run and report the ratios.
    #[arg(long, value_name = "RUN_SH")]
    pub pinocchio: Option<PathBuf>,
    /// Calls per figure for Pinocchio's script.
    #[arg(long, default_value_t = 200_000)]
    pub pinocchio_calls: u64,
    /// No progress lines on stderr.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs the benchmarks, writes the report and prints it.
pub fn run(args: &BenchArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let effort = if args.quick {
        Effort::Quick
    } else {
        Effort::Full
    };
    let start = Instant::now();
    let script = args.pinocchio.as_ref().map(|path| PinocchioScript {
        path: path.clone(),
        calls: args.pinocchio_calls,
    });
    let scratch = args.out.join("pinocchio-urdf");
    let pinocchio = script.as_ref().map(|s| (s, scratch.as_path()));
    let report = bench::run(effort, pinocchio, |step| {
        if !args.quiet {
            eprintln!("[{:7.1} s] {step}", start.elapsed().as_secs_f64());
        }
    })?;
    let written = report.write(&args.out)?;
    write!(out, "{}", report.markdown())?;
    writeln!(
        out,
        "\nwrote {} files to {} in {:.1} s",
        written.len(),
        args.out.display(),
        start.elapsed().as_secs_f64()
    )?;
    Ok(())
}
