//! The swing-up of the thesis's planar elbow: from hanging at rest to upright at rest, under
//! the motor limit |u_i| ≤ 39.4 N·m of (6.26).
//!
//! Angles are the thesis's (chapter 4, figure 4.1): q₁ is link 1's angle from the base x axis,
//! q₂ link 2's relative to link 1, gravity along −y (4.10). Hanging is q = (−π/2, 0), upright
//! q = (π/2, 0). Holding link 1 horizontal takes (m₁ l_c1 + m₂ l₁ + m₂ l_c2) g = 88.3 N·m
//! (6.27), more than twice the limit, so the arm cannot be lifted directly: it must be pumped
//! up by swinging, which is what makes this a problem for trajectory optimisation.

use std::f64::consts::FRAC_PI_2;

use nalgebra::SVector;

use crate::backward_pass::Bounds;
use crate::cost::QuadraticCost;
use crate::discretisation::Rk4;
use crate::error::Error;
use crate::ilqr::{solve, Options, Problem, Solution};
use crate::planar_elbow;

/// The motor torque limit of each joint, N·m: (6.26), 20.73 · 1.9 N·m.
pub const TORQUE_LIMIT: f64 = 39.4;
/// Hanging at rest, (q₁, q₂, q̇₁, q̇₂).
pub const HANGING: [f64; 4] = [-FRAC_PI_2, 0.0, 0.0, 0.0];
/// Upright at rest.
pub const UPRIGHT: [f64; 4] = [FRAC_PI_2, 0.0, 0.0, 0.0];

/// State weight of the running cost, per second: a small pull towards upright.
const STATE_WEIGHT: [f64; 4] = [1.0, 1.0, 0.01, 0.01];
/// Control weight of the running cost, per second and N²·m².
const CONTROL_WEIGHT: [f64; 2] = [1e-3, 1e-3];
/// Terminal weight: be upright and at rest at the end of the horizon.
const TERMINAL_WEIGHT: [f64; 4] = [1000.0, 1000.0, 100.0, 100.0];

/// The discretised swing-up problem and the optimiser's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct SwingUp {
    /// The Runge–Kutta step h, s.
    pub time_step: f64,
    /// The number of steps N; the horizon is N h.
    pub steps: usize,
    /// The optimiser's settings.
    pub options: Options,
}

impl SwingUp {
    /// The documented run: h = 10 ms over 3 s, up to 500 iterations.
    pub fn full() -> Self {
        SwingUp {
            time_step: 0.01,
            steps: 300,
            options: Options::default(),
        }
    }

    /// The short form CI runs in a debug build: h = 50 ms over 3 s, up to 40 iterations.
    pub fn quick() -> Self {
        SwingUp {
            time_step: 0.05,
            steps: 60,
            options: Options {
                max_iterations: 40,
                ..Options::default()
            },
        }
    }

    /// The cost of this discretisation.
    pub fn cost(&self) -> QuadraticCost<4, 2> {
        QuadraticCost::diagonal(
            UPRIGHT,
            STATE_WEIGHT,
            CONTROL_WEIGHT,
            TERMINAL_WEIGHT,
            self.time_step,
        )
    }

    /// The discrete dynamics: one Runge–Kutta step of the generated forward dynamics.
    pub fn dynamics(&self) -> Result<Rk4<planar_elbow::Model, 2>, Error> {
        Rk4::new(planar_elbow::Model, self.time_step)
    }

    /// Optimises the swing-up from zero torques.
    pub fn solve(&self) -> Result<Solution<4, 2>, Error> {
        let dynamics = self.dynamics()?;
        let cost = self.cost();
        let problem = Problem {
            dynamics: &dynamics,
            cost: &cost,
            bounds: Bounds::symmetric([TORQUE_LIMIT; 2]),
            initial_state: HANGING.into(),
        };
        solve(&problem, &vec![SVector::zeros(); self.steps], &self.options)
    }
}
