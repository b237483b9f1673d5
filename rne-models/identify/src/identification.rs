//! Identification from measurements: the base regressor of every sample stacked against the
//! measured torques and solved by (weighted) least squares; and the torques an identified
//! model predicts on other data.

use nalgebra::DVector;

use crate::base::BaseSet;
use crate::data::Measurements;
use crate::least_squares::{estimate, Estimate};
use crate::regressors::Regressors;
use crate::IdentifyError;

/// How well predicted torques match measured ones.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// Per joint: RMS(τ̂_j − τ_j) / RMS(τ_j).
    pub joints: Vec<f64>,
    /// Over all joints: ‖τ̂ − τ‖ / ‖τ‖.
    pub overall: f64,
}

/// Checks that `data` suit `reference`: NQ positions and NV rates, accelerations and forces
/// per sample.
fn check<R: Regressors + ?Sized>(reference: &R, data: &Measurements) -> Result<(), IdentifyError> {
    if data.joints != reference.nv() || data.positions != reference.nq() {
        return Err(IdentifyError::Model(format!(
            "data of {} positions and {} velocities for a robot of {} and {}",
            data.positions,
            data.joints,
            reference.nq(),
            reference.nv()
        )));
    }
    Ok(())
}

/// The base parameters of `base` estimated from `data` by weighted (`weighted`) or ordinary
/// least squares.
pub fn identify<R: Regressors + ?Sized>(
    reference: &mut R,
    base: &BaseSet,
    data: &Measurements,
    weighted: bool,
) -> Result<Estimate, IdentifyError> {
    check(reference, data)?;
    let w = base.stack(
        reference,
        data.samples
            .iter()
            .map(|s| (s.q.as_slice(), s.qd.as_slice(), s.qdd.as_slice())),
    )?;
    let y = DVector::from_iterator(
        w.nrows(),
        data.samples.iter().flat_map(|s| s.tau.iter().copied()),
    );
    estimate(&w, &y, data.joints, weighted)
}

/// τ̂ = Y_b(q, q̇, q̈) θ at every sample of `data`.
pub fn predict<R: Regressors + ?Sized>(
    reference: &mut R,
    base: &BaseSet,
    theta: &[f64],
    data: &Measurements,
) -> Result<Vec<Vec<f64>>, IdentifyError> {
    check(reference, data)?;
    let theta = DVector::from_column_slice(theta);
    data.samples
        .iter()
        .map(|s| {
            let y = base.base_regressor(reference, &s.q, &s.qd, &s.qdd)?;
            Ok((y * &theta).iter().copied().collect())
        })
        .collect()
}

/// The relative RMS errors of `predicted` against the measured torques of `data`.
pub fn fit(predicted: &[Vec<f64>], data: &Measurements) -> Fit {
    let n = data.joints;
    let mut error = vec![0.0; n];
    let mut size = vec![0.0; n];
    for (p, s) in predicted.iter().zip(&data.samples) {
        for j in 0..n {
            error[j] += (p[j] - s.tau[j]).powi(2);
            size[j] += s.tau[j].powi(2);
        }
    }
    Fit {
        joints: error
            .iter()
            .zip(&size)
            .map(|(e, s)| (e / s).sqrt())
            .collect(),
        overall: (error.iter().sum::<f64>() / size.iter().sum::<f64>()).sqrt(),
    }
}
