//! The built-in robots: their spec files (`robots/`, embedded in the crate), the modules
//! `derive_dynamics!` generates from them ([`generated`]), and [`Visitor`], which runs code
//! written once over [`rne_codegen::Dynamics`] on a robot named at run time; [`robots_dir`]
//! and [`QUADRUPED`] (a robot file without a generated module) for programs and tests that read
//! the files themselves.
//!
//! Simulation, benchmarks, stress tests and the `rne` command are crates of their own below
//! `rne-models/`; this crate holds only what is compiled from the robot files.
#![deny(missing_docs)]

pub mod builtin;
pub mod generated;
mod robot_file;
pub mod suggest;
mod visit;

pub use builtin::{builtin, BuiltinRobot, RobotSource, BUILTIN_ROBOTS};
pub use robot_file::{robots_dir, RobotFile, QUADRUPED};
pub use visit::Visitor;
