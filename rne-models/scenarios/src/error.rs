//! Why a scenario could not be run or written.

use std::path::PathBuf;

use rne_figures::FigureError;
use rne_sim::RunError;

/// A scenario that failed: an unknown name, a bad scenario file, a failed simulation, or output
/// that could not be written. Every message names what it is about.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// No built-in scenario has this name and it is not a `.toml` file.
    #[error(
        "unknown scenario `{0}`; `rne simulate --list` lists them, or pass a .toml scenario file"
    )]
    Unknown(String),
    /// A scenario file is malformed or inconsistent.
    #[error("{}: {message}", path.display())]
    File {
        /// The scenario file.
        path: PathBuf,
        /// What is wrong, naming the key.
        message: String,
    },
    /// The robot of a scenario file could not be read.
    #[error("{}: model: {cause}", path.display())]
    Model {
        /// The scenario file.
        path: PathBuf,
        /// The spec reader's error.
        cause: rne_symbolic::spec::SpecError,
    },
    /// A simulation stopped early.
    #[error(transparent)]
    Simulation(#[from] RunError),
    /// A figure or a report file could not be drawn or written.
    #[error(transparent)]
    Output(#[from] FigureError),
    /// A scenario file's robot could not be evaluated at run time.
    #[error("{}: model: {cause}", path.display())]
    Evaluation {
        /// The scenario file.
        path: PathBuf,
        /// Why.
        cause: rne_interpreted::Error,
    },
}
