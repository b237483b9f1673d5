//! The `Dynamics` trait: the one generic handle every generated module implements (its
//! `Model` type), so that simulators, controllers and benchmarks are written once for every
//! robot.

use crate::{Kernel, Real};

/// A robot's generated dynamics (docs/design.md §4), with `NQ` configuration and `NV` velocity
/// variables.
///
/// Every generated module has a `pub struct Model` implementing this trait; the methods of
/// the kernels the module generated return `Some`, every other one `None` (see
/// [`Dynamics::KERNELS`] and [`Dynamics::has`]). Matrices are row-major.
///
/// ```
/// use rne_runtime::{Dynamics, Real};
///
/// /// The torques that hold a robot still at `q`, for any robot that has gravity torques.
/// fn holding_torques<const NQ: usize, const NV: usize, D: Dynamics<NQ, NV>>(
///     robot: &D,
///     q: &[D::Scalar; NQ],
/// ) -> Option<[D::Scalar; NV]> {
///     robot.gravity_torques(q)
/// }
/// ```
pub trait Dynamics<const NQ: usize, const NV: usize> {
    /// The scalar the kernels compute in.
    type Scalar: Real;
    /// The robot's name.
    const NAME: &'static str;
    /// Joint variable names, in state order.
    const JOINTS: &'static [&'static str];
    /// Whether the model has a free-flyer root (q = [x, y, z, qx, qy, qz, qw, joints]).
    const FLOATING_BASE: bool;
    /// The kernels this module generated; every other method returns `None`.
    const KERNELS: &'static [Kernel];

    /// Whether the module generated `kernel` (its method returns `Some`).
    fn has(&self, kernel: Kernel) -> bool {
        Self::KERNELS.contains(&kernel)
    }

    /// Joint torques τ = M(q) q̈ + C(q, q̇) q̇ + g(q).
    fn inverse_dynamics(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
        qdd: &[Self::Scalar; NV],
    ) -> Option<[Self::Scalar; NV]> {
        let _ = (q, qd, qdd);
        None
    }

    /// Mass matrix M(q), symmetric.
    fn mass_matrix(&self, q: &[Self::Scalar; NQ]) -> Option<[[Self::Scalar; NV]; NV]> {
        let _ = q;
        None
    }

    /// Christoffel Coriolis matrix C(q, q̇) (Ṁ − 2C is skew-symmetric).
    fn coriolis_matrix(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
    ) -> Option<[[Self::Scalar; NV]; NV]> {
        let _ = (q, qd);
        None
    }

    /// Gravity torques g(q).
    fn gravity_torques(&self, q: &[Self::Scalar; NQ]) -> Option<[Self::Scalar; NV]> {
        let _ = q;
        None
    }

    /// Bias torques C(q, q̇) q̇ + g(q).
    fn bias_torques(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
    ) -> Option<[Self::Scalar; NV]> {
        let _ = (q, qd);
        None
    }

    /// Accelerations q̈ = M(q)⁻¹ (τ − C(q, q̇) q̇ − g(q)).
    fn forward_dynamics(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
        tau: &[Self::Scalar; NV],
    ) -> Option<[Self::Scalar; NV]> {
        let _ = (q, qd, tau);
        None
    }

    /// Kinetic energy ½ q̇ᵀ M(q) q̇.
    fn kinetic_energy(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
    ) -> Option<Self::Scalar> {
        let _ = (q, qd);
        None
    }

    /// Potential energy (zero with every centre of mass at the base origin).
    fn potential_energy(&self, q: &[Self::Scalar; NQ]) -> Option<Self::Scalar> {
        let _ = q;
        None
    }

    /// (∂τ/∂q, ∂τ/∂q̇), ∂/∂q in the tangent space; ∂τ/∂q̈ is the mass matrix.
    #[allow(clippy::type_complexity)]
    fn inverse_dynamics_derivatives(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
        qdd: &[Self::Scalar; NV],
    ) -> Option<([[Self::Scalar; NV]; NV], [[Self::Scalar; NV]; NV])> {
        let _ = (q, qd, qdd);
        None
    }

    /// (∂q̈/∂q, ∂q̈/∂q̇, M⁻¹) at q̈ = FD(q, q̇, τ); ∂q̈/∂τ is M⁻¹.
    #[allow(clippy::type_complexity)]
    fn forward_dynamics_derivatives(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
        tau: &[Self::Scalar; NV],
    ) -> Option<(
        [[Self::Scalar; NV]; NV],
        [[Self::Scalar; NV]; NV],
        [[Self::Scalar; NV]; NV],
    )> {
        let _ = (q, qd, tau);
        None
    }

    /// Inverse mass matrix M(q)⁻¹.
    fn mass_matrix_inverse(&self, q: &[Self::Scalar; NQ]) -> Option<[[Self::Scalar; NV]; NV]> {
        let _ = q;
        None
    }

    /// Joint friction f_v q̇ + f_c sign(q̇) + offset.
    fn friction_torques(&self, qd: &[Self::Scalar; NV]) -> Option<[Self::Scalar; NV]> {
        let _ = qd;
        None
    }
}

