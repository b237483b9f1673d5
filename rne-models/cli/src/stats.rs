//! `rne stats MODEL`: operation counts, critical path and generation time per kernel.

use std::io::Write;

use clap::{Args, ValueEnum};
use rne_codegen::Kernel;
use rne_codegen_core::{generate, GeneratedModule, GenerationOptions, ParameterMode};

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
    /// How parameters enter the kernels (the macro's `parameters:`).
    #[arg(long, value_enum, default_value_t = Parameters::Constant)]
    pub parameters: Parameters,
    /// Fused multiply-add (the macro's `fma: true`): the same counts (a fused pair is a
    /// multiplication and an addition), a shorter critical path.
    #[arg(long)]
    pub fma: bool,
    /// The derivative kernels built in lanes (the macro's `derivatives: lanes`): their counts
    /// are of instructions, a vector instruction counting once for its four lanes.
    #[arg(long)]
    pub lanes: bool,
}

/// The macro's `parameters:` setting.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum Parameters {
    /// Folded as numbers.
    Constant,
    /// The spec's named parameters, read at run time.
    Runtime,
    /// The base parameters, read at run time.
    Base,
}

/// Generates every kernel of docs/design.md §4 and reports its cost.
pub fn run(args: &StatsArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let source = RobotSource::resolve(&args.model);
    let model = args
        .options
        .load(&source, args.parameters == Parameters::Runtime)?;
    let mut options = generation_options(args);
    // Forward dynamics, its derivatives and M⁻¹ are undefined when a joint moves no mass: the
    // other kernels are still generated, and each undefined one is named with the joint.
    let undefined: Vec<(Kernel, String)> = match model.check_mass_matrix_invertible() {
        Ok(()) => Vec::new(),
        Err(e) => {
            let undefined = options.outputs.iter().filter(|k| k.inverts_mass_matrix());
            let undefined = undefined.map(|&k| (k, e.to_string())).collect();
            options.outputs.retain(|k| !k.inverts_mass_matrix());
            undefined
        }
    };
    let module = generate(
        &model,
        &args.options.scene(),
        &options,
        &source.display_name(),
    )?;
    let name = source.display_name();
    if args.json {
        write_json(out, &name, &module, &undefined)
    } else {
        write_table(out, &name, &module, &undefined)
    }
}

/// Every kernel, with the parameter mode, fused multiply-add and derivative lanes `args` asks
/// for.
fn generation_options(args: &StatsArgs) -> GenerationOptions {
    GenerationOptions {
        outputs: Kernel::ALL.to_vec(),
        parameters: match args.parameters {
            Parameters::Constant => ParameterMode::Constant,
            Parameters::Runtime => ParameterMode::Runtime,
            Parameters::Base => ParameterMode::Base,
        },
        fma: args.fma,
        derivative_lanes: args.lanes,
        ..GenerationOptions::default()
    }
}

/// The report of `module` (of the robot `name`) as one JSON object, with the kernels left
/// `undefined` and why.
fn write_json(
    out: &mut dyn Write,
    name: &str,
    module: &GeneratedModule,
    undefined: &[(Kernel, String)],
) -> Result<(), CliError> {
    let kernels: Vec<serde_json::Value> = module
        .kernels
        .iter()
        .map(|k| {
            serde_json::json!({
                "kernel": k.kernel.name(),
                "mul": k.ops.mul, "add": k.ops.add, "div": k.ops.div, "neg": k.ops.neg,
                "sin": k.ops.sin, "cos": k.ops.cos, "sqrt": k.ops.sqrt, "sign": k.ops.sign,
                "cost": k.ops.cost(), "critical_path": k.critical_path,
                "generation_ms": k.generation_time.as_secs_f64() * 1e3,
            })
        })
        .collect();
    let report = serde_json::json!({
        "model": name,
        "dof": module.ndof,
        "kernels": kernels,
        "generation_ms": module.generation_time.as_secs_f64() * 1e3,
        "undefined": undefined.iter().map(|(k, why)| serde_json::json!({
            "kernel": k.name(), "reason": why,
        })).collect::<Vec<_>>(),
        "forward_dynamics_choice": module.forward_dynamics_choice.as_ref().map(|c| serde_json::json!({
            "aba": {"mul": c.aba.mul, "add": c.aba.add, "cost": c.aba.cost()},
            "ldlt": {"mul": c.ldlt.mul, "add": c.ldlt.add, "cost": c.ldlt.cost()},
            "chosen": format!("{:?}", c.chosen).to_lowercase(),
        })),
    });
    writeln!(out, "{report}")?;
    Ok(())
}

/// The report of `module` (of the robot `name`) as a table, a line per kernel, then the
/// kernels left `undefined` and why, the forward-dynamics choice and the generation time.
fn write_table(
    out: &mut dyn Write,
    name: &str,
    module: &GeneratedModule,
    undefined: &[(Kernel, String)],
) -> Result<(), CliError> {
    writeln!(out, "{} ({} joints)", name, module.ndof)?;
    writeln!(
        out,
        "{:<28} {:>7} {:>7} {:>5} {:>5} {:>5} {:>5} {:>5} {:>5} {:>7} {:>6} {:>10}",
        "kernel",
        "mul",
        "add",
        "div",
        "neg",
        "sin",
        "cos",
        "sqrt",
        "sign",
        "cost",
        "path",
        "gen (ms)"
    )?;
    for k in &module.kernels {
        let o = k.ops;
        writeln!(
            out,
            "{:<28} {:>7} {:>7} {:>5} {:>5} {:>5} {:>5} {:>5} {:>5} {:>7} {:>6} {:>10.3}",
            k.kernel.name(),
            o.mul,
            o.add,
            o.div,
            o.neg,
            o.sin,
            o.cos,
            o.sqrt,
            o.sign,
            o.cost(),
            k.critical_path,
            k.generation_time.as_secs_f64() * 1e3
        )?;
    }
    for (kernel, why) in undefined {
        writeln!(out, "{:<28} undefined: {why}", kernel.name())?;
    }
    if let Some(choice) = &module.forward_dynamics_choice {
        writeln!(
            out,
            "forward_dynamics: articulated-body {} mul {} add (cost {}), M + LDLT {} mul {} add (cost {}); emitted: {:?}",
            choice.aba.mul,
            choice.aba.add,
            choice.aba.cost(),
            choice.ldlt.mul,
            choice.ldlt.add,
            choice.ldlt.cost(),
            choice.chosen
        )?;
    }
    writeln!(
        out,
        "total generation time: {:.3} ms",
        module.generation_time.as_secs_f64() * 1e3
    )?;
    Ok(())
}
