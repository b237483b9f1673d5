//! `rne bench [--quick] [--out DIR] [--pinocchio [RUN_SH] [--no-codegen] [--pinocchio-extra SH]]`:
//! run time against error for the kernels and the integrators (docs/design.md §5), written as
//! markdown with SVG and PNG figures; `rne bench MODEL [--json]`: one robot, any URDF or spec,
//! kernel by kernel on every engine (module `bench_robot`).

use std::io::Write;
use std::path::PathBuf;

use clap::Args;

pub use super::bench_robot::{BenchEngine, JitTier};
use super::long_run::LongRun;
use super::model::ModelOptions;
use super::CliError;
use rne_bench::pinocchio::{default_script, extra_beside};
use rne_bench::{self as bench, Effort, PinocchioScript};

/// Arguments of `rne bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// One robot to time kernel by kernel (a built-in name, a .toml spec or a .urdf file)
    /// instead of the report on the built-in robots.
    pub model: Option<String>,
    /// Model options (with MODEL).
    #[command(flatten)]
    pub options: ModelOptions,
    /// With MODEL: the engines to time, comma-separated (`compiled` only for a built-in
    /// robot on its own base: its dynamics, and the URDF robots' M⁻¹ and derivatives).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "jit,compiled,interpreted"
    )]
    pub engines: Vec<BenchEngine>,
    /// With MODEL: the kernels to time, comma-separated, or `all`; default the dynamics and
    /// their derivatives.
    #[arg(long, value_delimiter = ',')]
    pub kernels: Vec<String>,
    /// With MODEL: fuse multiply-adds where the processor has FMA (the macro's `fma: true`).
    #[arg(long)]
    pub fma: bool,
    /// With MODEL: Cranelift's register allocator, `optimized` (backtracking: faster code) or
    /// `fast` (single pass: about ten times faster to compile, code about half as fast).
    #[arg(long, value_enum, default_value = "optimized")]
    pub jit_tier: JitTier,
    /// With MODEL: print one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Few states, short batches and short runs: a check in seconds instead of the report.
    #[arg(long)]
    pub quick: bool,
    /// Directory for bench-report.md and the figures (created if missing).
    #[arg(long, default_value = "out/bench")]
    pub out: PathBuf,
    /// Time Pinocchio on the URDF robots during the run and report the ratios, with the timing
    /// script RUN_SH; without a path, the repository's `tools/peers/run.sh` (install Pinocchio
    /// with `tools/peers/setup.sh` first).
    #[arg(long, value_name = "RUN_SH")]
    pub pinocchio: Option<Option<PathBuf>>,
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
    /// The Jacobian and regressor timer; default: `run_extra.sh` beside RUN_SH, run when that
    /// file exists.
    #[arg(long, value_name = "RUN_EXTRA_SH")]
    pub pinocchio_extra: Option<PathBuf>,
    /// No progress lines on stderr.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs the benchmarks, writes the report and prints it.
pub fn run(args: &BenchArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if let Some(model) = &args.model {
        return super::bench_robot::run(model, args, out);
    }
    super::long_run::prepare_out(&args.out)?;
    let effort = if args.quick {
        Effort::Quick
    } else {
        Effort::Full
    };
    let script = match &args.pinocchio {
        None => None,
        Some(path) => {
            let path = path.clone().unwrap_or_else(default_script);
            let extra = match &args.pinocchio_extra {
                Some(extra) if extra.is_file() => Some(extra.clone()),
                Some(extra) => {
                    return Err(CliError::Argument(format!(
                        "--pinocchio-extra: no file {}",
                        extra.display()
                    )))
                }
                None => extra_beside(&path),
            };
            Some(PinocchioScript {
                codegen_runs: usize::from(args.codegen_runs),
                ..PinocchioScript::new(
                    path,
                    args.pinocchio_calls,
                    (!args.no_codegen).then_some(args.codegen_calls),
                    extra,
                )
            })
        }
    };
    let run = LongRun::start(args.quiet);
    let scratch = args.out.join("pinocchio-urdf");
    let pinocchio = script.as_ref().map(|s| (s, scratch.as_path()));
    let report = bench::run(effort, pinocchio, |step| run.progress(step))?;
    let written = report.write(&args.out)?;
    run.finish(out, &report.markdown(), &written, &args.out)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use clap::Parser;

    use crate::{Cli, Command};

    fn bench_args(args: &[&str]) -> super::BenchArgs {
        let cli = Cli::try_parse_from(["rne", "bench"].iter().chain(args)).expect("parses");
        match cli.command {
            Command::Bench(args) => args,
            other => panic!("not bench: {other:?}"),
        }
    }

    /// `--pinocchio` alone asks for the repository's harness, which resolves to
    /// `tools/peers/run.sh` of this checkout; an explicit path is kept as given, and without the
    /// option Pinocchio is not timed.
    #[test]
    fn pinocchio_takes_an_optional_path_defaulting_to_the_peer_harness() {
        let args = bench_args(&["--pinocchio", "--quick"]);
        assert_eq!(args.pinocchio, Some(None));
        assert!(args.quick);
        let resolved = rne_bench::pinocchio::default_script();
        assert!(resolved.is_file(), "{}", resolved.display());
        assert!(resolved.ends_with(Path::new("tools/peers/run.sh")));
        assert_eq!(
            bench_args(&["--pinocchio", "/opt/peers/run.sh"]).pinocchio,
            Some(Some(PathBuf::from("/opt/peers/run.sh")))
        );
        assert_eq!(
            bench_args(&["--pinocchio=/opt/peers/run.sh"]).pinocchio,
            Some(Some(PathBuf::from("/opt/peers/run.sh")))
        );
        assert_eq!(bench_args(&["--quick"]).pinocchio, None);
        assert_eq!(bench_args(&[]).pinocchio_extra, None);
    }

    /// An explicit extra script that does not exist is an error before anything is timed.
    #[test]
    fn a_missing_extra_script_is_an_error() {
        let args = bench_args(&[
            "--pinocchio",
            "--pinocchio-extra",
            "/nonexistent/run_extra.sh",
        ]);
        let error = super::run(&args, &mut Vec::new()).unwrap_err();
        assert!(
            error.to_string().contains("/nonexistent/run_extra.sh"),
            "{error}"
        );
    }
}