/// A reference to a model is the model: generic code can take `&D` or `D` alike.
impl<const NQ: usize, const NV: usize, D: Dynamics<NQ, NV> + ?Sized> Dynamics<NQ, NV> for &D {
    type Scalar = D::Scalar;
    const NAME: &'static str = D::NAME;
    const JOINTS: &'static [&'static str] = D::JOINTS;
    const FLOATING_BASE: bool = D::FLOATING_BASE;
    const KERNELS: &'static [Kernel] = D::KERNELS;

    fn has(&self, kernel: Kernel) -> bool {
        (**self).has(kernel)
    }

    fn inverse_dynamics(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
        qdd: &[Self::Scalar; NV],
    ) -> Option<[Self::Scalar; NV]> {
        (**self).inverse_dynamics(q, qd, qdd)
    }

    fn mass_matrix(&self, q: &[Self::Scalar; NQ]) -> Option<[[Self::Scalar; NV]; NV]> {
        (**self).mass_matrix(q)
    }

    fn coriolis_matrix(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
    ) -> Option<[[Self::Scalar; NV]; NV]> {
        (**self).coriolis_matrix(q, qd)
    }

    fn gravity_torques(&self, q: &[Self::Scalar; NQ]) -> Option<[Self::Scalar; NV]> {
        (**self).gravity_torques(q)
    }

    fn bias_torques(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
    ) -> Option<[Self::Scalar; NV]> {
        (**self).bias_torques(q, qd)
    }

    fn forward_dynamics(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
        tau: &[Self::Scalar; NV],
    ) -> Option<[Self::Scalar; NV]> {
        (**self).forward_dynamics(q, qd, tau)
    }

    fn kinetic_energy(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
    ) -> Option<Self::Scalar> {
        (**self).kinetic_energy(q, qd)
    }

    fn potential_energy(&self, q: &[Self::Scalar; NQ]) -> Option<Self::Scalar> {
        (**self).potential_energy(q)
    }

    #[allow(clippy::type_complexity)]
    fn inverse_dynamics_derivatives(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
        qdd: &[Self::Scalar; NV],
    ) -> Option<([[Self::Scalar; NV]; NV], [[Self::Scalar; NV]; NV])> {
        (**self).inverse_dynamics_derivatives(q, qd, qdd)
    }

    #[allow(clippy::type_complexity)]
    fn forward_dynamics_derivatives(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
        tau: &[Self::Scalar; NV],
    ) -> Option<(
        [[Self::Scalar; NV]; NV],
        [[Self::Scalar; NV]; NV],
        [[Self::Scalar; NV]; NV],
    )> {
        (**self).forward_dynamics_derivatives(q, qd, tau)
    }

    fn mass_matrix_inverse(&self, q: &[Self::Scalar; NQ]) -> Option<[[Self::Scalar; NV]; NV]> {
        (**self).mass_matrix_inverse(q)
    }

    fn friction_torques(&self, qd: &[Self::Scalar; NV]) -> Option<[Self::Scalar; NV]> {
        (**self).friction_torques(qd)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point mass m on a massless rod of length l, swinging in a vertical plane:
    /// M = m l², g(q) = m g l sin q. Only the mass matrix and gravity torques are "generated".
    struct Pendulum {
        m: f64,
        l: f64,
    }

    const GRAVITY: f64 = 9.81;

    impl Dynamics<1, 1> for Pendulum {
        type Scalar = f64;
        const NAME: &'static str = "pendulum";
        const JOINTS: &'static [&'static str] = &["q1"];
        const FLOATING_BASE: bool = false;
        const KERNELS: &'static [Kernel] = &[Kernel::MassMatrix, Kernel::GravityTorques];

        fn mass_matrix(&self, _q: &[f64; 1]) -> Option<[[f64; 1]; 1]> {
            Some([[self.m * self.l * self.l]])
        }

        fn gravity_torques(&self, q: &[f64; 1]) -> Option<[f64; 1]> {
            Some([self.m * GRAVITY * self.l * crate::sin_cos(q[0]).0])
        }
    }

    /// Generic code over the trait: the static torque through whichever reference it gets.
    fn holding_torque<D: Dynamics<1, 1, Scalar = f64>>(robot: D, q: f64) -> Option<f64> {
        robot.gravity_torques(&[q]).map(|g| g[0])
    }

    #[test]
    fn has_answers_from_the_generated_kernels() {
        let p = Pendulum { m: 2.0, l: 0.5 };
        assert!(p.has(Kernel::MassMatrix) && p.has(Kernel::GravityTorques));
        assert!(!p.has(Kernel::InverseDynamics) && !p.has(Kernel::KineticEnergy));
    }

    #[test]
    fn kernels_not_generated_return_none() {
        let p = Pendulum { m: 2.0, l: 0.5 };
        assert_eq!(p.inverse_dynamics(&[0.1], &[0.2], &[0.3]), None);
        assert_eq!(p.coriolis_matrix(&[0.1], &[0.2]), None);
        assert_eq!(p.bias_torques(&[0.1], &[0.2]), None);
        assert_eq!(p.forward_dynamics(&[0.1], &[0.2], &[0.3]), None);
        assert_eq!(p.kinetic_energy(&[0.1], &[0.2]), None);
        assert_eq!(p.potential_energy(&[0.1]), None);
        assert_eq!(p.inverse_dynamics_derivatives(&[0.1], &[0.2], &[0.3]), None);
        assert_eq!(p.forward_dynamics_derivatives(&[0.1], &[0.2], &[0.3]), None);
        assert_eq!(p.mass_matrix_inverse(&[0.1]), None);
        assert_eq!(p.friction_torques(&[0.2]), None);
    }

    #[test]
    fn a_reference_forwards_to_the_model() {
        let p = Pendulum { m: 2.0, l: 0.5 };
        let q = core::f64::consts::FRAC_PI_2;
        assert_eq!(holding_torque(&p, q), Some(2.0 * GRAVITY * 0.5));
        type ByReference<'a> = &'a Pendulum;
        let r: ByReference = &p;
        assert_eq!(
            <ByReference as Dynamics<1, 1>>::mass_matrix(&r, &[0.0]),
            Some([[0.5]])
        );
        assert_eq!(<ByReference as Dynamics<1, 1>>::NAME, "pendulum");
        assert!(<ByReference as Dynamics<1, 1>>::has(
            &r,
            Kernel::GravityTorques
        ));
        assert!(!<ByReference as Dynamics<1, 1>>::has(
            &r,
            Kernel::BiasTorques
        ));
        assert_eq!(
            <ByReference as Dynamics<1, 1>>::inverse_dynamics(&r, &[0.0], &[0.0], &[0.0]),
            None
        );
    }
}
