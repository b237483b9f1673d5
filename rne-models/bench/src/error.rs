//! Why a benchmark could not run or its report could not be written.

use rne_codegen_core::CodegenError;
use rne_symbolic::spec::SpecError;

use rne_figures::FigureError;
use rne_reference::ReferenceError;
use rne_sim::RunError;

/// A benchmark that failed. Every message names the robot, run or file it is about.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// A built-in robot's spec was rejected by the reader.
    #[error("{robot}: {cause}")]
    Spec {
        /// The robot.
        robot: String,
        /// The reader's error.
        cause: SpecError,
    },
    /// A scene could not be applied or generated.
    #[error("{robot}: {cause}")]
    Codegen {
        /// The robot.
        robot: String,
        /// The generator's error.
        cause: CodegenError,
    },
    /// The numeric reference rejected the model.
    #[error("{robot}: {cause}")]
    Reference {
        /// The robot.
        robot: String,
        /// The reference's error.
        cause: ReferenceError,
    },
    /// An implementation could not be set up on the sampled states (a variant with another
    /// number of joints, a model the reference cannot evaluate at run time).
    #[error("{robot}: {cause}")]
    Evaluation {
        /// The robot.
        robot: String,
        /// Why.
        cause: rne_interpreted::Error,
    },
    /// The benchmark has no generated variants for a built-in robot, or they do not match it.
    #[error("{robot}: {problem}")]
    Variants {
        /// The robot.
        robot: String,
        /// What is missing or wrong.
        problem: String,
    },
    /// A simulation stopped early.
    #[error(transparent)]
    Simulation(#[from] RunError),
    /// Pinocchio's timing script failed or printed something unexpected.
    #[error("{robot}: Pinocchio: {problem}")]
    Pinocchio {
        /// The robot.
        robot: String,
        /// What went wrong.
        problem: String,
    },
    /// A figure or a report file could not be drawn or written.
    #[error(transparent)]
    Output(#[from] FigureError),
}
