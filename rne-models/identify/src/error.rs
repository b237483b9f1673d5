//! What can go wrong in identification, with the file, line and column of bad data.

use std::path::PathBuf;

/// Why identification failed.
#[derive(Debug, thiserror::Error)]
pub enum IdentifyError {
    /// A measurement file is malformed: the file, the line (1-based) and, when one is to blame,
    /// the column (1-based, with its header name).
    #[error("{}:{line}{}: {message}", file.display(), column.as_ref().map(|(k, name)| format!(": column {k} (`{name}`)")).unwrap_or_default())]
    Data {
        /// The file.
        file: PathBuf,
        /// The line, 1-based.
        line: usize,
        /// The column, 1-based, and its name in the header.
        column: Option<(usize, String)>,
        /// What is wrong.
        message: String,
    },
    /// Reading or writing a file failed.
    #[error("{}: {cause}", file.display())]
    Io {
        /// The file.
        file: PathBuf,
        /// The cause.
        cause: std::io::Error,
    },
    /// The model cannot be identified the way asked.
    #[error("{0}")]
    Model(String),
    /// The data do not determine every base parameter.
    #[error("the data do not excite every base parameter: the stacked base regressor ({rows} equations, {columns} base parameters) has condition number {condition:.3e}; use a richer trajectory (rne identify MODEL --excite OUT.csv)")]
    NotExcited {
        /// Equations.
        rows: usize,
        /// Base parameters.
        columns: usize,
        /// σ_max / σ_min of the stacked base regressor.
        condition: f64,
    },
    /// The numeric reference rejected a state (a wrong vector length).
    #[error(transparent)]
    Reference(#[from] rne_reference::ReferenceError),
    /// The engine evaluating the regressor (`Regressors`) failed.
    #[error(transparent)]
    Engine(Box<dyn std::error::Error + Send + Sync>),
    /// Drawing a figure failed.
    #[error("figure {}: {message}", file.display())]
    Figure {
        /// The figure's file.
        file: PathBuf,
        /// What went wrong.
        message: String,
    },
}
