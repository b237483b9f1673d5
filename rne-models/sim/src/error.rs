//! Why a simulation stopped early.

use rne_runtime::Kernel;

/// A simulation that could not be completed. Every variant after the first three carries the
/// time reached.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimError {
    /// The output times are empty, not finite or not strictly increasing.
    #[error("output times must be non-empty, finite and strictly increasing")]
    InvalidTimes,
    /// An integrator setting is out of range (a non-positive step or tolerance, ...).
    #[error("invalid integrator setting: {0}")]
    InvalidSetting(&'static str),
    /// The model lacks a kernel the simulation calls ([`SIMULATED`](crate::SIMULATED)).
    #[error("the model has no `{kernel}` kernel, which simulation needs")]
    MissingKernel {
        /// The missing kernel.
        kernel: Kernel,
    },
    /// The state or its derivative became NaN or infinite.
    #[error("state became non-finite at t = {t}")]
    NonFinite {
        /// Time at which it happened.
        t: f64,
    },
    /// The adaptive step size fell below what the floating-point time can resolve
    /// (Hairer–Nørsett–Wanner's `0.1 |h| <= |t| · eps` test): the problem is stiff or singular.
    #[error("step size {h:e} too small at t = {t}")]
    StepSizeTooSmall {
        /// Time reached.
        t: f64,
        /// The step size that was too small.
        h: f64,
    },
    /// The adaptive integrator needed more than its step budget.
    #[error("more than {steps} steps needed; stopped at t = {t}")]
    TooManySteps {
        /// Time reached.
        t: f64,
        /// The step budget that was exhausted.
        steps: u64,
    },
    /// The implicit stage equations of the Gauss–Legendre integrator did not converge within the
    /// iteration cap: the step is too large for fixed-point iteration (h · Lipschitz constant
    /// not small), so reduce it.
    #[error(
        "Gauss-Legendre stage equations did not converge in the step from t = {t} \
         ({iterations} iterations, last change {residual:e}); reduce the step size"
    )]
    NotConverged {
        /// Start time of the failing step.
        t: f64,
        /// Iterations performed.
        iterations: u32,
        /// The last scaled change of the stage values.
        residual: f64,
    },
    /// M(q) was not positive definite to working precision where it had to be factored.
    #[error("mass matrix not positive definite at t = {t}")]
    MassMatrixNotPositiveDefinite {
        /// Time at which it happened.
        t: f64,
    },
}

/// A named run that stopped early: the name says which simulation of a report failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{run}: {cause}")]
pub struct RunError {
    /// The run.
    pub run: String,
    /// Why it stopped.
    pub cause: SimError,
}

impl SimError {
    /// The error of the run `run`, for `map_err`.
    pub fn in_run(run: impl Into<String>) -> impl FnOnce(SimError) -> RunError {
        let run = run.into();
        move |cause| RunError { run, cause }
    }
}
