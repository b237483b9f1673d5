//! The thesis's chapter 6 experiments as named scenarios, and user scenarios from TOML files:
//! what `rne simulate` runs.
//!
//! The robots are the generated `Model`s of [`rne_models::generated`] for each scene of
//! chapter 6 (full, gravity removed, joints 1–2 locked), simulated by [`rne_sim`].
//!
//! - [`parameters`]: the thesis's gains, motor limits, initial conditions, durations and solver
//!   settings, and the set-points rne chose where the thesis does not state them;
//! - [`experiments`]: one typed run per experiment (figures 6.2–6.21);
//! - [`measures`]: settling times, convergence, divergence, flips, turning points;
//! - [`SCENARIOS`] / [`find`]: the named scenarios, each producing an [`Outcome`]: CSV tables,
//!   [`Figure`](rne_figures::time_series::Figure)s rendered as SVG and PNG, and [`Finding`]s (rne's measurement beside the
//!   thesis's report);
//! - [`UserScenario`]: a scenario file (model, initial state, controller, gains, saturation,
//!   duration, integrator, tolerance) run through the same machinery, on the generated kernels
//!   of a built-in robot or on the optimised programs of any spec file
//!   ([`RuntimeModel`](rne_interpreted::RuntimeModel)).
//!
//! ```no_run
//! use rne_scenarios::{find, Format, RunOptions};
//!
//! let outcome = find("damped-pendulum").unwrap().run(&RunOptions::default()).unwrap();
//! println!("{}", outcome.findings_table());
//! outcome.write("out".as_ref(), &Format::ALL).unwrap();
//! ```

#![deny(missing_docs)]

mod catalogue;
mod control;
mod error;
pub mod experiments;
mod figures;
mod floating_run;
mod free_runs;
mod friction_run;
pub mod measures;
mod outcome;
pub mod parameters;
mod progress;
mod timing;
mod user;

pub use catalogue::{find, FileEngine, RunOptions, Scenario, SCENARIOS};
pub use error::ScenarioError;
pub use outcome::{Finding, Format, Outcome, Table};
pub use progress::WithProgress;
pub use timing::{time_thesis_release, Timing};
pub use user::{GravityMode, UserScenario};
