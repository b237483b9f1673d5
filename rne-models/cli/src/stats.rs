//! `rne stats MODEL`: operation counts and generation time per kernel.

use std::io::Write;

use clap::Args;
use rne_codegen::{generate, Scene};

use super::model::ModelOptions;
use super::CliError;
use rne_models::RobotSource;

/// Arguments of `rne stats`.
#[derive(Debug, Args)]
pub struct StatsArgs {
    /// A built-in robot name or a path to a .toml spec or .urdf file.
    pub model: String,
    /// Model options.
    #[command(flatten)]
    pub options: ModelOptions,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Generates every kernel and reports its cost.
pub fn run(args: &StatsArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let source = RobotSource::resolve(&args.model);
    let model = args.options.load(&source, false)?;
    let module = generate(&model, &Scene::default(), &source.display_name())?;
    if args.json {
        let kernels: Vec<serde_json::Value> = module
            .kernels
            .iter()
            .map(|k| {
                serde_json::json!({
                    "kernel": k.kernel.name(),
                    "mul": k.ops.mul, "add": k.ops.add, "div": k.ops.div, "neg": k.ops.neg,
                    "sin": k.ops.sin, "cos": k.ops.cos, "sqrt": k.ops.sqrt, "cost": k.ops.cost(),
                    "generation_ms": k.generation_time.as_secs_f64() * 1e3,
                })
            })
            .collect();
        let report = serde_json::json!({
            "model": source.display_name(),
            "dof": module.ndof,
            "kernels": kernels,
            "generation_ms": module.generation_time.as_secs_f64() * 1e3,
        });
        writeln!(out, "{report}")?;
        return Ok(());
    }
    writeln!(out, "{} ({} joints)", source.display_name(), module.ndof)?;
    writeln!(
        out,
        "{:<18} {:>6} {:>6} {:>5} {:>5} {:>5} {:>5} {:>5} {:>6} {:>10}",
        "kernel", "mul", "add", "div", "neg", "sin", "cos", "sqrt", "cost", "gen (ms)"
    )?;
    for k in &module.kernels {
        let o = k.ops;
        writeln!(
            out,
            "{:<18} {:>6} {:>6} {:>5} {:>5} {:>5} {:>5} {:>5} {:>6} {:>10.3}",
            k.kernel.name(),
            o.mul,
            o.add,
            o.div,
            o.neg,
            o.sin,
            o.cos,
            o.sqrt,
            o.cost(),
            k.generation_time.as_secs_f64() * 1e3
        )?;
    }
    writeln!(
        out,
        "total generation time: {:.3} ms",
        module.generation_time.as_secs_f64() * 1e3
    )?;
    Ok(())
}
