//! Why a run-time evaluation or a comparison could not run.

use rne_codegen::{Input, Kernel};
use rne_reference::ReferenceError;

/// An error of this crate: a state of the wrong size, a kernel a model does not have, or a
/// model the numeric reference cannot evaluate.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A state array had the wrong length.
    #[error("`{}` has {got} values; the robot needs {expected}", input.name())]
    Dimension {
        /// The array.
        input: Input,
        /// Its length.
        got: usize,
        /// The length the robot needs.
        expected: usize,
    },
    /// The model was built or generated without this kernel.
    #[error("the model has no `{kernel}` kernel")]
    MissingKernel {
        /// The kernel asked for.
        kernel: Kernel,
    },
    /// The kernel maps standard parameters, which a joint state does not hold.
    #[error("`{kernel}` takes standard parameters, not a joint state")]
    StandardParameters {
        /// The kernel asked for.
        kernel: Kernel,
    },
    /// A run-time model of N joints was asked for a robot with another number.
    #[error("a model of {expected} joints was asked for a robot with {dof}")]
    Size {
        /// The number of joints of the robot.
        dof: usize,
        /// The number of joints asked for.
        expected: usize,
    },
    /// Run-time models are instantiated for at most `max` joints.
    #[error("the model has {dof} joints; run-time models support 1 to {max}")]
    TooManyJoints {
        /// The number of joints of the robot.
        dof: usize,
        /// The most supported.
        max: usize,
    },
    /// A frame of the kinematics kernels is no link of the numeric reference's model.
    #[error("frame `{0}` is no link of the numeric reference's model")]
    Frame(String),
    /// The JIT could not compile the model or call a kernel.
    #[error(transparent)]
    Jit(#[from] rne_jit::JitError),
    /// The numeric reference cannot evaluate the model.
    #[error("numeric reference: {0}")]
    Reference(ReferenceError),
}

// By hand rather than `#[from]`, which would also return the cause from `source()`, so that a
// printed chain would show it twice (docs/design.md §2.3).
impl From<ReferenceError> for Error {
    fn from(error: ReferenceError) -> Error {
        Error::Reference(error)
    }
}
