//! Simulation: integrators, controllers and the thesis's chapter 6 experiments.
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
