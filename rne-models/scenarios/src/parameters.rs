//! The numbers of the thesis's chapter 6: motor limits (6.26), (6.52) and table 6.3, PD gains
//! (6.34)–(6.35), (6.54)–(6.55), the damping of (6.30), initial conditions, and the solver
//! settings (section 6.1). The set-points of figures 6.12–6.15 and 6.19–6.21 are not given in
//! the text: the ones here are chosen by rne (see [`ELBOW_SET_POINTS`], [`IRB140_SET_POINTS`]).

use std::f64::consts::{FRAC_PI_2, PI};

use rne_sim::Dopri5;

/// The motor limit of both planar-elbow joints, 20.73 · 1.9 N·m = 39.4 N·m, (6.26).
pub const ELBOW_U_MAX: [f64; 2] = [39.4, 39.4];

/// The planar elbow's proportional gains Kp = (22, 45) N·m/rad, (6.34).
pub const ELBOW_KP: [f64; 2] = [22.0, 45.0];

/// The planar elbow's derivative gains Kd = (15, 8) N·m·s/rad, (6.35).
pub const ELBOW_KD: [f64; 2] = [15.0, 8.0];

/// The damping gains Kd = (1.5, 1.5) N·m·s/rad of the damped double pendulum, (6.30) and
/// figure 6.10.
pub const DAMPING_KD: [f64; 2] = [1.5, 1.5];

/// The initial q₁ of the second open-loop simulation, π − 0.01 (figure 6.3).
pub const NEAR_UPRIGHT_Q1: f64 = PI - 0.01;

/// The perturbed release of figure 6.5: q₁ = 0.000001 rad.
pub const PERTURBED_Q1: f64 = 1e-6;

/// The equilibrium the damped double pendulum settles to, q = (−π/2, 0) (figure 6.10).
pub const HANGING_DOWN: [f64; 2] = [-FRAC_PI_2, 0.0];

/// Set-points of the four planar-elbow PD runs, figures 6.12–6.15, from rest at q = 0.
///
/// The thesis shows the responses but states neither the set-points nor the initial state;
/// these are chosen by rne to span the workspace: a quarter turn of each joint, a folded pose,
/// a large move of joint 1 against a negative elbow, and a move that saturates both motors.
/// Every joint moves, so that each has a settling time.
pub const ELBOW_SET_POINTS: [[f64; 2]; 4] = [
    [FRAC_PI_2, 0.5],
    [-FRAC_PI_2, FRAC_PI_2],
    [PI, -1.0],
    [1.0, 2.0],
];

/// The IRB 140's motor limits (39.4, 39.4, 30.3) N·m, table 6.3 and (6.52).
pub const IRB140_U_MAX: [f64; 3] = [39.4, 39.4, 30.3];

/// The IRB 140's proportional gains Kp = (25, 18, 100) N·m/rad, (6.54).
pub const IRB140_KP: [f64; 3] = [25.0, 18.0, 100.0];

/// The IRB 140's derivative gains Kd = (27, 18, 20) N·m·s/rad, (6.55).
pub const IRB140_KD: [f64; 3] = [27.0, 18.0, 20.0];

/// Set-points of the three IRB 140 PD runs, figures 6.19–6.21, all from q = q̇ = 0 as the
/// thesis states. The set-points are not given; these are chosen by rne within the IRB 140's
/// joint ranges (axis 1 ±180°, axis 2 −90°…110°, axis 3 −230°…50°): a small move of every joint,
/// a large turn of the base with the arm raised, and a large move of joints 2 and 3 together.
pub const IRB140_SET_POINTS: [[f64; 3]; 3] =
    [[0.5, 0.3, -0.4], [2.0, -0.8, 0.6], [-1.0, 1.2, -1.5]];

/// Output spacing of every scenario's records and figures (s).
pub const SAMPLE: f64 = 0.01;

/// Duration of the open-loop run from q = 0, figure 6.2 (s): "unstable almost instantly".
pub const OPEN_LOOP_FROM_ZERO_END: f64 = 5.0;

/// Duration of the open-loop run from q₁ = π − 0.01, figure 6.3 (s).
pub const OPEN_LOOP_NEAR_UPRIGHT_END: f64 = 8.0;

/// Duration of the double-pendulum releases, figures 6.4–6.8 (s).
pub const RELEASE_END: f64 = 70.0;

/// Duration of the damped double pendulum, figure 6.10 (s).
pub const DAMPED_END: f64 = 40.0;

/// Duration of the planar-elbow PD runs, figures 6.12–6.15 (s).
pub const ELBOW_PD_END: f64 = 10.0;

/// Duration of the IRB 140 joint-3 pendulum, figures 6.16–6.17 (s).
pub const IRB140_PENDULUM_END: f64 = 20.0;

/// Duration of the IRB 140 PD runs, figures 6.19–6.21 (s).
pub const IRB140_PD_END: f64 = 15.0;

/// The thesis's solver, ode45 (Dormand–Prince 5(4)) at relative tolerance 1e-10 (section 6.1),
/// with an absolute tolerance of 1e-12 (the thesis does not state one).
pub fn thesis_solver() -> Dopri5 {
    Dopri5::new(1e-10, 1e-12)
}

/// ode45 as MATLAB runs it when only the relative tolerance is set: RelTol 1e-10 with the
/// default AbsTol 1e-6, sampled by interpolation. Used to compare with figure 6.17.
pub fn matlab_ode45() -> Dopri5 {
    Dopri5::new(1e-10, 1e-6)
}

/// Dormand–Prince for energy measurements: relative tolerance `rtol`, absolute tolerance
/// `rtol` / 100, and every output time ends a step (`step_to_outputs`), so every sample is a
/// 5th-order step value rather than the 4th-order dense output, whose interpolation error (a few
/// 1e-9 J on the double pendulum at rtol 1e-12) would dominate the drift.
pub fn energy_solver(rtol: f64) -> Dopri5 {
    Dopri5 {
        step_to_outputs: true,
        ..Dopri5::new(rtol, rtol * 1e-2)
    }
}

/// The relative tolerance of the double-pendulum energy run (figure 6.8): 1e-12.
pub const RELEASE_ENERGY_RTOL: f64 = 1e-12;

/// The relative tolerance of the IRB 140 pendulum energy run (figure 6.17): 1e-13. Its total
/// energy is 154 J against the double pendulum's 0 J (66 J exchanged), and at rtol 1e-12 the
/// drift over 20 s is 1.2e-9 J; rtol 1e-13 brings it to about 1.4e-10 J.
pub const IRB140_ENERGY_RTOL: f64 = 1e-13;

/// The step of the symplectic Gauss–Legendre runs (s): 5 ms, half the output spacing. The
/// energy error of a symplectic method stays bounded only while h is small against the
/// motion's fastest time scale; the chaotic release has fast phases where 10 ms is not: over
/// twelve starts perturbed by 1e-13 rad its largest |E − E(0)| over 1000 s grew to 2–7 times
/// that of the first 100 s (0.04–0.13 J), while at 5 ms it stays within 1.6 times (6–8e-4 J).
pub const GAUSS_LEGENDRE_STEP: f64 = 0.005;

/// Duration of the long symplectic run of the double pendulum (s).
pub const LONG_RUN_END: f64 = 1000.0;
