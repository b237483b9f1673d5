//! The robot a command names (docs/design.md §5: "MODEL is a built-in name (`rne models`
//! lists them) or a path to a `.toml` or `.urdf` file"), the model options every such command
//! takes (`--floating-base`, `--mimic free`, `--strict`), and the warnings of reading it,
//! printed to stderr.

use clap::{Args, ValueEnum};
use rne_codegen_core::{MimicMode, Scene};
use rne_symbolic::model::Base;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::RobotModel;

use super::CliError;
use rne_models::RobotSource;

/// How mimic joints are treated (the macro's `mimic:` setting).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum MimicOption {
    /// URDF semantics: a follower has no variable, `q_f = multiplier · q_leader + offset`.
    #[default]
    Constrained,
    /// Every follower is a joint of its own (Pinocchio's default when loading a URDF).
    Free,
}

/// Model options shared by every command that takes a MODEL.
#[derive(Debug, Default, Args)]
pub struct ModelOptions {
    /// Strict validation: every warning about the robot file (a broken triangle inequality, a
    /// negligible negative inertia, a joint that moves no mass) is an error.
    #[arg(long)]
    pub strict: bool,
    /// A free-flyer root (the macro's `base: floating`): q = [x, y, z, qx, qy, qz, qw, joints],
    /// v = [base linear and angular velocity in the base frame, joint rates].
    #[arg(long)]
    pub floating_base: bool,
    /// Mimic joints follow their leaders (`constrained`, URDF semantics) or are joints of their
    /// own (`free`).
    #[arg(long, value_enum, default_value_t = MimicOption::Constrained)]
    pub mimic: MimicOption,
    /// Take every constant angle as written: `cos(1.5707963267948966)` is 6.1e-17 instead of
    /// 0. By default, rotations by an angle within 4 ulps of a multiple of π/2 (URDF
    /// `rpy="0 1.5707963267948966 0"`) have exact 0 and ±1 entries, so no round-off term
    /// reaches the equations or the kernels (docs/cli.md).
    #[arg(long)]
    pub literal_angles: bool,
}

impl ModelOptions {
    /// The reader's options: these, with parameters folded or kept as `symbolic_parameters`
    /// says.
    pub fn load_options(&self, symbolic_parameters: bool) -> LoadOptions {
        LoadOptions {
            symbolic_parameters,
            strict: self.strict,
            free_mimic: self.mimic == MimicOption::Free,
            exact_right_angles: !self.literal_angles,
        }
    }

    /// Whether the model is the one the robot file describes, as the built-in robots' kernels
    /// were generated (no base override, mimic joints constrained).
    pub fn keeps_the_file_model(&self) -> bool {
        !self.floating_base && self.mimic == MimicOption::Constrained && !self.literal_angles
    }

    /// The codegen scene's mimic mode for these options.
    pub fn mimic_mode(&self) -> MimicMode {
        match self.mimic {
            MimicOption::Constrained => MimicMode::Constrained,
            MimicOption::Free => MimicMode::Free,
        }
    }

    /// A default scene for a model loaded with these options: the model already has its base
    /// and its mimic joints as asked, and generation must keep them.
    pub fn scene(&self) -> Scene {
        Scene {
            mimic: self.mimic_mode(),
            ..Scene::default()
        }
    }

    /// Reads `source`, printing each warning to stderr as `warning: <file>:<line>: ...`, then
    /// applies the options ([`ModelOptions::apply`]).
    pub fn load(
        &self,
        source: &RobotSource,
        symbolic_parameters: bool,
    ) -> Result<RobotModel, CliError> {
        let model = self.read(source, symbolic_parameters)?;
        self.apply(source, model)
    }

    /// Reads `source` as its file describes the robot (mimic followers with their own joint
    /// names, the file's base), printing each warning to stderr.
    pub fn read(
        &self,
        source: &RobotSource,
        symbolic_parameters: bool,
    ) -> Result<RobotModel, CliError> {
        if let RobotSource::File(path) = source {
            if let Some(message) = rne_models::suggest::not_found(&path.to_string_lossy()) {
                return Err(CliError::Argument(message));
            }
        }
        let model = source
            .load(&self.load_options(symbolic_parameters))
            .map_err(|e| self.suggest_free_mimic(source, e.into()))?;
        for warning in &model.warnings {
            eprintln!("warning: {warning}");
        }
        Ok(model)
    }

    /// Sets the base (`--floating-base`) and constrains mimic followers (unless `--mimic
    /// free`). A robot with a fixed base and no moving joint is an error.
    pub fn apply(
        &self,
        source: &RobotSource,
        mut model: RobotModel,
    ) -> Result<RobotModel, CliError> {
        if self.floating_base {
            model.set_base(Base::Floating);
        }
        if self.mimic == MimicOption::Constrained {
            model.constrain_mimic_joints().map_err(|cause| {
                let error = CliError::Mimic {
                    model: source.display_name(),
                    cause,
                };
                self.suggest_free_mimic(source, error)
            })?;
        }
        model
            .check_moves()
            .map_err(|cause| CliError::NothingMoves {
                model: source.display_name(),
                cause,
            })?;
        Ok(model)
    }

    /// `error`, a failure to read `source` or to constrain its mimic joints, with the
    /// suggestion of `--mimic free` when the mimic joints are constrained and reading the
    /// robot with them free (quietly: no warning printed) and applying the other options
    /// succeeds.
    fn suggest_free_mimic(&self, source: &RobotSource, error: CliError) -> CliError {
        if self.mimic == MimicOption::Free
            || !matches!(error, CliError::Spec(_) | CliError::Mimic { .. })
        {
            return error;
        }
        let free = ModelOptions {
            strict: self.strict,
            floating_base: self.floating_base,
            mimic: MimicOption::Free,
            literal_angles: self.literal_angles,
        };
        let loads = source
            .load(&free.load_options(false))
            .map_err(CliError::from)
            .and_then(|model| free.apply(source, model));
        match loads {
            Ok(_) => CliError::MimicFreeLoads {
                cause: Box::new(error),
            },
            Err(_) => error,
        }
    }
}
