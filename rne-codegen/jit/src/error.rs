//! Why a model could not be compiled or a kernel called.

use rne_codegen_core::{CodegenError, Input, Kernel};

/// An error of the JIT.
#[derive(Debug, thiserror::Error)]
pub enum JitError {
    /// The robot could not be read or its programs generated.
    #[error(transparent)]
    Codegen(#[from] CodegenError),
    /// This processor has no Cranelift backend (rne's interpreter is the fallback).
    #[error("no JIT for this processor: {0}")]
    UnsupportedHost(String),
    /// Cranelift refused a program: a bug of rne.
    #[error("Cranelift could not compile `{kernel}`: {message}; this is a bug: please report it")]
    Compile {
        /// The kernel.
        kernel: Kernel,
        /// Cranelift's message.
        message: String,
    },
    /// The model has no such kernel (it was not among the outputs asked for).
    #[error("the model has no `{kernel}` kernel (it was not among the outputs asked for)")]
    MissingKernel {
        /// The kernel asked for.
        kernel: Kernel,
    },
    /// An input array has the wrong length.
    #[error("`{kernel}`: `{}` has {got} values; the robot needs {expected}", input.name())]
    InputLength {
        /// The kernel called.
        kernel: Kernel,
        /// The array.
        input: Input,
        /// Its length.
        got: usize,
        /// The length needed.
        expected: usize,
    },
    /// The output array has the wrong length.
    #[error("`{kernel}` returns {expected} values; the output array has {got}")]
    OutputLength {
        /// The kernel called.
        kernel: Kernel,
        /// Its length.
        got: usize,
        /// The length needed.
        expected: usize,
    },
    /// An input holds NaN or an infinity.
    #[error("`{kernel}`: `{}[{index}]` is {value}; the state must be finite", input.name())]
    NonFinite {
        /// The kernel called.
        kernel: Kernel,
        /// The array.
        input: Input,
        /// The entry.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A state of a batch failed its check ([`JitError::NonFinite`]): which state, counted
    /// from 0, and why.
    #[error("state {state} of the batch: {error}")]
    InBatch {
        /// The state's number in the batch.
        state: usize,
        /// Its error, as a single call with it would give.
        error: Box<JitError>,
    },
    /// A batch of a kernel returning several matrices was given arrays for another number
    /// of them (`JitModel::evaluate_batch_matrices`).
    #[error("`{kernel}` returns {expected} matrices (0: it is not one that returns several); {got} arrays were given")]
    MatrixArrays {
        /// The kernel called.
        kernel: Kernel,
        /// The arrays given.
        got: usize,
        /// The kernel's matrices.
        expected: usize,
    },
    /// The parameters given have the wrong length.
    #[error("the model reads {expected} parameters; {got} were given")]
    ParameterLength {
        /// Their number.
        got: usize,
        /// The number the model reads.
        expected: usize,
    },
    /// A batch's arrays disagree in their number of states.
    #[error("`{kernel}` batch: `{}` holds {got} values, not a multiple of {per_state} for {states} states", input.name())]
    BatchLength {
        /// The kernel called.
        kernel: Kernel,
        /// The array.
        input: Input,
        /// Its length.
        got: usize,
        /// Values per state.
        per_state: usize,
        /// States in the batch (from the output array).
        states: usize,
    },
}

impl JitError {
    /// This error as state `state`'s of a batch.
    pub(crate) fn in_batch(self, state: usize) -> JitError {
        JitError::InBatch {
            state,
            error: Box::new(self),
        }
    }
}
