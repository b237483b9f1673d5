//! Why a stress case could not run or its report could not be written.

use rne_symbolic::spec::SpecError;

use rne_figures::FigureError;
use rne_sim::RunError;

/// A stress case that failed. Every message names the case or the file it is about.
#[derive(Debug, thiserror::Error)]
pub enum StressError {
    /// A stress robot's spec was rejected by the reader (a bug in the case's robot).
    #[error("stress robot {robot}: {cause}")]
    Robot {
        /// The robot.
        robot: String,
        /// The reader's error.
        cause: SpecError,
    },
    /// A built-in robot the case uses is missing.
    #[error("no built-in robot `{0}`")]
    MissingRobot(String),
    /// A robot's compiled kernels could not be evaluated at a state.
    #[error("{robot}: {cause}")]
    Evaluation {
        /// The robot.
        robot: String,
        /// Why.
        cause: rne_interpreted::Error,
    },
    /// A robot's kernels could not be compiled in memory.
    #[error("{robot}: {cause}")]
    Compile {
        /// The robot.
        robot: String,
        /// Why.
        cause: rne_jit::JitError,
    },
    /// A simulation stopped early.
    #[error(transparent)]
    Simulation(#[from] RunError),
    /// A figure or a report file could not be drawn or written.
    #[error(transparent)]
    Output(#[from] FigureError),
}
