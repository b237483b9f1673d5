//! The experiments of the thesis's chapter 6 as typed runs on the generated `Model`s of
//! [`rne_models::generated`] (the full arms and the [`scenes`](rne_models::generated::scenes)
//! of chapter 6): each
//! function fixes the model and the input of one experiment, the caller the integrator and the
//! output times.

use super::parameters::{
    DAMPING_KD, ELBOW_KD, ELBOW_KP, ELBOW_U_MAX, IRB140_KD, IRB140_KP, IRB140_U_MAX,
};
use rne_models::generated::planar_elbow::{self, Model as PlanarElbow};
use rne_models::generated::scenes::irb140_joint3::Model as Irb140Joint3;
use rne_models::generated::scenes::irb140_weightless::Model as Irb140Weightless;
use rne_models::generated::scenes::planar_elbow_viscous::Model as PlanarElbowViscous;
use rne_models::generated::scenes::planar_elbow_weightless::Model as PlanarElbowWeightless;
use rne_sim::{
    simulate, ConstantTorque, Controller, Damping, Integrator, Pd, Record, SimError, State,
    ZeroInput,
};

/// The open-loop torque of section 6.2.3, τ = g(π, 0): the torque that holds the arm at the
/// desired q = (π, 0), (6.27)–(6.28), from the generated gravity kernel.
pub fn upright_torque() -> [f64; 2] {
    planar_elbow::gravity_torques(&[std::f64::consts::PI, 0.0])
}

/// Open loop, figures 6.2 and 6.3: the planar elbow driven by the constant τ = g(π, 0) from
/// rest at (q₁₀, 0). Unstable from q = 0 (6.2) and, more slowly, from q₁ = π − 0.01 (6.3).
pub fn open_loop<I: Integrator<2>>(
    q1_0: f64,
    integrator: &I,
    times: &[f64],
) -> Result<Record<2>, SimError> {
    let torque = ConstantTorque(upright_torque());
    simulate(
        &PlanarElbow,
        &torque,
        integrator,
        &State::at_rest([q1_0, 0.0]),
        times,
    )
}

/// The released double pendulum, figures 6.4–6.8: the planar elbow with no input (6.29) from
/// rest at `q0`, a conservative and chaotic system.
pub fn released<I: Integrator<2>>(
    q0: [f64; 2],
    integrator: &I,
    times: &[f64],
) -> Result<Record<2>, SimError> {
    simulate(
        &PlanarElbow,
        &ZeroInput,
        integrator,
        &State::at_rest(q0),
        times,
    )
}

/// The damped double pendulum, figure 6.10: u = −Kd q̇ with Kd = (1.5, 1.5), (6.30)–(6.31),
/// released from q = 0.
pub fn damped<I: Integrator<2>>(integrator: &I, times: &[f64]) -> Result<Record<2>, SimError> {
    let damping = Damping::new(DAMPING_KD);
    simulate(
        &PlanarElbow,
        &damping,
        integrator,
        &State::at_rest([0.0, 0.0]),
        times,
    )
}

/// The damped double pendulum of figure 6.10 with the damping in the model instead of the
/// controller: the planar elbow whose spec gives both joints viscous friction fv = 1.5, no
/// input, released from q = 0. Its equation M q̈ + C q̇ + g + fv q̇ = 0 is (6.31).
pub fn damped_by_friction<I: Integrator<2>>(
    integrator: &I,
    times: &[f64],
) -> Result<Record<2>, SimError> {
    simulate(
        &PlanarElbowViscous,
        &ZeroInput,
        integrator,
        &State::at_rest([0.0, 0.0]),
        times,
    )
}

/// PD control of the planar elbow, figures 6.12–6.15: gravity removed from the model,
/// u = sat(−Kp (q − q_ref) − Kd q̇) with (6.34), (6.35) and ±39.4 N·m (6.26), the closed loop
/// (6.33), from rest at q = 0.
pub fn elbow_pd<I: Integrator<2>>(
    q_ref: [f64; 2],
    integrator: &I,
    times: &[f64],
) -> Result<Record<2>, SimError> {
    let pd = Pd::new(ELBOW_KP, ELBOW_KD, q_ref).saturated(ELBOW_U_MAX);
    simulate(
        &PlanarElbowWeightless,
        &pd,
        integrator,
        &State::at_rest([0.0, 0.0]),
        times,
    )
}

/// The IRB 140 joint-3 pendulum, figures 6.16 and 6.17: joints 1 and 2 locked at 0, no input,
/// link 3 released from rest at q₃ = 0.
pub fn irb140_pendulum<I: Integrator<1>>(
    integrator: &I,
    times: &[f64],
) -> Result<Record<1>, SimError> {
    simulate(
        &Irb140Joint3,
        &ZeroInput,
        integrator,
        &State::at_rest([0.0]),
        times,
    )
}

/// PD control of the IRB 140, figures 6.19–6.21: gravity removed from the model (6.53),
/// u = sat(−Kp (q − q_ref) − Kd q̇) with (6.54), (6.55) and table 6.3's limits, from
/// q = q̇ = 0.
pub fn irb140_pd<I: Integrator<3>>(
    q_ref: [f64; 3],
    integrator: &I,
    times: &[f64],
) -> Result<Record<3>, SimError> {
    let pd = Pd::new(IRB140_KP, IRB140_KD, q_ref).saturated(IRB140_U_MAX);
    simulate(
        &Irb140Weightless,
        &pd,
        integrator,
        &State::at_rest([0.0; 3]),
        times,
    )
}
