//! The crate's one error type.

use std::path::PathBuf;

use rne_codegen::Kernel;

/// What can go wrong setting up or solving a problem, or drawing its figure.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The robot's generated module lacks a kernel the discretisation needs.
    #[error("robot `{robot}`: the generated module has no `{kernel}`; add it to the `outputs:` of derive_dynamics!")]
    MissingKernel {
        /// The robot's name.
        robot: &'static str,
        /// The missing kernel.
        kernel: Kernel,
    },
    /// The time step is not a positive finite number.
    #[error("time step {step} s: must be positive and finite")]
    InvalidTimeStep {
        /// The step given.
        step: f64,
    },
    /// No controls to optimise.
    #[error("the horizon has no steps: give at least one initial control")]
    EmptyHorizon,
    /// A control's limits are not finite or not ordered.
    #[error("control {control}: bounds [{lower}, {upper}] must be finite with lower ≤ upper")]
    InvalidBounds {
        /// Index of the control.
        control: usize,
        /// Its lower bound.
        lower: f64,
        /// Its upper bound.
        upper: f64,
    },
    /// The initial state has a NaN or an infinity.
    #[error("the initial state is not finite")]
    NonFiniteInitialState,
    /// The optimiser's settings cannot work.
    #[error("iLQR options: the regularisation factor must exceed 1, the acceptance lie in (0, 1) and the line search steps in (0, 1]")]
    InvalidOptions,
    /// The initial controls drive the state to infinity.
    #[error("the rollout of the initial controls diverges")]
    DivergentInitialRollout,
    /// The figure could not be drawn or written.
    #[error("figure {}: {message}", path.display())]
    Plot {
        /// The file being written.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
}
