//! Reading a robot file for generation.

use std::path::Path;

use rne_symbolic::spec::{load_file, LoadOptions};
use rne_symbolic::RobotModel;

use crate::error::CodegenError;
use crate::module::{generate, GeneratedModule};
use crate::scene::{ParameterMode, Scene};

/// Reads a robot file, keeping parameters symbolic when `scene` wants them at run time.
pub fn load_for_scene(path: &Path, scene: &Scene) -> Result<RobotModel, CodegenError> {
    let options = LoadOptions {
        symbolic_parameters: scene.parameters == ParameterMode::Runtime,
    };
    Ok(load_file(path, &options)?)
}

/// Reads a robot file and generates the module `scene` asks for.
pub fn generate_from_path(path: &Path, scene: &Scene) -> Result<GeneratedModule, CodegenError> {
    let model = load_for_scene(path, scene)?;
    generate(&model, scene, &path.display().to_string())
}
