//! Why a stress case could not run or its report could not be written.

use std::path::PathBuf;

use rne_symbolic::spec::SpecError;

use rne_figures::FigureError;
use rne_sim::SimError;

/// A stress case that failed. Every message names the case or the file it is about.
#[derive(Debug, thiserror::Error)]
pub enum StressError {
    /// A stress robot's spec was rejected by the reader (a bug in the case's robot).
    #[error("stress robot {robot}: {source}")]
    Robot {
        /// The robot.
        robot: String,
        /// The reader's error.
        #[source]
        source: SpecError,
    },
    /// A built-in robot the case uses is missing.
    #[error("no built-in robot `{0}`")]
    MissingRobot(String),
    /// A robot's compiled kernels could not be evaluated at a state.
    #[error("{robot}: {source}")]
    Evaluation {
        /// The robot.
        robot: String,
        /// Why.
        #[source]
        source: rne_interpreted::Error,
    },
    /// A simulation of the chaotic-run case stopped.
    #[error("{run}: {source}")]
    Simulation {
        /// The run.
        run: String,
        /// Why it stopped.
        #[source]
        source: SimError,
    },
    /// A file could not be written.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The system's error.
        #[source]
        source: std::io::Error,
    },
    /// A figure could not be drawn or written.
    #[error(transparent)]
    Figure(#[from] FigureError),
}
