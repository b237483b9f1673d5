//! Generated Rust code for a robot's dynamics.
//!
//! Add `rne-codegen` to a crate and write
//!
//! ```
//! rne_codegen::derive_dynamics! {
//!     /// The planar elbow manipulator of the thesis.
//!     pub mod elbow {
//!         robot: "tests/robots/planar-elbow.toml",
//!         outputs: [inverse_dynamics, mass_matrix, forward_dynamics],
//!     }
//! }
//!
//! let (q, qd, qdd) = ([0.3, -0.5], [1.0, 0.2], [0.0, 0.0]);
//! let tau = elbow::inverse_dynamics(&q, &qd, &qdd);
//! // Forward dynamics undoes inverse dynamics.
//! let back = elbow::forward_dynamics(&q, &qd, &tau);
//! assert!((back[0] - qdd[0]).abs() < 1e-12 && (back[1] - qdd[1]).abs() < 1e-12);
//!
//! // The same through the `Dynamics` trait, as generic code sees any robot.
//! use rne_codegen::{Dynamics, Kernel};
//! let robot = elbow::Model;
//! assert_eq!(robot.inverse_dynamics(&q, &qd, &qdd), Some(tau));
//! assert!(robot.has(Kernel::MassMatrix) && !robot.has(Kernel::GravityTorques));
//! assert_eq!(robot.gravity_torques(&q), None);
//! assert_eq!(elbow::Model::JOINTS, ["q1", "q2"]);
//! ```
//!
//! to get flat, allocation-free functions (docs/design.md §4): `inverse_dynamics`, `mass_matrix`,
//! `coriolis_matrix` (Christoffel), `gravity_torques`, `bias_torques`, `forward_dynamics`,
//! `kinetic_energy`, `potential_energy`, the constants `NDOF`, `NQ`, `NV` and `JOINTS`, and
//! a `Model` type implementing [`Dynamics`]. The module is regenerated when the robot file
//! changes. Scene settings generate only what the application needs:
//! `gravity: [0.0, 0.0, 0.0]` removes every gravity term, `lock: { q1: 0.0, "joint 8": 0.0 }`
//! turns joints into constants, `at_rest: true` makes a static scene (q̇ = 0: no Coriolis
//! or centrifugal terms), `parameters: runtime` reads the model parameters from a `Params`
//! struct at run time (`parameters: base`: the base parameters, the identifiable combinations
//! of masses and inertias, with `Params::from_standard`), `scalar: f32 | generic` changes the scalar type (generic functions
//! take any [`Real`], e.g. [`DoubleDouble`] for ~32 digits), `base: floating` puts a
//! free-flyer under the robot, `mimic: free` makes mimic followers joints of their own,
//! `validation: strict` makes every warning about the robot file a compile error (by default
//! the warnings are listed in the module's documentation), and
//! `crate: ::my_reexport::rne_codegen` says where the generated code finds this crate when
//! it is renamed or re-exported.
//!
//! # What a crate links
//! Generation runs inside the macro (or a build script); the generated code needs only the
//! runtime (`rne-runtime`, re-exported here: [`Real`], [`Dynamics`], [`Kernel`],
//! [`DoubleDouble`], [`sin_cos`]). Without features this crate is `#![no_std]` and depends
//! on nothing but the runtime and the macro, so generated modules compile in `no_std`
//! crates.
//!
//! # Many states per call
//! With the feature `simd`, [`F64x4`] and [`F32x8`] implement [`Real`]: a `scalar: generic`
//! kernel called with them computes 4 or 8 states at once, each lane bit for bit the scalar
//! kernel at its state. [`batch::evaluate`] runs a kernel over a slice of states, filling the
//! lanes; with the feature `threads`, [`batch::evaluate_threaded`] splits them between the
//! threads of rayon's pool.
//!
//! # Build scripts
//! With the feature `builder` (in `[build-dependencies]`), `Builder` writes the same module
//! to `OUT_DIR`. The feature adds the build-script API and nothing of the generator behind it:
//! `Builder` and `generate_from_path`, their settings (`Scene`, `GenerationOptions`,
//! `ScalarType`, `ParameterMode`, `MimicMode`, `ForwardDynamicsMethod`, `Base`), what they
//! return (`GeneratedModule`,
//! `KernelReport`, `ForwardDynamicsChoice`, `SpecWarning`) and their error (`CodegenError`).
//! The generator's own API (kernels, programs, the C emitter) is `rne-codegen-core`'s.
//! ```toml
//! [build-dependencies]
//! rne-codegen = { version = "0.1", features = ["builder"] }
//! ```
//!
//! # Compile-time cost
//! Generation runs in the macro at compile time. Proc macros are built without optimisation
//! in debug builds; add `[profile.dev.build-override] opt-level = 3` to the workspace to make
//! expansion of large robots fast.
#![cfg_attr(not(feature = "builder"), no_std)]
#![deny(missing_docs)]

pub use rne_codegen_macros::derive_dynamics;
pub use rne_runtime::{
    batch, lanes, sin_cos, sin_cos_array, DoubleDouble, Dynamics, Identification, Input, Kernel,
    Kinematics, Lanes, OrderedReal, Real, Shape, UnknownKernel,
};
#[cfg(feature = "simd")]
pub use rne_runtime::{F32x8, F64x4};

#[cfg(feature = "nalgebra")]
pub use rne_runtime::convert;

// The build-script API, and nothing of the generator behind it: the builder, the function it
// runs, their settings, what they return and their error. Kernel construction, programs and the
// C emitter are rne-codegen-core's own API, which the workspace's tools use directly
// (docs/architecture.md, "The API boundary").
#[cfg(feature = "builder")]
pub use rne_codegen_core::{
    generate_from_path, Builder, CodegenError, ForwardDynamicsChoice, ForwardDynamicsMethod,
    GeneratedModule, GenerationOptions, KernelReport, MimicMode, ParameterMode, ScalarType, Scene,
    KEEP_GENERATED_ENV,
};
/// How the robot's root is attached to the world ([`Builder::base`]).
#[cfg(feature = "builder")]
pub use rne_symbolic::model::Base;
/// A warning about the robot file ([`Builder::generate_with_warnings`]).
#[cfg(feature = "builder")]
pub use rne_symbolic::spec::SpecWarning;

/// What generated code reaches the runtime by (`::rne_codegen::__private::Real`, ...); not
/// an API.
#[doc(hidden)]
pub mod __private {
    pub use rne_runtime::*;
}
