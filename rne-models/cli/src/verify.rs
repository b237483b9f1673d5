//! `rne verify [MODEL..]`: the main job on the built-in robots — generate every kernel the
//! generator emits (the eighteen of docs/design.md §4.2), compile them in memory, and check
//! them, and the dynamics kernels of the built-in compiled modules, against the independent
//! numeric reference, each kernel against its own tolerance ([`tolerance::of`]).

mod compiled;
mod robot;
pub mod tolerance;

use std::io::Write;

use clap::Args;

use super::CliError;
use rne_models::{builtin, BuiltinRobot, BUILTIN_ROBOTS};
use robot::{KernelRow, RobotCheck};

/// Arguments of `rne verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// Built-in robots to verify (default: all).
    pub models: Vec<String>,
    /// Random states per robot.
    #[arg(long, default_value_t = 1_000)]
    pub samples: usize,
    /// Seed of the random states.
    #[arg(long, default_value_t = 2026)]
    pub seed: u64,
    /// One largest relative error for every kernel, instead of each kernel's own (1e-13 for
    /// the dynamics, 1e-12 for derivatives, M⁻¹, kinematics, friction and the regressor,
    /// 1e-11 for the base regressor and base parameters).
    #[arg(long)]
    pub tolerance: Option<f64>,
}

/// Generates, compiles and checks; fails if any error exceeds its tolerance.
pub fn run(args: &VerifyArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if let Some(t) = args.tolerance.filter(|t| !(t.is_finite() && *t >= 0.0)) {
        return Err(CliError::Argument(format!(
            "--tolerance must be a finite, non-negative number, got {t}"
        )));
    }
    if args.samples == 0 {
        return Err(CliError::Argument(
            "--samples must be at least 1: no states would check nothing".into(),
        ));
    }
    let robots = robots(&args.models)?;
    let mut failures = Vec::new();
    for &robot in &robots {
        let check = robot::check(robot, args.samples, args.seed, args.tolerance)?;
        report(robot, &check, args.samples, out)?;
        failures.extend(
            check
                .rows
                .iter()
                .filter(|row| !row.passes())
                .map(|row| failure(robot, row)),
        );
    }
    if failures.is_empty() {
        writeln!(
            out,
            "all {} kernels of {} robots agree with the numeric reference within their tolerances",
            rne_codegen::Kernel::ALL.len(),
            robots.len()
        )?;
        Ok(())
    } else {
        Err(CliError::Disagreement { failures })
    }
}

/// The robots named, or every built-in robot.
fn robots(names: &[String]) -> Result<Vec<&'static BuiltinRobot>, CliError> {
    if names.is_empty() {
        return Ok(BUILTIN_ROBOTS.iter().collect());
    }
    names
        .iter()
        .map(|name| {
            builtin(name).ok_or_else(|| {
                CliError::Argument(format!(
                    "`{name}` is not a built-in robot (see `rne models`)"
                ))
            })
        })
        .collect()
}

/// One robot's table: every kernel with its operations, its errors and its tolerance.
fn report(
    robot: &BuiltinRobot,
    check: &RobotCheck,
    samples: usize,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    writeln!(
        out,
        "{} ({} joints): {} kernels generated in {:.1} ms, compiled in memory in {:.1} ms",
        robot.name,
        check.ndof,
        check.rows.len(),
        check.generation.as_secs_f64() * 1e3,
        check.compilation.as_secs_f64() * 1e3
    )?;
    writeln!(
        out,
        "  largest normwise relative error against the numeric reference over {samples} seeded states:"
    )?;
    writeln!(
        out,
        "  {:<30} {:>10} {:>10} {:>10} {:>10}",
        "kernel", "operations", "compiled", "jit", "tolerance"
    )?;
    for row in &check.rows {
        let compiled = row
            .compiled
            .map_or_else(|| "-".to_owned(), |e| format!("{e:.2e}"));
        writeln!(
            out,
            "  {:<30} {:>10} {:>10} {:>10.2e} {:>10.0e}  {}",
            row.kernel.name(),
            row.operations,
            compiled,
            row.jit,
            row.tolerance,
            if row.passes() { "ok" } else { "FAIL" }
        )?;
    }
    Ok(())
}

/// A failed row, for the error message.
fn failure(robot: &BuiltinRobot, row: &KernelRow) -> String {
    let compiled = row
        .compiled
        .map_or_else(String::new, |e| format!(", compiled {e:.2e}"));
    format!(
        "{} {} (jit {:.2e}{compiled} > {:e})",
        robot.name,
        row.kernel.name(),
        row.jit,
        row.tolerance
    )
}
