//! Simulation: integrators, controllers and the thesis's chapter 6 experiments.
//!
//! The thesis simulated M(q) q̈ + C(q, q̇) q̇ + g(q) = u in Simulink through the first-order form
//! (6.1)–(6.11), q̈ = M⁻¹ (u − C q̇ − g) (6.2), with ode45 at relative tolerance 1e-10. This
//! module does the same on any [`Dynamics`] (the generated kernels or the numeric reference),
//! allocation-free per step and const-generic over the number of joints N:
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
//! use rne_models::sim::{output_times, simulate, Damping, Dopri5, Dynamics, State};
//!
//! /// A point mass m = 1 kg on a 1 m rod, q = 0 hanging down.
//! struct Pendulum;
//! impl Dynamics<1> for Pendulum {
//!     fn forward_dynamics(&self, q: &[f64; 1], _qd: &[f64; 1], tau: &[f64; 1]) -> [f64; 1] {
//!         [tau[0] - 9.81 * q[0].sin()]
//!     }
//!     fn mass_matrix(&self, _q: &[f64; 1]) -> [[f64; 1]; 1] { [[1.0]] }
//!     fn coriolis_matrix(&self, _q: &[f64; 1], _qd: &[f64; 1]) -> [[f64; 1]; 1] { [[0.0]] }
//!     fn gravity_torques(&self, q: &[f64; 1]) -> [f64; 1] { [9.81 * q[0].sin()] }
//!     fn kinetic_energy(&self, _q: &[f64; 1], qd: &[f64; 1]) -> f64 { 0.5 * qd[0] * qd[0] }
//!     fn potential_energy(&self, q: &[f64; 1]) -> f64 { -9.81 * q[0].cos() }
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

mod controller;
mod dopri5;
mod dynamics;
mod error;
mod gauss_legendre;
mod integrator;
pub mod linalg;
mod metrics;
mod record;
mod rk4;
pub mod scenarios;
mod simulate;
mod state;

#[cfg(test)]
mod alloc_tests;
#[cfg(test)]
mod test_models;
#[cfg(test)]
mod thesis_tests;

pub use controller::{
    ConstantTorque, Controller, Damping, GravityCompensation, Pd, Saturation, Sum, ZeroInput,
};
pub use dopri5::Dopri5;
pub use dynamics::{Dynamics, WithoutGravity};
pub use error::SimError;
pub use gauss_legendre::{GaussLegendre, Stages};
pub use integrator::{Integrator, Method, Stats};
pub use metrics::{Summary, SETTLING_BAND};
pub use record::Record;
pub use rk4::Rk4;
pub use simulate::{output_times, simulate};
pub use state::State;
