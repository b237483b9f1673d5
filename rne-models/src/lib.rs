//! Built-in robots, the independent numeric reference, simulations and the `rne` command.
#![deny(missing_docs)]

pub mod accuracy;
pub mod bench;
pub mod builtin;
pub mod cli;
pub mod generated;
pub mod interpreted;
pub mod kernels;
pub mod reference;
pub mod sim;
pub mod stress;
