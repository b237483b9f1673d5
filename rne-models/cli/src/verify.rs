//! `rne verify [MODEL..]`: the main job on the built-in robots — generate every kernel,
//! report its cost, and check the compiled kernels against the independent numeric reference.

use std::io::Write;

use clap::Args;
use rne_codegen_core::{generate, Scene};
use rne_symbolic::spec::LoadOptions;

use super::accuracy::Compare;
use super::CliError;
use rne_models::{builtin, RobotSource, BUILTIN_ROBOTS};

/// Arguments of `rne verify`.
#[derive(Debug, Args)]
pub struct VerifyArgs {
    /// Built-in robots to verify (default: all).
    pub models: Vec<String>,
    /// Random states per robot.
    #[arg(long, default_value_t = 10_000)]
    pub samples: usize,
    /// Seed of the random states.
    #[arg(long, default_value_t = 2026)]
    pub seed: u64,
    /// Largest relative error accepted.
    #[arg(long, default_value_t = 1e-13)]
    pub tolerance: f64,
}

/// Generates, counts and checks; fails if any error exceeds the tolerance.
pub fn run(args: &VerifyArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if !(args.tolerance.is_finite() && args.tolerance >= 0.0) {
        return Err(CliError::Argument(format!(
            "--tolerance must be a finite, non-negative number, got {}",
            args.tolerance
        )));
    }
    if args.samples == 0 {
        return Err(CliError::Argument(
            "--samples must be at least 1: no states would check nothing".into(),
        ));
    }
    let robots = if args.models.is_empty() {
        BUILTIN_ROBOTS.iter().collect::<Vec<_>>()
    } else {
        args.models
            .iter()
            .map(|name| {
                builtin(name).ok_or_else(|| {
                    CliError::Argument(format!(
                        "`{name}` is not a built-in robot (see `rne models`)"
                    ))
                })
            })
            .collect::<Result<_, _>>()?
    };
    let mut failures = Vec::new();
    for robot in robots {
        let model = RobotSource::Builtin(robot).load(&LoadOptions::default())?;
        let module = generate(&model, &Scene::default(), robot.file)?;
        writeln!(
            out,
            "{} ({} joints): every kernel generated in {:.1} ms",
            robot.name,
            module.ndof,
            module.generation_time.as_secs_f64() * 1e3
        )?;
        for k in &module.kernels {
            writeln!(out, "  {:<18} {}", k.kernel.name(), k.ops)?;
        }
        let agreement = robot.visit(Compare {
            model: &model,
            samples: args.samples,
            seed: args.seed,
        })?;
        writeln!(
            out,
            "  against the numeric reference, {} seeded states (max / median relative error):",
            args.samples
        )?;
        for a in &agreement {
            let verdict = if a.max_error <= args.tolerance {
                "ok"
            } else {
                "FAIL"
            };
            writeln!(
                out,
                "  {:<10} {:>10.2e} {:>10.2e}  {verdict}",
                a.quantity, a.max_error, a.median_error
            )?;
            if a.max_error > args.tolerance {
                failures.push(format!("{} {}", robot.name, a.quantity));
            }
        }
    }
    if failures.is_empty() {
        writeln!(
            out,
            "all kernels agree with the reference to {:e}",
            args.tolerance
        )?;
        Ok(())
    } else {
        Err(CliError::Disagreement {
            tolerance: args.tolerance,
            failures,
        })
    }
}
