//! The build-script API: the same module as the macro, written to `OUT_DIR`.

use std::path::{Path, PathBuf};

use crate::error::CodegenError;
use crate::generation_options::{
    ForwardDynamicsMethod, GenerationOptions, ParameterMode, ScalarType,
};
use crate::kernel::Kernel;
use crate::load::read_robot;
use crate::module::{generate, GeneratedModule};
use crate::scene::{MimicMode, Scene};
use rne_symbolic::model::Base;
use rne_symbolic::spec::SpecWarning;

/// Environment variable naming a directory where [`Builder::write`] also puts a copy of the
/// generated source, outside `target/`, for people to read.
pub const KEEP_GENERATED_ENV: &str = "RNE_KEEP_GENERATED";

/// Generates a robot's dynamics module from `build.rs`.
///
/// ```no_run
/// // build.rs, with `[build-dependencies] rne-codegen = { .., features = ["builder"] }`
/// // (users write `rne_codegen::`, which re-exports these)
/// use rne_codegen_core::{Builder, Kernel};
/// Builder::new("robots/arm.toml")
///     .outputs(&[Kernel::InverseDynamics, Kernel::MassMatrix])
///     .write("arm.rs")
///     .unwrap();
/// // lib.rs:  mod arm { include!(concat!(env!("OUT_DIR"), "/arm.rs")); }
/// ```
#[derive(Clone, Debug)]
pub struct Builder {
    robot: PathBuf,
    scene: Scene,
    options: GenerationOptions,
}

impl Builder {
    /// A builder for the robot file at `robot` (relative paths are taken from
    /// `CARGO_MANIFEST_DIR` when it is set), generating every kernel by default.
    pub fn new(robot: impl AsRef<Path>) -> Builder {
        let robot = robot.as_ref();
        let robot = match std::env::var_os("CARGO_MANIFEST_DIR") {
            Some(dir) if robot.is_relative() => PathBuf::from(dir).join(robot),
            _ => robot.to_path_buf(),
        };
        Builder {
            robot,
            scene: Scene::default(),
            options: GenerationOptions::default(),
        }
    }

    /// The kernels to generate.
    pub fn outputs(mut self, kernels: &[Kernel]) -> Builder {
        self.options.outputs = kernels.to_vec();
        self
    }

    /// Overrides the spec's gravity (`[0, 0, 0]` removes every gravity term).
    pub fn gravity(mut self, gravity: [f64; 3]) -> Builder {
        self.scene.gravity = Some(gravity);
        self
    }

    /// Locks a joint at a value: it becomes a constant and leaves the state.
    pub fn lock(mut self, joint: &str, value: f64) -> Builder {
        self.scene.lock.push((joint.to_owned(), value));
        self
    }

    /// A static scene (the macro's `at_rest: true`; [`Scene::at_rest`]): every joint velocity
    /// is 0, so the Coriolis and centrifugal terms vanish; the functions keep their `qd`
    /// arguments and ignore them.
    pub fn at_rest(mut self, at_rest: bool) -> Builder {
        self.scene.at_rest = at_rest;
        self
    }

    /// A fixed or floating base, overriding the spec's (the macro's `base:`).
    pub fn base(mut self, base: Base) -> Builder {
        self.scene.base = Some(base);
        self
    }

    /// Mimic followers constrained to their leaders (the default) or free (the macro's
    /// `mimic:`).
    pub fn mimic(mut self, mode: MimicMode) -> Builder {
        self.scene.mimic = mode;
        self
    }

    /// The derivative kernels built in lanes (the macro's `derivatives: lanes`;
    /// [`GenerationOptions::derivative_lanes`]).
    pub fn derivative_lanes(mut self, lanes: bool) -> Builder {
        self.options.derivative_lanes = lanes;
        self
    }

    /// Fused multiply-add in the kernels (the macro's `fma: true`; [`GenerationOptions::fma`]).
    pub fn fma(mut self, fused: bool) -> Builder {
        self.options.fma = fused;
        self
    }

    /// Joint friction included in the inverse and forward dynamics and the regressor (the
    /// macro's `friction: include`).
    pub fn friction(mut self, include: bool) -> Builder {
        self.scene.friction = include;
        self
    }

    /// How `forward_dynamics` is generated (the macro's `forward_dynamics:`; by default the
    /// cheaper of the articulated-body algorithm and M + LᵀDL).
    pub fn forward_dynamics(mut self, method: ForwardDynamicsMethod) -> Builder {
        self.options.forward_dynamics = method;
        self
    }

    /// The frames (link names) of the kinematics kernels, in output order (the macro's
    /// `frames:`; every link by default).
    pub fn frames(mut self, frames: &[&str]) -> Builder {
        self.options.frames = Some(frames.iter().map(|f| (*f).to_owned()).collect());
        self
    }

