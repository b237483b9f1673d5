//! Reading a robot file for generation.

use std::path::Path;

use rne_symbolic::spec::{LoadOptions, RobotFormat};
use rne_symbolic::{Description, RobotModel};

use crate::error::CodegenError;
use crate::generation_options::{GenerationOptions, ParameterMode};
use crate::module::{generate, GeneratedModule};
use crate::scene::{MimicMode, Scene};

/// Reads the robot file at `path` (`.toml` spec or `.urdf`, by its extension) through
/// rne-symbolic's one entry point ([`rne_symbolic::read_robot`]), naming it `origin` in error
/// messages, with parameters kept symbolic when `options` want them at run time, warnings made
/// errors when they ask for strict validation and mimic tags without a leader dropped when the
/// `scene`'s mimic joints are free. The model's
/// [`warnings`](RobotModel::warnings) are what the Builder prints and the macro documents.
pub fn read_robot(
    path: &Path,
    origin: &str,
    scene: &Scene,
    options: &GenerationOptions,
) -> Result<RobotModel, CodegenError> {
    let load = LoadOptions {
        symbolic_parameters: options.parameters == ParameterMode::Runtime,
        strict: options.strict,
        free_mimic: scene.mimic == MimicMode::Free,
        ..LoadOptions::default()
    };
    let format = RobotFormat::from_path(Path::new(origin))?;
    let bytes = std::fs::read(path).map_err(|cause| CodegenError::Read {
        file: origin.to_owned(),
        cause,
    })?;
    let description = Description::bytes(&bytes, format, origin);
    Ok(rne_symbolic::read_robot(description, &load)?)
}

/// Reads a robot file and generates the module `options` ask for, in `scene`.
pub fn generate_from_path(
    path: &Path,
    scene: &Scene,
    options: &GenerationOptions,
) -> Result<GeneratedModule, CodegenError> {
    let origin = path.display().to_string();
    let model = read_robot(path, &origin, scene, options)?;
    generate(&model, scene, options, &origin)
}
