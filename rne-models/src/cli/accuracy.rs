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
use rne_symbolic::RobotModel;

use crate::kernels::{DimensionError, Kernels};
use rne_reference::{Reference, ReferenceError};

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

/// Why a comparison could not run.
#[derive(Debug, thiserror::Error)]
pub enum AccuracyError {
    /// The model cannot be evaluated numerically.
    #[error(transparent)]
    Reference(#[from] ReferenceError),
    /// Kernels and model disagree on the number of joints.
    #[error(transparent)]
    Dimension(#[from] DimensionError),
}

/// Normwise relative error ‖a − b‖∞ / ‖b‖∞ (absolute when b is zero).
pub fn relative_error(a: &[f64], b: &[f64]) -> f64 {
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    let scale = b.iter().map(|y| y.abs()).fold(0.0, f64::max);
    if scale > 0.0 {
        diff / scale
    } else {
        diff
    }
}

/// Compares `kernels` with the reference built from `model` over `samples` states with
/// |q| ≤ π, |q̇| ≤ 10, |q̈| ≤ 10 drawn from a ChaCha8 generator seeded with `seed`.
pub fn compare(
    model: &RobotModel,
    kernels: &dyn Kernels,
    samples: usize,
    seed: u64,
) -> Result<Vec<Agreement>, AccuracyError> {
    let mut reference = Reference::try_new(&model.to_numeric())?;
    let mut weightless = model.to_numeric();
    weightless.gravity = [0.0; 3];
    let mut weightless = Reference::try_new(&weightless)?;
    let n = kernels.dof();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut uniform =
        |bound: f64| -> Vec<f64> { (0..n).map(|_| rng.gen_range(-bound..=bound)).collect() };
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
        errors[0].push(relative_error(
            &kernels.inverse_dynamics(&q, &qd, &qdd)?,
            &tau_ref,
        ));
        let m_ref: Vec<f64> = reference.mass_matrix(&q)?.transpose().data.into();
        errors[1].push(relative_error(&kernels.mass_matrix(&q)?.concat(), &m_ref));
        let g_ref: Vec<f64> = reference.gravity_torques(&q)?.data.into();
        errors[2].push(relative_error(&kernels.gravity_torques(&q)?, &g_ref));
        let bias_ref: Vec<f64> = reference.bias_torques(&q, &qd)?.data.into();
        errors[3].push(relative_error(&kernels.bias_torques(&q, &qd)?, &bias_ref));
        let c = kernels.coriolis_matrix(&q, &qd)?;
        let c_qd: Vec<f64> = c
            .iter()
            .map(|row| row.iter().zip(&qd).map(|(a, b)| a * b).sum())
            .collect();
        let c_qd_ref: Vec<f64> = weightless.bias_torques(&q, &qd)?.data.into();
        errors[4].push(relative_error(&c_qd, &c_qd_ref));
        let scale = g_ref.iter().fold(10.0, |m: f64, g| m.max(g.abs()));
        let tau_in = uniform(scale);
        let qdd_ref: Vec<f64> = reference.forward_dynamics(&q, &qd, &tau_in)?.data.into();
        errors[5].push(relative_error(
            &kernels.forward_dynamics(&q, &qd, &tau_in)?,
            &qdd_ref,
        ));
        let t_ref = reference.kinetic_energy(&q, &qd)?;
        errors[6].push(relative_error(
            &[kernels.kinetic_energy(&q, &qd)?],
            &[t_ref],
        ));
        let v_ref = reference.potential_energy(&q)?;
        let v_scale = g_ref.iter().fold(v_ref.abs(), |m, g| m.max(g.abs()));
        let v = kernels.potential_energy(&q)?;
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
