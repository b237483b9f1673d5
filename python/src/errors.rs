//! rne's errors as Python exceptions: a bad argument or state is a `ValueError` (a wrong type
//! a `TypeError`, raised where the arrays are read), an unreadable file an `OSError`, a failure
//! of rne itself a `RuntimeError`; the message is rne's own.

use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyRuntimeError, PyValueError};
use pyo3::PyErr;
use rne_codegen_core::CodegenError;
use rne_identify::IdentifyError;
use rne_jit::JitError;

/// A JIT error: the compiler's and the processor's are rne's (`RuntimeError`), the rest are
/// about the model or the arrays given (`ValueError`).
pub(crate) fn jit(error: JitError) -> PyErr {
    match error {
        JitError::Codegen(e) => codegen(e),
        e @ (JitError::Compile { .. } | JitError::UnsupportedHost(_)) => {
            PyRuntimeError::new_err(e.to_string())
        }
        e => PyValueError::new_err(e.to_string()),
    }
}

/// A generation error: reading the file is an `OSError`, everything else is about the robot or
/// the options (`ValueError`).
pub(crate) fn codegen(error: CodegenError) -> PyErr {
    match error {
        e @ (CodegenError::Read { .. } | CodegenError::Io { .. }) => {
            PyOSError::new_err(e.to_string())
        }
        e => PyValueError::new_err(e.to_string()),
    }
}

/// An identification error: a file's is an `OSError`, the others `ValueError`.
pub(crate) fn identify(error: IdentifyError) -> PyErr {
    match error {
        e @ IdentifyError::Io { .. } => PyOSError::new_err(e.to_string()),
        e => PyValueError::new_err(e.to_string()),
    }
}

/// A robot file that could not be read.
pub(crate) fn io(path: &str, error: &std::io::Error) -> PyErr {
    let message = format!("{path}: {error}");
    match error.kind() {
        std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(format!(
            "{message} (not a file, nor a built-in robot: {})",
            crate::builtin::BUILTINS
                .iter()
                .map(|b| b.name)
                .collect::<Vec<_>>()
                .join(", ")
        )),
        _ => PyOSError::new_err(message),
    }
}
