//! The model interface the simulator integrates: M(q) q̈ + C(q, q̇) q̇ + g(q) = u.

/// A rigid-body model M(q) q̈ + C(q, q̇) q̇ + g(q) = u with N joints, as the generated kernels
/// (DESIGN §4) and the numeric reference provide it.
///
/// Every method mirrors one generated free function over fixed-size arrays, so an
/// implementation for a generated robot is a unit struct forwarding to its module. All methods
/// must be allocation-free: the integrators call them inside the step loop.
///
/// Contract relied on by the integrators:
/// - `mass_matrix` is symmetric positive definite (thesis section 6.1.1, below (6.2));
/// - `coriolis_matrix` is the Christoffel-symbol matrix, so that Ṁ = C + Cᵀ and Ṁ − 2C is skew
///   (DESIGN §6). The symplectic integrator uses Cᵀ q̇ = ½ q̇ᵀ (∂M/∂q) q̇ and the Lyapunov
///   argument of section 6.4, (6.58)–(6.62), uses the skew symmetry; the thesis's (4.46) gives
///   the right C q̇ but breaks both;
/// - `forward_dynamics` returns q̈ = M⁻¹ (u − C q̇ − g), the thesis's (6.2);
/// - `gravity_torques` is ∂`potential_energy`/∂q.
pub trait Dynamics<const N: usize> {
    /// q̈ = M(q)⁻¹ (τ − C(q, q̇) q̇ − g(q)), the thesis's (6.2).
    fn forward_dynamics(&self, q: &[f64; N], qd: &[f64; N], tau: &[f64; N]) -> [f64; N];
    /// The joint-space inertia matrix M(q), symmetric positive definite, row-major.
    fn mass_matrix(&self, q: &[f64; N]) -> [[f64; N]; N];
    /// The Christoffel Coriolis/centrifugal matrix C(q, q̇), with Ṁ = C + Cᵀ.
    fn coriolis_matrix(&self, q: &[f64; N], qd: &[f64; N]) -> [[f64; N]; N];
    /// The gravity torques g(q) = ∂V/∂q.
    fn gravity_torques(&self, q: &[f64; N]) -> [f64; N];
    /// The kinetic energy T = ½ q̇ᵀ M(q) q̇.
    fn kinetic_energy(&self, q: &[f64; N], qd: &[f64; N]) -> f64;
    /// The potential energy V(q) with g(q) = ∂V/∂q.
    fn potential_energy(&self, q: &[f64; N]) -> f64;
}

impl<const N: usize, D: Dynamics<N> + ?Sized> Dynamics<N> for &D {
    fn forward_dynamics(&self, q: &[f64; N], qd: &[f64; N], tau: &[f64; N]) -> [f64; N] {
        (**self).forward_dynamics(q, qd, tau)
    }
    fn mass_matrix(&self, q: &[f64; N]) -> [[f64; N]; N] {
        (**self).mass_matrix(q)
    }
    fn coriolis_matrix(&self, q: &[f64; N], qd: &[f64; N]) -> [[f64; N]; N] {
        (**self).coriolis_matrix(q, qd)
    }
    fn gravity_torques(&self, q: &[f64; N]) -> [f64; N] {
        (**self).gravity_torques(q)
    }
    fn kinetic_energy(&self, q: &[f64; N], qd: &[f64; N]) -> f64 {
        (**self).kinetic_energy(q, qd)
    }
    fn potential_energy(&self, q: &[f64; N]) -> f64 {
        (**self).potential_energy(q)
    }
}

/// The same model with gravity removed: M(q) q̈ + C(q, q̇) q̇ = u, the thesis's (6.33) and (6.53).
///
/// This is the thesis's way of compensating gravity ("removing g(q) directly in the dynamic
/// model", section 6.2.5): it is exact when g is known, and equivalent to adding g(q) to an
/// unsaturated input. A generated module with `gravity: [0.0, 0.0, 0.0]` is the same model
/// without the extra evaluation of g; this wrapper serves models that only exist with gravity
/// (the numeric reference, hand-written test models).
///
/// `forward_dynamics(q, q̇, τ)` is the wrapped model's `forward_dynamics(q, q̇, τ + g(q))`,
/// `gravity_torques` and `potential_energy` are zero.
#[derive(Clone, Copy, Debug)]
pub struct WithoutGravity<D>(pub D);

impl<const N: usize, D: Dynamics<N>> Dynamics<N> for WithoutGravity<D> {
    fn forward_dynamics(&self, q: &[f64; N], qd: &[f64; N], tau: &[f64; N]) -> [f64; N] {
        let g = self.0.gravity_torques(q);
        let tau_g: [f64; N] = std::array::from_fn(|i| tau[i] + g[i]);
        self.0.forward_dynamics(q, qd, &tau_g)
    }
    fn mass_matrix(&self, q: &[f64; N]) -> [[f64; N]; N] {
        self.0.mass_matrix(q)
    }
    fn coriolis_matrix(&self, q: &[f64; N], qd: &[f64; N]) -> [[f64; N]; N] {
        self.0.coriolis_matrix(q, qd)
    }
    fn gravity_torques(&self, _q: &[f64; N]) -> [f64; N] {
        [0.0; N]
    }
    fn kinetic_energy(&self, q: &[f64; N], qd: &[f64; N]) -> f64 {
        self.0.kinetic_energy(q, qd)
    }
    fn potential_energy(&self, _q: &[f64; N]) -> f64 {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::test_models::PlanarElbow;

    /// `WithoutGravity` removes g from (6.2): with τ = 0 at rest the arm does not move, and the
    /// inertia and Coriolis terms are those of the wrapped model.
    #[test]
    fn without_gravity_removes_only_gravity() {
        let arm = PlanarElbow::thesis();
        let free = WithoutGravity(arm);
        let q = [0.3, -0.7];
        assert_eq!(free.forward_dynamics(&q, &[0.0; 2], &[0.0; 2]), [0.0; 2]);
        assert_eq!(free.gravity_torques(&q), [0.0; 2]);
        assert_eq!(free.potential_energy(&q), 0.0);
        assert_eq!(free.mass_matrix(&q), arm.mass_matrix(&q));
        let qd = [1.0, -2.0];
        let tau = [3.0, 1.0];
        let a = free.forward_dynamics(&q, &qd, &tau);
        let g = arm.gravity_torques(&q);
        let b = arm.forward_dynamics(&q, &qd, &[tau[0] + g[0], tau[1] + g[1]]);
        assert_eq!(a, b);
        assert!(arm.forward_dynamics(&q, &[0.0; 2], &[0.0; 2])[0].abs() > 1.0);
    }
}
