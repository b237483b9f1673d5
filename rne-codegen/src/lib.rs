//! Generated Rust code for a robot's dynamics.
//!
//! Add `rne-codegen` to a crate and write
//!
//! ```ignore
//! rne_codegen::derive_dynamics! {
//!     /// The IRB 140's first three joints.
//!     pub mod irb140 {
//!         robot: "robots/irb140-3dof.toml",
//!         outputs: [inverse_dynamics, mass_matrix, forward_dynamics],
//!     }
//! }
//! let tau = irb140::inverse_dynamics(&q, &qd, &qdd);
//! ```
//!
//! to get flat, allocation-free functions (DESIGN.md §4): `inverse_dynamics`, `mass_matrix`,
//! `coriolis_matrix` (Christoffel), `gravity_torques`, `bias_torques`, `forward_dynamics`,
//! `kinetic_energy`, `potential_energy`, and the constants `NDOF` and `JOINTS`. The module is
//! regenerated when the robot file changes. Scene settings generate only what the
//! application needs: `gravity: [0.0, 0.0, 0.0]` removes every gravity term,
//! `lock: { q1: 0.0 }` turns joints into constants, `velocities: zero` makes a static scene
//! (q̇ = 0: no Coriolis or centrifugal terms), `parameters: runtime` reads the model
//! parameters from a `Params` struct at run time, and `scalar: f32 | generic` changes the
//! scalar type (generic functions take any [`Real`], e.g. [`DoubleDouble`] for ~32 digits).
//!
//! Build scripts use [`Builder`] instead, which writes the same module to `OUT_DIR`.
//!
//! # Compile-time cost
//! Generation runs in the macro at compile time. Proc macros are built without optimisation
//! in debug builds; add `[profile.dev.build-override] opt-level = 3` to the workspace to make
//! expansion of large robots fast.
#![deny(missing_docs)]

pub use rne_codegen_core::{
    build_kernel, generate, generate_from_path, kernel_program, Builder, BuiltKernel, CodegenError,
    GeneratedModule, Kernel, KernelReport, ParameterMode, Program, ScalarType, Scene,
    KEEP_GENERATED_ENV,
};
pub use rne_codegen_macros::derive_dynamics;
pub use rne_symbolic::{DoubleDouble, Real};
