//! Why a simulation stopped early.

use std::fmt;

/// A simulation that could not be completed. Every variant carries the time reached.
#[derive(Clone, Debug, PartialEq)]
pub enum SimError {
    /// The output times are empty, not finite or not strictly increasing.
    InvalidTimes,
    /// An integrator setting is out of range (a non-positive step or tolerance, ...).
    InvalidSetting(&'static str),
    /// The state or its derivative became NaN or infinite.
    NonFinite {
        /// Time at which it happened.
        t: f64,
    },
    /// The adaptive step size fell below what the floating-point time can resolve
    /// (Hairer–Nørsett–Wanner's `0.1 |h| <= |t| · eps` test): the problem is stiff or singular.
    StepSizeTooSmall {
        /// Time reached.
        t: f64,
        /// The step size that was too small.
        h: f64,
    },
    /// The adaptive integrator needed more than its step budget.
    TooManySteps {
        /// Time reached.
        t: f64,
        /// The step budget that was exhausted.
        steps: u64,
    },
    /// The implicit stage equations of the Gauss–Legendre integrator did not converge within the
    /// iteration cap: the step is too large for fixed-point iteration (h · Lipschitz constant
    /// not small), so reduce it.
    NotConverged {
        /// Start time of the failing step.
        t: f64,
        /// Iterations performed.
        iterations: u32,
        /// The last scaled change of the stage values.
        residual: f64,
    },
    /// M(q) was not positive definite to working precision where it had to be factored.
    MassMatrixNotPositiveDefinite {
        /// Time at which it happened.
        t: f64,
    },
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidTimes => {
                write!(
                    f,
                    "output times must be non-empty, finite and strictly increasing"
                )
            }
            Self::InvalidSetting(what) => write!(f, "invalid integrator setting: {what}"),
            Self::NonFinite { t } => write!(f, "state became non-finite at t = {t}"),
            Self::StepSizeTooSmall { t, h } => {
                write!(f, "step size {h:e} too small at t = {t}")
            }
            Self::TooManySteps { t, steps } => {
                write!(f, "more than {steps} steps needed; stopped at t = {t}")
            }
            Self::NotConverged {
                t,
                iterations,
                residual,
            } => write!(
                f,
                "Gauss-Legendre stage equations did not converge in the step from t = {t} \
                 ({iterations} iterations, last change {residual:e}); reduce the step size"
            ),
            Self::MassMatrixNotPositiveDefinite { t } => {
                write!(f, "mass matrix not positive definite at t = {t}")
            }
        }
    }
}

impl std::error::Error for SimError {}