    /// Constant (folded) or runtime parameters: the spec's (`Params`), or the base parameters
    /// (`Params` of `BASE_PARAMETERS`, the macro's `parameters: base`).
    pub fn parameters(mut self, mode: ParameterMode) -> Builder {
        self.options.parameters = mode;
        self
    }

    /// The scalar type.
    pub fn scalar(mut self, scalar: ScalarType) -> Builder {
        self.options.scalar = scalar;
        self
    }

    /// Where the generated code finds the `rne-codegen` crate, as a path
    /// (`::my_reexport::rne_codegen`; default `::rne_codegen`). Checked by [`Builder::generate`].
    pub fn crate_path(mut self, path: &str) -> Builder {
        self.options.crate_path = path.to_owned();
        self
    }

    /// Strict validation (the macro's `validation: strict`): every warning about the robot
    /// file is an error.
    pub fn strict(mut self, strict: bool) -> Builder {
        self.options.strict = strict;
        self
    }

    /// The physical scene as configured.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The generation options as configured.
    pub fn options(&self) -> &GenerationOptions {
        &self.options
    }

    /// Generates the module without writing it.
    pub fn generate(&self) -> Result<GeneratedModule, CodegenError> {
        Ok(self.generate_with_warnings()?.0)
    }

    /// Generates the module without writing it, with the warnings of reading the robot file
    /// (docs/design.md §2.4; none under strict validation, where they are errors).
    pub fn generate_with_warnings(
        &self,
    ) -> Result<(GeneratedModule, Vec<SpecWarning>), CodegenError> {
        let origin = self.robot.display().to_string();
        let model = read_robot(&self.robot, &origin, &self.scene, &self.options)?;
        let module = generate(&model, &self.scene, &self.options, &origin)?;
        Ok((module, model.warnings))
    }

    /// Generates the module into `$OUT_DIR/file_name`, prints `cargo:rerun-if-changed` for
    /// the robot file and a `cargo:warning=` line for each warning about it, and copies the
    /// source to `$RNE_KEEP_GENERATED/file_name` when that variable is set. Returns the path
    /// written.
    pub fn write(&self, file_name: &str) -> Result<PathBuf, CodegenError> {
        println!("cargo:rerun-if-changed={}", self.robot.display());
        println!("cargo:rerun-if-env-changed={KEEP_GENERATED_ENV}");
        let out_dir = std::env::var_os("OUT_DIR").ok_or(CodegenError::MissingEnv("OUT_DIR"))?;
        let (module, warnings) = self.generate_with_warnings()?;
        for warning in &warnings {
            println!("{}", cargo_warning(warning));
        }
        let source = module.to_pretty_string();
        let path = PathBuf::from(out_dir).join(file_name);
        write_file(&path, &source)?;
        if let Some(dir) = std::env::var_os(KEEP_GENERATED_ENV) {
            write_file(&PathBuf::from(dir).join(file_name), &source)?;
        }
        Ok(path)
    }
}

/// The build-script directive that shows `warning` in cargo's output: one line, as cargo reads
/// directives line by line.
fn cargo_warning(warning: &SpecWarning) -> String {
    let text = warning.to_string().replace(['\r', '\n'], " ");
    format!("cargo:warning={text}")
}

fn write_file(path: &Path, contents: &str) -> Result<(), CodegenError> {
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(|cause| CodegenError::Io {
            path: parent.to_path_buf(),
            cause,
        })?;
    }
    // Leave an identical file untouched, so that cargo does not rebuild what includes it.
    if std::fs::read_to_string(path).is_ok_and(|old| old == contents) {
        return Ok(());
    }
    std::fs::write(path, contents).map_err(|cause| CodegenError::Io {
        path: path.to_path_buf(),
        cause,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rne_symbolic::spec::LoadOptions;
    use rne_symbolic::Description;

    #[test]
    fn a_warning_becomes_one_cargo_warning_line_naming_file_link_and_field() {
        let text = "<robot name=\"r\">\n<link name=\"a\"/>\n<joint name=\"j\" type=\"revolute\">\
                    <parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 1\"/></joint>\n\
                    <link name=\"b\"><inertial><mass value=\"1\"/>\
                    <inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.05\"/>\
                    </inertial></link>\n</robot>";
        let model =
            rne_symbolic::read_robot(Description::urdf(text, "r.urdf"), &LoadOptions::default())
                .expect("a warning, not an error");
        let [warning] = &model.warnings[..] else {
            panic!("one warning: {:?}", model.warnings)
        };
        let line = cargo_warning(warning);
        assert!(
            line.starts_with("cargo:warning=r.urdf:4: link 'b', field 'inertial.inertia': "),
            "{line}"
        );
        assert!(line.contains("triangle inequality") && !line.contains('\n'));
    }
}
