//! Simulated measurements: the torques of a trajectory by the numeric reference's inverse
//! dynamics (friction included when the reference includes it), with seeded Gaussian noise.

use crate::data::{Measurements, Sample};
use crate::excitation::FourierTrajectory;
use crate::free_flyer::free_flyer_state;
use crate::random::Random;
use crate::regressors::Regressors;
use crate::IdentifyError;

/// How to sample and disturb a trajectory.
#[derive(Clone, Debug, PartialEq)]
pub struct Simulation {
    /// Length of the record, s.
    pub duration: f64,
    /// Samples per second.
    pub rate: f64,
    /// Standard deviation of the torque noise of each joint, relative to the RMS of that
    /// joint's torque over the record (0.01: 1 %).
    pub noise: f64,
    /// The noise's seed.
    pub seed: u64,
}

/// The measurements a perfect sensor of q, q̇, q̈ and a noisy torque sensor would record along
/// `trajectory`: τ = ID(q, q̇, q̈) + noise · RMS_j(τ_j) · N(0, 1) per joint. On a floating
/// base the trajectory's first six coordinates move the base ([`free_flyer_state`]) and the
/// first six "torques" are the wrench on it, as force plates or a simulator report it.
pub fn simulate<R: Regressors + ?Sized>(
    reference: &mut R,
    trajectory: &FourierTrajectory,
    simulation: &Simulation,
) -> Result<Measurements, IdentifyError> {
    let n = trajectory.joints();
    if n != reference.nv() {
        return Err(IdentifyError::Model(format!(
            "a trajectory of {n} coordinates for a model of {} velocities",
            reference.nv()
        )));
    }
    let floating = reference.nq() != reference.nv();
    let count = (simulation.duration * simulation.rate).round();
    if !(count >= 1.0 && simulation.noise >= 0.0) {
        return Err(IdentifyError::Model(format!(
            "a simulation needs a positive duration and rate and a non-negative noise, got {simulation:?}"
        )));
    }
    let mut samples = trajectory
        .states(simulation.duration, count as usize)
        .into_iter()
        .map(|(t, coordinates)| {
            let (q, qd, qdd) = if floating {
                free_flyer_state(&coordinates)
            } else {
                coordinates
            };
            let tau = reference.inverse_dynamics(&q, &qd, &qdd)?;
            Ok(Sample {
                t: Some(t),
                tau,
                q,
                qd,
                qdd,
            })
        })
        .collect::<Result<Vec<_>, IdentifyError>>()?;
    let rms: Vec<f64> = (0..n)
        .map(|j| {
            (samples.iter().map(|s| s.tau[j].powi(2)).sum::<f64>() / samples.len() as f64).sqrt()
        })
        .collect();
    let mut random = Random::new(simulation.seed);
    for sample in &mut samples {
        for (tau, rms) in sample.tau.iter_mut().zip(&rms) {
            *tau += simulation.noise * rms * random.normal();
        }
    }
    Ok(Measurements {
        positions: reference.nq(),
        joints: n,
        samples,
    })
}
