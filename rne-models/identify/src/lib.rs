//! Identification of robot dynamics (docs/design.md §4–§5, `rne identify`).
//!
//! The joint torques are linear in the standard parameters, τ = Y(q, q̇, q̈) π (per moving
//! body m, m·c, the inertia about the body origin; per joint friction and armature), and only
//! the base parameters π_b = π₁ + K π₂ are determined by the dynamics. This crate
//!
//! - finds the base parameters of a model from the independent numeric reference's regressor
//!   ([`BaseSet`], Gautier's numerical method) and names them as combinations of standard
//!   ones (`I1zz + 0.09·m2`, [`names`]);
//! - estimates them from measured q, q̇, q̈, τ ([`Measurements`], CSV) by weighted least
//!   squares, with standard deviations and the condition number of the stacked base
//!   regressor ([`identify`], [`least_squares`]);
//! - designs excitation trajectories, finite Fourier series optimised for that condition
//!   number within joint limits ([`excitation`]), and simulates measurements of them with
//!   torque noise ([`simulate()`]);
//! - draws measured against predicted torques (`torque_figure`, feature `figure`, on by
//!   default).
//!
//! # Limitations
//!
//! A floating base is identified from all NV equations of each sample, the wrench on the base
//! included (force plates, or a simulator); Ayusawa, Venture and Nakamura ("Identifiability
//! and identification of inertial parameters using the underactuated base-link dynamics for
//! legged multibody systems", IJRR 33(3), 2014) show that the base's six equations alone
//! determine the same base parameters, which this crate does not exploit. Positions, rates
//! and accelerations are taken as exact: the noise model is on
//! the torques alone, as in Gautier and Poignet's weighted least squares.
#![deny(missing_docs)]

mod base;
mod data;
mod error;
pub mod excitation;
#[cfg(feature = "figure")]
mod figure;
mod free_flyer;
mod identification;
pub mod least_squares;
pub mod names;
mod random;
mod regressors;
mod simulate;

pub use base::{BaseSet, State};
pub use data::{Measurements, Sample};
pub use error::IdentifyError;
pub use excitation::{
    candidates, design, design_with_progress, Design, Excitation, FourierTrajectory, Limits,
};
#[cfg(feature = "figure")]
pub use figure::torque_figure;
pub use free_flyer::{free_flyer_state, BASE_COORDINATES};
pub use identification::{fit, identify, predict, Fit};
pub use least_squares::Estimate;
pub use regressors::Regressors;
pub use simulate::{simulate, Simulation};
