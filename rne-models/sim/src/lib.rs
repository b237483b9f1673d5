//! Simulation: integrators and controllers, the means of the thesis's chapter 6 experiments.
//! The experiments themselves (the named scenarios of `rne simulate`, their measures and
//! figures) live in the crate `rne-scenarios`, which runs them on this crate; here the unit
//! tests check the integrators and controllers against chapter 6's runs on a hand-written
//! planar elbow.
//!
//! The thesis simulated M(q) q̈ + C(q, q̇) q̇ + g(q) = u in Simulink through the first-order form
//! (6.1)–(6.11), q̈ = M⁻¹ (u − C q̇ − g) (6.2), with ode45 at relative tolerance 1e-10. This
//! crate does the same on any [`Dynamics<N, N>`](rne_runtime::Dynamics) in `f64` with the
//! kernels of [`SIMULATED`] (a generated module's `Model`, a run-time model, a hand-written
//! one; see the contract in [`model`]), allocation-free per step and const-generic over the
//! number of joints N:
//!
//! - integrators ([`Integrator`]): fixed-step [`Rk4`]; adaptive [`Dopri5`], Dormand–Prince 5(4)
//!   with dense output (ode45's method); and the symplectic [`GaussLegendre`] collocation in
//!   canonical coordinates (q, p = M q̇) for conservative runs, whose energy error stays bounded
//!   where the thesis saw a 2 J wobble (figure 6.17);
//! - inputs ([`Controller`]): [`ZeroInput`], [`ConstantTorque`], [`Damping`] (6.30), [`Pd`]
//!   (6.32) with gravity compensation ([`WithoutGravity`] or
//!   [`Controller::with_gravity_compensation`]) and per-joint [`Saturation`], combined freely;
//! - [`simulate`] runs one of them into a [`Record`] (states, inputs, energies and the Lyapunov
//!   function (6.57) at the output times), written as CSV and summarised by the metrics of
//!   [`Record::summary`].
//!
//! Floating-base robots (`base: floating`, docs/design.md §4.5: q = [p, quaternion xyzw, joints]
//! with NQ = NV + 1, v = [base twist in the base frame, joint rates]) do not fit the first-order
//! form over ℝ²ᴺ: their configuration lives on SE(3) × ℝⁿ. For them (and for fixed bases alike):
//!
//! - [`integrate`] is q ⊕ v on the configuration manifold, with the SE(3) exponential for the
//!   base (Pinocchio's `integrate`);
//! - [`LieVariational`] is a second-order Lie-group variational integrator over
//!   [`Dynamics<NQ, NV>`](rne_runtime::Dynamics) with states [`ManifoldState`]: symplectic,
//!   the base quaternion unit to rounding, and the world-frame momentum of a floating robot
//!   without external forces conserved to rounding (discrete Noether), whatever its joints do;
//! - [`world_momentum`] is the robot's total momentum in the world frame, from the first six
//!   rows of M(q) v.
//!
//! ```
//! use rne_runtime::{Dynamics, Kernel};
//! use rne_sim::{world_momentum, LieVariational, ManifoldState};
//!
//! /// A 1 kg box, 0.1 kg·m² about each axis, without gravity: M = diag(1, 1, 1, 0.1, 0.1, 0.1).
//! struct Box;
//! impl Dynamics<7, 6> for Box {
//!     type Scalar = f64;
//!     const NAME: &'static str = "box";
//!     const JOINTS: &'static [&'static str] = &[];
//!     const FLOATING_BASE: bool = true;
//!     const KERNELS: &'static [Kernel] =
//!         &[Kernel::MassMatrix, Kernel::CoriolisMatrix, Kernel::GravityTorques];
//!     fn mass_matrix(&self, _q: &[f64; 7]) -> Option<[[f64; 6]; 6]> {
//!         let d = [1.0, 1.0, 1.0, 0.1, 0.1, 0.1];
//!         Some(std::array::from_fn(|i| std::array::from_fn(|j| if i == j { d[i] } else { 0.0 })))
//!     }
//!     fn coriolis_matrix(&self, _q: &[f64; 7], _v: &[f64; 6]) -> Option<[[f64; 6]; 6]> {
//!         Some([[0.0; 6]; 6]) // only its joint rows are used, and the box has no joints
//!     }
//!     fn gravity_torques(&self, _q: &[f64; 7]) -> Option<[f64; 6]> {
//!         Some([0.0; 6])
//!     }
//! }
//!
//! // Thrown along x while spinning about z: the box's centre runs along a straight line.
//! let x0 = ManifoldState::new([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0, 0.0, 2.0]);
//! let h0 = world_momentum(&Box, &x0.q, &x0.v).unwrap();
//! let no_input = |_: f64, _: &[f64; 7], _: &[f64; 6]| [0.0; 6];
//! let mut last = x0;
//! LieVariational::new(1e-2)
//!     .integrate(&Box, &no_input, &x0, &[0.0, 1.0], |_, x| last = *x)
//!     .unwrap();
//! // Second order: at h = 10 ms the origin is within 1e-4 m of x = 1 m and the turn within
//! // 1e-3 of 2 rad; the momentum is that of the start to rounding.
//! assert!((last.q[0] - 1.0).abs() < 1e-4 && last.q[1].abs() < 1e-12);
//! assert!((2.0 * last.q[5].atan2(last.q[6]) - 2.0).abs() < 1e-3);
//! assert!(world_momentum(&Box, &last.q, &last.v).unwrap().max_difference(&h0) < 1e-14);
//! ```
//!
//! ```
//! use rne_runtime::{Dynamics, Kernel};
//! use rne_sim::{output_times, simulate, Damping, Dopri5, State, SIMULATED};
//!
//! /// A point mass m = 1 kg on a 1 m rod, q = 0 hanging down.
//! struct Pendulum;
//! impl Dynamics<1, 1> for Pendulum {
//!     type Scalar = f64;
//!     const NAME: &'static str = "pendulum";
//!     const JOINTS: &'static [&'static str] = &["q"];
//!     const FLOATING_BASE: bool = false;
//!     const KERNELS: &'static [Kernel] = &SIMULATED;
//!     fn forward_dynamics(&self, q: &[f64; 1], _: &[f64; 1], tau: &[f64; 1]) -> Option<[f64; 1]> {
//!         Some([tau[0] - 9.81 * q[0].sin()])
//!     }
//!     fn mass_matrix(&self, _q: &[f64; 1]) -> Option<[[f64; 1]; 1]> {
//!         Some([[1.0]])
//!     }
//!     fn coriolis_matrix(&self, _q: &[f64; 1], _qd: &[f64; 1]) -> Option<[[f64; 1]; 1]> {
//!         Some([[0.0]])
//!     }
//!     fn gravity_torques(&self, q: &[f64; 1]) -> Option<[f64; 1]> {
//!         Some([9.81 * q[0].sin()])
//!     }
//!     fn kinetic_energy(&self, _q: &[f64; 1], qd: &[f64; 1]) -> Option<f64> {
//!         Some(0.5 * qd[0] * qd[0])
//!     }
//!     fn potential_energy(&self, q: &[f64; 1]) -> Option<f64> {
//!         Some(-9.81 * q[0].cos())
//!     }
//! }
//!
//! let run = simulate(
//!     &Pendulum,
//!     &Damping::new([0.5]),
//!     &Dopri5::new(1e-10, 1e-12),
//!     &State::at_rest([1.0]),
//!     &output_times(0.0, 30.0, 0.01),
//! )
//! .unwrap();
//! assert!(run.q.last().unwrap()[0].abs() < 1e-2);
//! run.write_csv(std::io::sink()).unwrap();
//! ```

#![deny(missing_docs)]

mod configuration;
mod controller;
mod dopri5;
mod error;
mod fixed_point;
mod gauss_legendre;
mod integrator;
mod lie_variational;
pub mod linalg;
mod manifold_state;
mod metrics;
pub mod model;
mod momentum;
mod record;
mod rk4;
mod se3;
mod simulate;
mod state;

#[cfg(test)]
mod alloc_tests;
#[cfg(test)]
mod test_models;
#[cfg(test)]
mod thesis_tests;

pub use configuration::integrate;
pub use controller::{
    ConstantTorque, Controller, Damping, GravityCompensation, Pd, Saturation, Sum, ZeroInput,
};
pub use dopri5::Dopri5;
pub use error::{RunError, SimError};
pub use gauss_legendre::{GaussLegendre, Stages};
pub use integrator::{Integrator, Method, Stats};
pub use lie_variational::LieVariational;
pub use manifold_state::ManifoldState;
pub use metrics::{Summary, SETTLING_BAND};
pub use model::{check_kernels, WithoutGravity, SIMULATED};
pub use momentum::{world_momentum, Momentum};
pub use record::Record;
pub use rk4::Rk4;
pub use simulate::{output_times, simulate};
pub use state::State;
