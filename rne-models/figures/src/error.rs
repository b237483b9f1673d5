//! Why a figure or a table could not be written.

use std::path::PathBuf;

/// A figure that could not be drawn or a file that could not be written; the message names it.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// The embedded font could not be registered with plotters.
    #[error("the embedded font could not be read")]
    Font,
    /// plotters failed while drawing.
    #[error("cannot draw figure {figure}: {message}")]
    Draw {
        /// The figure's file name.
        figure: String,
        /// plotters' error.
        message: String,
    },
    /// A figure file whose name ends in neither `.svg` nor `.png`.
    #[error("{}: the figure's file name must end in .svg or .png", .0.display())]
    Extension(PathBuf),
    /// A file or directory could not be written.
    #[error("cannot write {}: {cause}", path.display())]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The system's error.
        cause: std::io::Error,
    },
}

impl FigureError {
    /// The error of writing `path`, for `map_err`.
    pub fn io(path: impl Into<PathBuf>) -> impl FnOnce(std::io::Error) -> FigureError {
        let path = path.into();
        move |cause| FigureError::Io { path, cause }
    }
}
