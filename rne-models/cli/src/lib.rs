//! The `rne` command line (docs/design.md §5): one file per subcommand, each turning its arguments
//! into calls of the library crates (`rne-models`, `rne-interpreted`, `rne-scenarios`,
//! `rne-bench`, `rne-stress`) and their errors into one [`CliError`] that keeps every cause.
#![deny(missing_docs)]

mod bench;
mod bench_robot;
mod check;
mod corpus;
mod emit;
mod eval;
mod eval_kernels;
mod identify;
mod identify_engine;
mod internal;
mod list;
mod long_run;
mod model;
mod options;
mod progress;
mod show;
mod simulate;
mod stats;
mod stress;
mod verify;

use std::io::Write;

use clap::{Parser, Subcommand};

pub use internal::{guarded, quiet_panics};
pub use model::{MimicOption, ModelOptions};
pub use options::{parse_list, parse_locks, CliError};

/// Exact, fast robot dynamics from a robot description.
#[derive(Debug, Parser)]
#[command(name = "rne", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// List the built-in robots.
    Models,
    /// Read and validate a robot: joints, links, degrees of freedom, mass, base, mimic joints
    /// and warnings (exit status 0 with warnings, non-zero on errors).
    Check(check::CheckArgs),
    /// Print M, C, g, the torques and the energies for people to read.
    Show(show::ShowArgs),
    /// Print the Rust that `derive_dynamics!` generates for a robot.
    Emit(emit::EmitArgs),
    /// Operation counts, critical path (modelled cycles) and generation time per generated function.
    Stats(stats::StatsArgs),
    /// Evaluate the dynamics at one state.
    Eval(eval::EvalArgs),
    /// Base parameters by weighted least squares from measured q, q̇, q̈, τ (CSV), or an
    /// optimised excitation trajectory with simulated torques (--excite).
    Identify(identify::IdentifyArgs),
    /// Generate all 18 kernels of every built-in robot, compile them in memory and check them,
    /// and the built-in modules' dynamics kernels, against the numeric reference, each kernel
    /// within its own tolerance.
    Verify(verify::VerifyArgs),
    /// Run the thesis's chapter 6 experiments or a scenario file: CSV, SVG/PNG figures, report.
    Simulate(simulate::SimulateArgs),
    /// Every URDF of a directory against Pinocchio's values (tools/peers/pinocchio_values.py):
    /// ID, M, g, bias and FD on a fixed and a floating base; the table of docs/robots.md.
    Corpus(corpus::CorpusArgs),
    /// Numerical stability report: extreme masses, lengths, angles, speeds, ill-conditioning,
    /// chaotic runs, large robots and non-finite inputs.
    Stress(stress::StressArgs),
    /// Run time against error: every kernel implementation of every built-in robot, scene
    /// savings and integrators, as markdown tables and SVG/PNG work-precision figures.
    Bench(bench::BenchArgs),
}

/// Runs one command, writing its output to `out`.
pub fn run(cli: Cli, out: &mut dyn Write) -> Result<(), CliError> {
    match cli.command {
        Command::Models => list::run(out),
        Command::Check(args) => check::run(&args, out),
        Command::Show(args) => show::run(&args, out),
        Command::Emit(args) => emit::run(&args, out),
        Command::Stats(args) => stats::run(&args, out),
        Command::Eval(args) => eval::run(&args, out),
        Command::Identify(args) => identify::run(&args, out),
        Command::Verify(args) => verify::run(&args, out),
        Command::Simulate(args) => simulate::run(&args, out),
        Command::Corpus(args) => corpus::run(&args, out),
        Command::Stress(args) => stress::run(&args, out),
        Command::Bench(args) => bench::run(&args, out),
    }
}
