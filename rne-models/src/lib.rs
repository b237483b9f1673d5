//! The built-in robots: their spec files (`robots/`, embedded in the crate), the modules
//! `derive_dynamics!` generates from them ([`generated`]), and [`Visitor`], which runs code
//! written once over [`rne_codegen::Dynamics`] on a robot named at run time.
//!
//! Simulation, benchmarks, stress tests and the `rne` command are crates of their own below
//! `rne-models/`; this crate holds only what is compiled from the robot files.
#![deny(missing_docs)]

pub mod builtin;
pub mod generated;
mod visit;

pub use builtin::{builtin, BuiltinRobot, RobotSource, BUILTIN_ROBOTS};
pub use visit::Visitor;
