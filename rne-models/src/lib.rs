//! Built-in robots, the independent numeric reference, simulations and the `rne` command.
#![deny(missing_docs)]

pub mod reference;
pub mod sim;
