//! `rne bench [--quick] [--out DIR] [--pinocchio RUN_SH [--no-codegen] [--pinocchio-extra SH]]`:
//! run time against error for the kernels and the integrators (docs/design.md §5), written as
//! markdown with SVG and PNG figures.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;

use super::long_run::LongRun;
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
    /// Calls per figure for Pinocchio's `run.sh` and `run_extra.sh`.
    #[arg(long, default_value_t = 200_000)]
    pub pinocchio_calls: u64,
    /// Calls per measurement for `run_cg.sh` (beside RUN_SH: Pinocchio's derivatives and its
    /// CppADCodeGen code; each run generates and compiles the code first).
    #[arg(long, default_value_t = 50_000)]
    pub codegen_calls: u64,
    /// Do not run `run_cg.sh`.
    #[arg(long)]
    pub no_codegen: bool,
    /// In how many of the three runs on each robot `run_cg.sh` takes part (the first ones);
    /// each generates and compiles Pinocchio's code anew, minutes per robot.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u8).range(1..=3))]
    pub codegen_runs: u8,
    /// The Jacobian and regressor timer (`tools/pinocchio/run_extra.sh` of this repository),
    /// run when the file exists.
    #[arg(
        long,
        value_name = "RUN_EXTRA_SH",
        default_value = "tools/pinocchio/run_extra.sh"
    )]
    pub pinocchio_extra: PathBuf,
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
    let run = LongRun::start(args.quiet);
    let script = args.pinocchio.as_ref().map(|path| PinocchioScript {
        codegen_runs: usize::from(args.codegen_runs),
        ..PinocchioScript::new(
            path.clone(),
            args.pinocchio_calls,
            (!args.no_codegen).then_some(args.codegen_calls),
            args.pinocchio_extra
                .is_file()
                .then(|| args.pinocchio_extra.clone()),
        )
    });
    let scratch = args.out.join("pinocchio-urdf");
    let pinocchio = script.as_ref().map(|s| (s, scratch.as_path()));
    let report = bench::run(effort, pinocchio, |step| run.progress(step))?;
    let written = report.write(&args.out)?;
    run.finish(out, &report.markdown(), &written, &args.out)?;
    Ok(())
}
