//! The `Identification` trait: the regressor τ = Y(q, q̇, q̈) π of a generated module, its
//! base parameters and base regressor (docs/design.md §4).

use crate::Dynamics;

/// The identification kernels of a robot with `NP` standard and `NB` base parameters.
/// Implemented by a generated module's `Model` when the module has an identification kernel;
/// the methods of the kernels it did not generate return `None`.
///
/// Standard parameters per moving body, in Pinocchio's order: m, m·cx, m·cy, m·cz, Ixx, Ixy,
/// Iyy, Ixz, Iyz, Izz (inertia about the body frame's origin), then the joints' friction and
/// armature parameters the model has.
pub trait Identification<const NQ: usize, const NV: usize, const NP: usize, const NB: usize>:
    Dynamics<NQ, NV>
{
    /// Names of the standard parameters π, in the regressor's column order.
    const PARAMETERS: &'static [&'static str];
    /// Names of the base parameters π_b, in the base regressor's column order.
    const BASE_PARAMETERS: &'static [&'static str];

    /// Y(q, q̇, q̈): τ = Y π.
    fn regressor(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
        qdd: &[Self::Scalar; NV],
    ) -> Option<[[Self::Scalar; NP]; NV]> {
        let _ = (q, qd, qdd);
        None
    }

    /// Y_b(q, q̇, q̈): τ = Y_b π_b, of full column rank.
    fn base_regressor(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
        qdd: &[Self::Scalar; NV],
    ) -> Option<[[Self::Scalar; NB]; NV]> {
        let _ = (q, qd, qdd);
        None
    }

    /// π_b of the standard parameters π.
    fn base_parameters(&self, standard: &[Self::Scalar; NP]) -> Option<[Self::Scalar; NB]> {
        let _ = standard;
        None
    }
}
