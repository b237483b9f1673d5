//! Agreement of a robot's generated kernels with the independent numeric reference over
//! seeded random states: what `rne verify` reports.
//!
//! Errors are normwise relative, ‖a − b‖∞ / ‖b‖∞, with three choices that keep the measure
//! about the kernel and not about the state:
//! - C(q, q̇) q̇ is compared with the reference's bias without gravity (not bias − g, whose
//!   subtraction cancels digits when velocities are small);
//! - forward dynamics is fed random torques of the size of the gravity torques (torques made
//!   as τ(q̈) cancel most of their digits against the bias when q̈ is small);
//! - the potential energy crosses zero, so its error is taken relative to the size of the
//!   gravity torques, which share its units.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_codegen::{Dynamics, Kernel};
use rne_figures::relative_error;
use rne_models::Visitor;
use rne_reference::Reference;
use rne_symbolic::RobotModel;

use super::CliError;

/// The worst error of one quantity over the sampled states.
#[derive(Clone, Debug, PartialEq)]
pub struct Agreement {
    /// `tau`, `M`, `g`, `bias`, `C qd`, `qdd`, `kinetic` or `potential`.
    pub quantity: &'static str,
    /// Largest relative error seen.
    pub max_error: f64,
    /// Median relative error.
    pub median_error: f64,
}

/// The comparison of a robot's generated `Model` with the reference built from `model` over
/// `samples` states with |q| ≤ π, |q̇| ≤ 10, |q̈| ≤ 10 drawn from a ChaCha8 generator seeded
/// with `seed`.
pub struct Compare<'a> {
    /// The robot's model, for the reference.
    pub model: &'a RobotModel,
    /// Number of states.
    pub samples: usize,
    /// Seed of the states.
    pub seed: u64,
}

impl Visitor for Compare<'_> {
    type Output = Result<Vec<Agreement>, CliError>;

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, robot: D) -> Self::Output {
        compare(self.model, &robot, self.samples, self.seed)
    }
}

/// The value of a kernel the robot must have: `verify` checks every kernel.
fn required<T>(value: Option<T>, kernel: Kernel) -> Result<T, CliError> {
    value.ok_or(CliError::Evaluation(
        rne_interpreted::Error::MissingKernel { kernel },
    ))
}

/// Compares `robot`'s kernels with the reference built from `model` (see [`Compare`]).
fn compare<const N: usize, D: Dynamics<N, N, Scalar = f64>>(
    model: &RobotModel,
    robot: &D,
    samples: usize,
    seed: u64,
) -> Result<Vec<Agreement>, CliError> {
    let mut reference = Reference::try_new(&model.to_numeric())?;
    let mut weightless = model.to_numeric();
    weightless.gravity = [0.0; 3];
    let mut weightless = Reference::try_new(&weightless)?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut uniform =
        |bound: f64| -> [f64; N] { std::array::from_fn(|_| rng.gen_range(-bound..=bound)) };
    const NAMES: [&str; 8] = [
        "tau",
        "M",
        "g",
        "bias",
        "C qd",
        "qdd",
        "kinetic",
        "potential",
    ];
    let mut errors: [Vec<f64>; 8] = Default::default();
    for _ in 0..samples {
        let (q, qd, qdd) = (uniform(std::f64::consts::PI), uniform(10.0), uniform(10.0));
        let tau_ref: Vec<f64> = reference.inverse_dynamics(&q, &qd, &qdd)?.data.into();
        let tau = required(
            robot.inverse_dynamics(&q, &qd, &qdd),
            Kernel::InverseDynamics,
        )?;
        errors[0].push(relative_error(&tau, &tau_ref));
        let m_ref: Vec<f64> = reference.mass_matrix(&q)?.transpose().data.into();
        let m = required(robot.mass_matrix(&q), Kernel::MassMatrix)?;
        errors[1].push(relative_error(m.as_flattened(), &m_ref));
        let g_ref: Vec<f64> = reference.gravity_torques(&q)?.data.into();
        let g = required(robot.gravity_torques(&q), Kernel::GravityTorques)?;
        errors[2].push(relative_error(&g, &g_ref));
        let bias_ref: Vec<f64> = reference.bias_torques(&q, &qd)?.data.into();
        let bias = required(robot.bias_torques(&q, &qd), Kernel::BiasTorques)?;
        errors[3].push(relative_error(&bias, &bias_ref));
        let c = required(robot.coriolis_matrix(&q, &qd), Kernel::CoriolisMatrix)?;
        let c_qd: Vec<f64> = c
            .iter()
            .map(|row| row.iter().zip(&qd).map(|(a, b)| a * b).sum())
            .collect();
        let c_qd_ref: Vec<f64> = weightless.bias_torques(&q, &qd)?.data.into();
        errors[4].push(relative_error(&c_qd, &c_qd_ref));
        let scale = g_ref.iter().fold(10.0, |m: f64, g| m.max(g.abs()));
        let tau_in = uniform(scale);
        let qdd_ref: Vec<f64> = reference.forward_dynamics(&q, &qd, &tau_in)?.data.into();
        let fd = required(
            robot.forward_dynamics(&q, &qd, &tau_in),
            Kernel::ForwardDynamics,
        )?;
        errors[5].push(relative_error(&fd, &qdd_ref));
        let t_ref = reference.kinetic_energy(&q, &qd)?;
        let t = required(robot.kinetic_energy(&q, &qd), Kernel::KineticEnergy)?;
        errors[6].push(relative_error(&[t], &[t_ref]));
        let v_ref = reference.potential_energy(&q)?;
        let v_scale = g_ref.iter().fold(v_ref.abs(), |m, g| m.max(g.abs()));
        let v = required(robot.potential_energy(&q), Kernel::PotentialEnergy)?;
        errors[7].push(if v_scale > 0.0 {
            (v - v_ref).abs() / v_scale
        } else {
            (v - v_ref).abs()
        });
    }
    Ok(NAMES
        .iter()
        .zip(errors.iter_mut())
        .map(|(&quantity, e)| {
            e.sort_by(f64::total_cmp);
            Agreement {
                quantity,
                max_error: e.last().copied().unwrap_or(0.0),
                median_error: e.get(e.len() / 2).copied().unwrap_or(0.0),
            }
        })
        .collect())
}
