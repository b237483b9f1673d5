//! Reading a robot file for generation.

use std::path::Path;

use rne_symbolic::spec::{LoadOptions, RobotFormat};
use rne_symbolic::{Description, RobotModel};

use crate::error::CodegenError;
use crate::module::{generate, GeneratedModule};
use crate::scene::{MimicMode, ParameterMode, Scene};

/// Reads the robot file at `path` (`.toml` spec or `.urdf`, by its extension) through
/// rne-symbolic's one entry point ([`rne_symbolic::read_robot`]), naming it `origin` in error
/// messages, with parameters kept symbolic when `scene` wants them at run
/// time, warnings made errors when it asks for strict validation and mimic tags without a
/// leader dropped when its mimic joints are free. The model's
/// [`warnings`](RobotModel::warnings) are what the Builder prints and the macro documents.
pub fn read_robot(path: &Path, origin: &str, scene: &Scene) -> Result<RobotModel, CodegenError> {
    let options = LoadOptions {
        symbolic_parameters: scene.parameters == ParameterMode::Runtime,
        strict: scene.strict,
        free_mimic: scene.mimic == MimicMode::Free,
        ..LoadOptions::default()
    };
    let format = RobotFormat::from_path(Path::new(origin))?;
    let bytes = std::fs::read(path).map_err(|cause| CodegenError::Read {
        file: origin.to_owned(),
        cause,
    })?;
    let description = Description::bytes(&bytes, format, origin);
    Ok(rne_symbolic::read_robot(description, &options)?)
}

/// Reads a robot file and generates the module `scene` asks for.
pub fn generate_from_path(path: &Path, scene: &Scene) -> Result<GeneratedModule, CodegenError> {
    let origin = path.display().to_string();
    let model = read_robot(path, &origin, scene)?;
    generate(&model, scene, &origin)
}
