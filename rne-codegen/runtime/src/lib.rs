//! What generated robot dynamics need at run time, and nothing else: `#![no_std]`, no
//! dependencies.
//!
//! - [`Real`]: the scalar the generic (`scalar: generic`) kernels compute in, implemented
//!   for `f32`, `f64` and [`DoubleDouble`] (about 32 significant digits);
//! - [`sin_cos`] and [`sin_cos_array`]: the fast, accurate sine and cosine the `f64`
//!   kernels call for every joint angle;
//! - [`Dynamics`] and [`Kernel`]: the trait every generated module's `Model` implements,
//!   and the names of the functions a module can contain; [`Kinematics`] and
//!   [`Identification`] for modules with frame or regressor kernels.
//! - [`cpu::has_avx2`]: whether the processor runs AVX and AVX2, for the large kernels that a
//!   portable x86-64 build compiles twice.
//!
//! Generated code reaches this crate through `rne_codegen::__private`; users write
//! `rne_codegen::Dynamics`, `rne_codegen::Real`, which re-export these items. `core` has no
//! `sqrt`, `floor` or `round` for `f64`: the runtime has its own, bit for bit those of `std`.
//! With the feature `nalgebra`, the module `convert` turns kernel arrays into nalgebra vectors and
//! matrices and back.
#![no_std]
#![deny(missing_docs)]
// Index loops over small fixed ranges mirror the formulas they implement.
#![allow(clippy::needless_range_loop)]

#[cfg(any(test, feature = "threads"))]
extern crate std;

pub mod batch;
#[cfg(feature = "nalgebra")]
pub mod convert;
pub mod cpu;
mod double_double;
mod dynamics;
mod eft;
mod float;
mod identification;
mod kernel;
mod kinematics;
pub mod lanes;
mod real;
pub mod trig;

pub use double_double::{DoubleDouble, MAX_DIGITS};
pub use dynamics::Dynamics;
pub use identification::Identification;
pub use kernel::{Input, Kernel, Shape, UnknownKernel};
pub use kinematics::Kinematics;
pub use lanes::Lanes;
#[cfg(feature = "simd")]
pub use lanes::{F32x8, F64x4};
pub use real::{OrderedReal, Real};
pub use trig::{sin_cos, sin_cos_array};
