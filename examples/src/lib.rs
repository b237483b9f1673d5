//! Worked uses of rne's generated kernels.
//!
//! `examples/ilqr_swing_up.rs` swings the thesis's planar elbow (chapter 4, table 6.1) from
//! hanging to upright under its ±39.4 N·m motor limits (6.26) by iterative LQR, with the
//! discrete dynamics and their Jacobians computed from the generated `forward_dynamics` and
//! `forward_dynamics_derivatives` (docs/control.md):
//!
//! ```sh
//! cargo run --release -p rne-examples --example ilqr_swing_up -- --svg docs/figures/ilqr_swing_up.svg
//! ```
//!
//! The pieces: [`Rk4`] (the Runge–Kutta step of a generated robot and its exact Jacobian),
//! [`QuadraticCost`], the box-constrained QP of control-limited DDP ([`solve_box_qp`]),
//! [`backward_pass`], the optimiser [`solve`], the problem [`SwingUp`] and its figure
//! ([`render_swing_up`]).
#![deny(missing_docs)]

mod backward_pass;
mod box_qp;
mod cost;
mod discretisation;
mod error;
mod figure;
mod ilqr;
mod swing_up;

pub use backward_pass::{backward_pass, Bounds, Gains};
pub use box_qp::{solve_box_qp, BoxQpSolution, NotPositiveDefinite};
pub use cost::{QuadraticCost, RunningDerivatives};
pub use discretisation::{Discretisation, Linearisation, Rk4};
pub use error::Error;
pub use figure::render_swing_up;
pub use ilqr::{solve, Iteration, Options, Problem, Solution, Stop, Timings, Trajectory};
pub use swing_up::{SwingUp, HANGING, TORQUE_LIMIT, UPRIGHT};

rne_codegen::derive_dynamics! {
    /// The thesis's planar elbow (chapter 4, parameters of table 6.1): the forward dynamics
    /// (6.2), its derivatives, and the gravity torques and potential energy that pin down the
    /// angle convention.
    pub mod planar_elbow {
        robot: "robots/planar-elbow.toml",
        outputs: [forward_dynamics, forward_dynamics_derivatives, gravity_torques,
                  potential_energy],
    }
}
