//! What the simulator needs of a model: M(q) q̈ + C(q, q̇) q̇ + g(q) = u as the runtime's
//! [`Dynamics<N, N>`] in `f64` — a generated module's `Model` (docs/design.md §4), a run-time
//! model, or a hand-written one — with the kernels of [`SIMULATED`].
//!
//! Contract relied on by the integrators:
//! - `mass_matrix` is symmetric positive definite (thesis section 6.1.1, below (6.2));
//! - `coriolis_matrix` is the Christoffel-symbol matrix, so that Ṁ = C + Cᵀ and Ṁ − 2C is skew
//!   (docs/design.md §4.2). The symplectic integrator uses Cᵀ q̇ = ½ q̇ᵀ (∂M/∂q) q̇ and the
//!   Lyapunov argument of section 6.4, (6.58)–(6.62), uses the skew symmetry; the thesis's (4.46)
//!   gives the right C q̇ but breaks both;
//! - `forward_dynamics` returns q̈ = M⁻¹ (u − C q̇ − g), the thesis's (6.2);
//! - `gravity_torques` is ∂`potential_energy`/∂q;
//! - every method is allocation-free for the runs to be: the integrators call them inside the
//!   step loop.

use rne_runtime::{Dynamics, Kernel};

use crate::error::SimError;

/// The kernels a simulation calls: forward dynamics (6.2) for the explicit integrators, M, C
/// and g for the symplectic one and for gravity compensation, and the energies for the record.
pub const SIMULATED: [Kernel; 6] = [
    Kernel::ForwardDynamics,
    Kernel::MassMatrix,
    Kernel::CoriolisMatrix,
    Kernel::GravityTorques,
    Kernel::KineticEnergy,
    Kernel::PotentialEnergy,
];

/// Checks that `model` has every kernel of [`SIMULATED`] ([`SimError::MissingKernel`]).
pub fn check_kernels<const N: usize, D>(model: &D) -> Result<(), SimError>
where
    D: Dynamics<N, N, Scalar = f64> + ?Sized,
{
    match SIMULATED.into_iter().find(|&k| !model.has(k)) {
        Some(kernel) => Err(SimError::MissingKernel { kernel }),
        None => Ok(()),
    }
}

/// A vector from a kernel [`check_kernels`] found. Were it missing after all, NaN values stop
/// the integration with [`SimError::NonFinite`] instead of a panic.
#[inline]
pub(crate) fn vector<const N: usize>(value: Option<[f64; N]>) -> [f64; N] {
    value.unwrap_or([f64::NAN; N])
}

/// A matrix from a kernel [`check_kernels`] found; see [`vector`].
#[inline]
pub(crate) fn matrix<const N: usize>(value: Option<[[f64; N]; N]>) -> [[f64; N]; N] {
    value.unwrap_or([[f64::NAN; N]; N])
}

/// A scalar from a kernel [`check_kernels`] found; see [`vector`].
#[inline]
pub(crate) fn scalar(value: Option<f64>) -> f64 {
    value.unwrap_or(f64::NAN)
}

/// The same model with gravity removed: M(q) q̈ + C(q, q̇) q̇ = u, the thesis's (6.33) and (6.53).
///
/// This is the thesis's way of compensating gravity ("removing g(q) directly in the dynamic
/// model", section 6.2.5): it is exact when g is known, and equivalent to adding g(q) to an
/// unsaturated input. A generated module with `gravity: [0.0, 0.0, 0.0]` is the same model
/// without the extra evaluation of g; this wrapper serves models that only exist with gravity
/// (run-time models, hand-written test models).
///
/// `forward_dynamics(q, q̇, τ)` is the wrapped model's `forward_dynamics(q, q̇, τ + g(q))`,
/// `gravity_torques` and `potential_energy` are zero; it has the wrapped model's kernels.
#[derive(Clone, Copy, Debug)]
pub struct WithoutGravity<D>(pub D);

impl<const N: usize, D: Dynamics<N, N, Scalar = f64>> Dynamics<N, N> for WithoutGravity<D> {
    type Scalar = f64;
    const NAME: &'static str = D::NAME;
    const JOINTS: &'static [&'static str] = D::JOINTS;
    const FLOATING_BASE: bool = D::FLOATING_BASE;
    const KERNELS: &'static [Kernel] = D::KERNELS;

    fn has(&self, kernel: Kernel) -> bool {
        self.0.has(kernel)
    }
    fn forward_dynamics(&self, q: &[f64; N], qd: &[f64; N], tau: &[f64; N]) -> Option<[f64; N]> {
        let g = self.0.gravity_torques(q)?;
        let tau_g: [f64; N] = std::array::from_fn(|i| tau[i] + g[i]);
        self.0.forward_dynamics(q, qd, &tau_g)
    }
    fn mass_matrix(&self, q: &[f64; N]) -> Option<[[f64; N]; N]> {
        self.0.mass_matrix(q)
    }
    fn coriolis_matrix(&self, q: &[f64; N], qd: &[f64; N]) -> Option<[[f64; N]; N]> {
        self.0.coriolis_matrix(q, qd)
    }
    fn gravity_torques(&self, _q: &[f64; N]) -> Option<[f64; N]> {
        Some([0.0; N])
    }
    fn kinetic_energy(&self, q: &[f64; N], qd: &[f64; N]) -> Option<f64> {
        self.0.kinetic_energy(q, qd)
    }
    fn potential_energy(&self, _q: &[f64; N]) -> Option<f64> {
        Some(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_models::PlanarElbow;

    /// `WithoutGravity` removes g from (6.2): with τ = 0 at rest the arm does not move, and the
    /// inertia and Coriolis terms are those of the wrapped model.
    #[test]
    fn without_gravity_removes_only_gravity() {
        let arm = PlanarElbow::thesis();
        let free = WithoutGravity(arm);
        let q = [0.3, -0.7];
        let fd = |qd: &[f64; 2], tau: &[f64; 2]| free.forward_dynamics(&q, qd, tau).unwrap();
        assert_eq!(fd(&[0.0; 2], &[0.0; 2]), [0.0; 2]);
        assert_eq!(free.gravity_torques(&q), Some([0.0; 2]));
        assert_eq!(free.potential_energy(&q), Some(0.0));
        assert_eq!(free.mass_matrix(&q), Some(arm.mass_matrix(&q)));
        let qd = [1.0, -2.0];
        let tau = [3.0, 1.0];
        let g = arm.gravity_torques(&q);
        let b = arm.forward_dynamics(&q, &qd, &[tau[0] + g[0], tau[1] + g[1]]);
        assert_eq!(fd(&qd, &tau), b);
        assert!(arm.forward_dynamics(&q, &[0.0; 2], &[0.0; 2])[0].abs() > 1.0);
    }

    /// A model without one of the simulated kernels is refused, naming the kernel.
    #[test]
    fn a_missing_kernel_is_named() {
        struct Inert;
        impl Dynamics<1, 1> for Inert {
            type Scalar = f64;
            const NAME: &'static str = "inert";
            const JOINTS: &'static [&'static str] = &["q"];
            const FLOATING_BASE: bool = false;
            const KERNELS: &'static [Kernel] = &[Kernel::MassMatrix];
        }
        assert_eq!(
            check_kernels(&Inert),
            Err(SimError::MissingKernel {
                kernel: Kernel::ForwardDynamics
            })
        );
        assert_eq!(check_kernels(&PlanarElbow::thesis()), Ok(()));
    }
}
