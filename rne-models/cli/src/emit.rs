//! `rne emit MODEL`: the Rust the macro generates.

use std::io::Write;

use clap::Args;
use rne_codegen::generate;

use super::model::ModelOptions;
use super::options::scene;
use super::CliError;
use rne_models::RobotSource;

/// Arguments of `rne emit`.
#[derive(Debug, Args)]
pub struct EmitArgs {
    /// A built-in robot name or a path to a .toml spec or .urdf file.
    pub model: String,
    /// Model options.
    #[command(flatten)]
    pub options: ModelOptions,
    /// Functions to generate, comma-separated (default: all).
    #[arg(long)]
    pub outputs: Option<String>,
    /// Gravity in the base frame, `x,y,z`.
    #[arg(long, allow_hyphen_values = true)]
    pub gravity: Option<String>,
    /// Joints to lock, `q1=0,q2=1.5`.
    #[arg(long, allow_hyphen_values = true)]
    pub lock: Option<String>,
    /// A static scene: every joint velocity is zero (the macro's `velocities: zero`).
    #[arg(long)]
    pub at_rest: bool,
    /// Fused multiply-add (the macro's `fma: true`): products summed through `Real::mul_add`,
    /// one instruction and one rounding on targets with FMA.
    #[arg(long)]
    pub fma: bool,
}

/// Prints the generated module.
pub fn run(args: &EmitArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let mut scene = scene(
        args.outputs.as_deref(),
        args.gravity.as_deref(),
        args.lock.as_deref(),
    )?;
    scene.zero_velocities = args.at_rest;
    scene.fma = args.fma;
    scene.mimic = args.options.mimic_mode();
    let source = RobotSource::resolve(&args.model);
    let model = args.options.load(&source, false)?;
    let module = generate(&model, &scene, &source.display_name())?;
    write!(out, "{}", module.to_pretty_string())?;
    Ok(())
}
