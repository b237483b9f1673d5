//! What evaluates the regressor and the inverse dynamics for identification: the independent
//! numeric reference, or any engine that computes the same columns (the generated regressor
//! kernel compiled in memory, in `rne identify --engine jit`).

use nalgebra::DMatrix;
use rne_reference::Reference;

use crate::IdentifyError;

/// The regressor `Y(q, q̇, q̈)` (NV rows, one column per standard parameter in
/// [`Reference::parameter_names`]' order) and the inverse dynamics of one robot.
pub trait Regressors {
    /// Size of q.
    fn nq(&self) -> usize;
    /// Size of q̇, q̈ and τ.
    fn nv(&self) -> usize;
    /// `Y(q, q̇, q̈)`, `nv × P`.
    fn regressor(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<DMatrix<f64>, IdentifyError>;
    /// `τ = ID(q, q̇, q̈)`.
    fn inverse_dynamics(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<Vec<f64>, IdentifyError>;
}

impl Regressors for Reference {
    fn nq(&self) -> usize {
        Reference::nq(self)
    }

    fn nv(&self) -> usize {
        Reference::nv(self)
    }

    fn regressor(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<DMatrix<f64>, IdentifyError> {
        Ok(Reference::regressor(self, q, qd, qdd)?)
    }

    fn inverse_dynamics(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<Vec<f64>, IdentifyError> {
        Ok(Reference::inverse_dynamics(self, q, qd, qdd)?
            .iter()
            .copied()
            .collect())
    }
}
