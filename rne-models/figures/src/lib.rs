//! The figures, tables and error measures of the simulation, bench and stress reports, written
//! once: one font registration and palette ([`mod@render`]), one markdown [`Table`], one number
//! format ([`sci`], [`ulps`]), one ulp and one normwise relative error ([`measure`]).
//!
//! Three kinds of figure, each drawn on any plotters backend ([`Draw`]) and written as SVG and
//! PNG by [`render()`] (or to one file the user names by [`render_file`]):
//! - [`time_series`]: panels of curves against time or another variable (the simulations,
//!   identification's torques, the iLQR example);
//! - [`work_precision`]: cost against error on log-log axes with ranges (the benchmarks);
//! - [`log_plot`]: errors on a log axis against a parameter (the stress cases).
#![deny(missing_docs)]

mod error;
mod format;
pub mod log_plot;
pub mod measure;
pub mod render;
mod table;
pub mod time_series;
pub mod work_precision;

pub use error::FigureError;
pub use format::{sci, ulps};
pub use measure::{relative_error, relative_error_floor, ulp, Deviation, Format};
pub use render::{register_font, render, render_file, Draw, Formats, Mark, PALETTE};
pub use table::Table;
