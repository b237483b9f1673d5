//! `rne emit MODEL`: the Rust the macro generates, or the same kernels as C (`--lang c`).

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use rne_codegen_core::{c_identifier, generate, generate_c, CodegenError, ParameterMode};

use super::model::ModelOptions;
use super::options::scene_and_options;
use super::stats::Parameters;
use super::CliError;
use rne_models::RobotSource;

/// The language `rne emit` writes.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Lang {
    /// The module `derive_dynamics!` expands to.
    #[default]
    Rust,
    /// A C99 header and source (also C++), the same kernels bit for bit.
    C,
}

/// Arguments of `rne emit`.
#[derive(Debug, Args)]
pub struct EmitArgs {
    /// A built-in robot name or a path to a .toml spec or .urdf file.
    pub model: String,
    /// Model options.
    #[command(flatten)]
    pub options: ModelOptions,
    /// Functions to generate, comma-separated (default: the dynamics: inverse_dynamics,
    /// mass_matrix, coriolis_matrix, gravity_torques, bias_torques, forward_dynamics and the
    /// energies).
    #[arg(long)]
    pub outputs: Option<String>,
    /// Gravity in the base frame, `x,y,z`.
    #[arg(long, allow_hyphen_values = true)]
    pub gravity: Option<String>,
    /// Joints to lock, `q1=0,q2=1.5`.
    #[arg(long, allow_hyphen_values = true)]
    pub lock: Option<String>,
    /// A static scene: every joint velocity is zero (the macro's `at_rest: true`).
    #[arg(long)]
    pub at_rest: bool,
    /// Fused multiply-add (the macro's `fma: true`): products summed through `Real::mul_add`,
    /// one instruction and one rounding on targets with FMA.
    #[arg(long)]
    pub fma: bool,
    /// How parameters enter the kernels (the macro's `parameters:`): with `runtime` or `base`
    /// the functions read them from a struct (Rust `Params`, C `struct <robot>_params`).
    #[arg(long, value_enum, default_value_t = Parameters::Constant)]
    pub parameters: Parameters,
    /// The language: `rust`, or `c` for a C99 header and source whose functions
    /// (`<robot>_<kernel>`) return the Rust kernels' values bit for bit (the header says how
    /// to compile them).
    #[arg(long, value_enum, default_value_t = Lang::Rust)]
    pub lang: Lang,
    /// Write the files to this directory (created if missing): `<robot>.rs`, or `<robot>.h`
    /// and `<robot>.c`, `<robot>` the robot's name as a C identifier. Without it the code is
    /// printed (C: the header, then the source).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Prints or writes the generated code.
pub fn run(args: &EmitArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let (mut scene, mut options) = scene_and_options(
        args.outputs.as_deref(),
        args.gravity.as_deref(),
        args.lock.as_deref(),
    )?;
    scene.at_rest = args.at_rest;
    scene.mimic = args.options.mimic_mode();
    options.fma = args.fma;
    options.parameters = match args.parameters {
        Parameters::Constant => ParameterMode::Constant,
        Parameters::Runtime => ParameterMode::Runtime,
        Parameters::Base => ParameterMode::Base,
    };
    let source = RobotSource::resolve(&args.model);
    let model = args
        .options
        .load(&source, args.parameters == Parameters::Runtime)?;
    let name = source.display_name();
    let files: Vec<(String, String)> = match args.lang {
        Lang::Rust => {
            let module = generate(&model, &scene, &options, &name)?;
            let stem = c_identifier(&model.name);
            vec![(format!("{stem}.rs"), module.to_pretty_string())]
        }
        Lang::C => {
            let module = generate_c(&model, &scene, &options, &name)?;
            vec![
                (format!("{}.h", module.name), module.header),
                (format!("{}.c", module.name), module.source),
            ]
        }
    };
    match &args.out {
        Some(dir) => write_files(dir, &files, out),
        None => {
            for (_, text) in &files {
                write!(out, "{text}")?;
            }
            Ok(())
        }
    }
}

/// Writes each file into `dir` (created first), naming each written file on `out`.
fn write_files(
    dir: &Path,
    files: &[(String, String)],
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let failed = |path: &Path, cause: std::io::Error| CodegenError::Io {
        path: path.to_path_buf(),
        cause,
    };
    std::fs::create_dir_all(dir).map_err(|e| failed(dir, e))?;
    for (file, text) in files {
        let path = dir.join(file);
        std::fs::write(&path, text).map_err(|e| failed(&path, e))?;
        writeln!(out, "wrote {}", path.display())?;
    }
    Ok(())
}
