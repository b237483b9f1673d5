//! Built-in robots, simulations and the `rne` command; the independent numeric reference is the
//! `rne-reference` crate.
#![deny(missing_docs)]

pub mod accuracy;
pub mod bench;
pub mod builtin;
pub mod cli;
pub mod corpus;
pub mod generated;
pub mod interpreted;
pub mod kernels;
pub mod sim;
pub mod stress;
