//! A robot's kernels evaluated at run time, for robots that are not compiled in.
//!
//! - [`Interpreted`]: the optimised straight-line programs `derive_dynamics!` emits, evaluated
//!   without compiling them (bit for bit the generated kernels in `f64`, any [`Real`] scalar),
//!   the double-double value of the model's graph, and the inputs each output reads;
//! - [`RuntimeModel`]: those programs, or the independent numeric reference, as
//!   [`Dynamics<N, N>`](rne_codegen::Dynamics) once N is known — the one adapter between a
//!   model built at run time and code written over the trait; [`Interpreted::visit`] picks N;
//! - [`evaluate`]: one kernel of any `Dynamics` at a run-time-sized [`StateRef`], flattened.
//!
//! [`Real`]: rne_codegen::Real
#![deny(missing_docs)]

pub mod agreement;
mod error;
mod evaluate;
mod interpreted;
mod runtime;
mod state;

pub use error::Error;
pub use evaluate::evaluate;
pub use interpreted::Interpreted;
pub use runtime::{visit_jit, RuntimeModel, MAX_DOF};
pub use state::{JointState, StateRef};
