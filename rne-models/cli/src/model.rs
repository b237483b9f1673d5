//! The robot a command names (DESIGN §5: "MODEL is a built-in name or a path to a `.toml` or
//! `.urdf` file"), the model options every such command takes, and the warnings of reading
//! it, printed to stderr.

use clap::Args;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::RobotModel;

use super::CliError;
use rne_models::RobotSource;

/// Model options shared by every command that takes a MODEL.
#[derive(Debug, Default, Args)]
pub struct ModelOptions {
    /// Strict validation: every warning about the robot file (a broken triangle inequality, a
    /// negligible negative inertia, a joint that moves no mass) is an error.
    #[arg(long)]
    pub strict: bool,
}

impl ModelOptions {
    /// The reader's options: these, with parameters folded or kept as `symbolic_parameters`
    /// says.
    pub fn load_options(&self, symbolic_parameters: bool) -> LoadOptions {
        LoadOptions {
            symbolic_parameters,
            strict: self.strict,
        }
    }

    /// Reads `source`, printing each warning to stderr as `warning: <file>:<line>: ...`.
    pub fn load(
        &self,
        source: &RobotSource,
        symbolic_parameters: bool,
    ) -> Result<RobotModel, CliError> {
        let model = source.load(&self.load_options(symbolic_parameters))?;
        for warning in &model.warnings {
            eprintln!("warning: {warning}");
        }
        Ok(model)
    }
}
