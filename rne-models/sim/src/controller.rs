//! Inputs u(t, q, q̇): open-loop torques, damping (6.30), PD control (6.32) with gravity
//! compensation and motor saturation, composable.
//!
//! A controller is anything implementing [`Controller`], closures included. The building blocks
//! combine through the provided methods, saturation last:
//!
//! ```
//! use rne_sim::{Controller, Pd};
//! // The thesis's planar-elbow controller, section 6.2.5: (6.34), (6.35), ±39.4 N·m (6.26).
//! let pd = Pd::new([22.0, 45.0], [15.0, 8.0], [1.0, 0.5]).saturated([39.4, 39.4]);
//! let u = pd.torque(0.0, &[0.0, 0.0], &[0.0, 0.0]);
//! assert_eq!(u, [22.0, 22.5]);
//! ```
//!
//! Gravity compensation comes in the two forms of section 6.2.5: simulate a model without
//! gravity (the thesis's way: pass a gravity-free [`Dynamics`], e.g.
//! [`WithoutGravity`](crate::WithoutGravity)), or add g(q) to the input before saturation with
//! [`Controller::with_gravity_compensation`]. The two agree exactly while the motors are not
//! saturated; under saturation only the second is physical (the motors must supply g too).

use rne_runtime::Dynamics;

use super::model::vector;

/// An input law u = u(t, q, q̇) for M(q) q̈ + C(q, q̇) q̇ + g(q) = u.
///
/// Implemented by the building blocks of this module and by every closure
/// `Fn(f64, &[f64; N], &[f64; N]) -> [f64; N]`. Evaluations must be allocation-free and, for the
/// adaptive integrator's error control to be meaningful, piecewise smooth in (t, q, q̇).
pub trait Controller<const N: usize> {
    /// The input torques u(t, q, q̇).
    fn torque(&self, t: f64, q: &[f64; N], qd: &[f64; N]) -> [f64; N];

    /// The energy ½ q̃ᵀ Kp q̃ stored in the virtual springs of a PD law, q̃ = q − q_ref, or `None`
    /// for inputs without a proportional term. The run record adds the kinetic energy to form
    /// the Lyapunov function V of (6.57).
    fn spring_energy(&self, q: &[f64; N]) -> Option<f64> {
        let _ = q;
        None
    }

    /// The sum of two inputs, u = u_self + u_other (spring energies add).
    fn plus<B: Controller<N>>(self, other: B) -> Sum<Self, B>
    where
        Self: Sized,
    {
        Sum(self, other)
    }

    /// Adds the gravity torques g(q) of `model` to this input (before any saturation applied
    /// afterwards): u = u_self + g(q).
    fn with_gravity_compensation<D: Dynamics<N, N, Scalar = f64>>(
        self,
        model: D,
    ) -> GravityCompensation<D, Self>
    where
        Self: Sized,
    {
        GravityCompensation { model, inner: self }
    }

    /// Clips each joint's input to |uᵢ| ≤ u_max,i, the motor limits of (6.26) and table 6.3.
    /// Apply it last so that it bounds the total torque.
    fn saturated(self, u_max: [f64; N]) -> Saturation<N, Self>
    where
        Self: Sized,
    {
        Saturation { inner: self, u_max }
    }
}

impl<const N: usize, F> Controller<N> for F
where
    F: Fn(f64, &[f64; N], &[f64; N]) -> [f64; N],
{
    fn torque(&self, t: f64, q: &[f64; N], qd: &[f64; N]) -> [f64; N] {
        self(t, q, qd)
    }
}

/// No input, u = 0: the released arm of (6.29), a double pendulum for the planar elbow.
#[derive(Clone, Copy, Debug, Default)]
pub struct ZeroInput;

impl<const N: usize> Controller<N> for ZeroInput {
    fn torque(&self, _t: f64, _q: &[f64; N], _qd: &[f64; N]) -> [f64; N] {
        [0.0; N]
    }
}

/// A constant open-loop torque u = τ, e.g. τ = g(π, 0) of (6.27)–(6.28).
#[derive(Clone, Copy, Debug)]
pub struct ConstantTorque<const N: usize>(pub [f64; N]);

impl<const N: usize> Controller<N> for ConstantTorque<N> {
    fn torque(&self, _t: f64, _q: &[f64; N], _qd: &[f64; N]) -> [f64; N] {
        self.0
    }
}

/// Viscous joint damping u = −Kd q̇ with diagonal Kd, the thesis's (6.30)–(6.31).
#[derive(Clone, Copy, Debug)]
pub struct Damping<const N: usize> {
    /// The diagonal of Kd (N·m·s/rad), each entry ≥ 0 for dissipation.
    pub kd: [f64; N],
}

impl<const N: usize> Damping<N> {
    /// Damping with gains `kd`.
    pub fn new(kd: [f64; N]) -> Self {
        Self { kd }
    }
}

impl<const N: usize> Controller<N> for Damping<N> {
    fn torque(&self, _t: f64, _q: &[f64; N], qd: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|i| -self.kd[i] * qd[i])
    }
}

/// Set-point PD control u = −Kp (q − q_ref) − Kd q̇ with diagonal gains: the thesis's (6.32)
/// with its sign fixed (docs/design.md §7; the text writes −Kp (q_ref − q) but defines q̃ = q −
/// q_ref).
///
/// With gravity compensated and no saturation, the closed loop (6.33) has the Lyapunov function
/// V = ½ q̇ᵀ M q̇ + ½ q̃ᵀ Kp q̃ of (6.57) with V̇ = q̇ᵀ (u + Kp q̃) = −q̇ᵀ Kd q̇ ≤ 0, (6.61)–(6.62),
/// using the skew symmetry of Ṁ − 2C. Under per-joint saturation V̇ = Σᵢ q̇ᵢ (sat(uᵢ) + Kp,i q̃ᵢ)
/// is still ≤ 0 wherever |Kp,i q̃ᵢ| ≤ u_max,i for every joint (clipping then never pushes
/// harder than the spring), so V decreases along set-point runs whose springs alone stay
/// within the motor limits.
#[derive(Clone, Copy, Debug)]
pub struct Pd<const N: usize> {
    /// The diagonal of Kp (N·m/rad), each entry > 0.
    pub kp: [f64; N],
    /// The diagonal of Kd (N·m·s/rad), each entry > 0.
    pub kd: [f64; N],
    /// The set-point q_ref.
    pub q_ref: [f64; N],
}

impl<const N: usize> Pd<N> {
    /// PD control with gains `kp`, `kd` towards `q_ref`.
    pub fn new(kp: [f64; N], kd: [f64; N], q_ref: [f64; N]) -> Self {
        Self { kp, kd, q_ref }
    }
}

impl<const N: usize> Controller<N> for Pd<N> {
    fn torque(&self, _t: f64, q: &[f64; N], qd: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|i| -self.kp[i] * (q[i] - self.q_ref[i]) - self.kd[i] * qd[i])
    }

    fn spring_energy(&self, q: &[f64; N]) -> Option<f64> {
        Some(
            (0..N)
                .map(|i| 0.5 * self.kp[i] * (q[i] - self.q_ref[i]).powi(2))
                .sum(),
        )
    }
}

/// The sum of two inputs; built by [`Controller::plus`].
#[derive(Clone, Copy, Debug)]
pub struct Sum<A, B>(pub A, pub B);

impl<const N: usize, A: Controller<N>, B: Controller<N>> Controller<N> for Sum<A, B> {
    fn torque(&self, t: f64, q: &[f64; N], qd: &[f64; N]) -> [f64; N] {
        let a = self.0.torque(t, q, qd);
        let b = self.1.torque(t, q, qd);
        std::array::from_fn(|i| a[i] + b[i])
    }

    fn spring_energy(&self, q: &[f64; N]) -> Option<f64> {
        match (self.0.spring_energy(q), self.1.spring_energy(q)) {
            (Some(a), Some(b)) => Some(a + b),
            (a, b) => a.or(b),
        }
    }
}

/// An input plus the gravity torques g(q) of a model; built by
/// [`Controller::with_gravity_compensation`].
#[derive(Clone, Copy, Debug)]
pub struct GravityCompensation<D, C> {
    /// The model whose g(q) is added (usually the simulated one, or `&model`).
    pub model: D,
    /// The compensated input.
    pub inner: C,
}

impl<const N: usize, D: Dynamics<N, N, Scalar = f64>, C: Controller<N>> Controller<N>
    for GravityCompensation<D, C>
{
    fn torque(&self, t: f64, q: &[f64; N], qd: &[f64; N]) -> [f64; N] {
        let u = self.inner.torque(t, q, qd);
        let g = vector(self.model.gravity_torques(q));
        std::array::from_fn(|i| u[i] + g[i])
    }

    fn spring_energy(&self, q: &[f64; N]) -> Option<f64> {
        self.inner.spring_energy(q)
    }
}

/// Per-joint motor saturation |uᵢ| ≤ u_max,i; built by [`Controller::saturated`].
#[derive(Clone, Copy, Debug)]
pub struct Saturation<const N: usize, C> {
    /// The saturated input.
    pub inner: C,
    /// The per-joint limits u_max,i ≥ 0 (N·m).
    pub u_max: [f64; N],
}

impl<const N: usize, C: Controller<N>> Controller<N> for Saturation<N, C> {
    fn torque(&self, t: f64, q: &[f64; N], qd: &[f64; N]) -> [f64; N] {
        let u = self.inner.torque(t, q, qd);
        std::array::from_fn(|i| u[i].clamp(-self.u_max[i], self.u_max[i]))
    }

    fn spring_energy(&self, q: &[f64; N]) -> Option<f64> {
        self.inner.spring_energy(q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_models::PlanarElbow;

    /// The PD law has the sign of (6.62): it pushes towards the set-point and against motion.
    #[test]
    fn pd_pushes_towards_set_point_and_against_motion() {
        let pd = Pd::new([22.0, 45.0], [15.0, 8.0], [1.0, -1.0]);
        assert_eq!(pd.torque(0.0, &[0.0, 0.0], &[0.0, 0.0]), [22.0, -45.0]);
        assert_eq!(pd.torque(0.0, &[1.0, -1.0], &[2.0, -1.0]), [-30.0, 8.0]);
        let v = pd.spring_energy(&[0.0, 0.0]).unwrap();
        assert!((v - 0.5 * (22.0 + 45.0)).abs() < 1e-15);
        assert_eq!(pd.spring_energy(&[1.0, -1.0]), Some(0.0));
    }

    /// Saturation clips each joint to its own limit and is applied after gravity compensation;
    /// sums, constants, damping and closures compose.
    #[test]
    fn composition_and_saturation_order() {
        let arm = PlanarElbow::thesis();
        let q = [0.0, 0.0];
        let g = arm.gravity_torques(&q);
        let comp = ZeroInput.with_gravity_compensation(arm);
        assert_eq!(comp.torque(0.0, &q, &[0.0; 2]), g);
        let sat = ZeroInput
            .with_gravity_compensation(arm)
            .saturated([39.4, 1.0]);
        let u = sat.torque(0.0, &q, &[0.0; 2]);
        assert_eq!(u, [g[0].min(39.4), 1.0]);
        assert!(g[0] > 39.4 && g[1] > 1.0, "{g:?}");

        let combo = ConstantTorque([1.0, 2.0])
            .plus(Damping::new([1.5, 1.5]))
            .plus(|t: f64, _: &[f64; 2], _: &[f64; 2]| [t, -t]);
        assert_eq!(combo.torque(0.5, &q, &[2.0, -2.0]), [-1.5, 4.5]);
        assert_eq!(combo.spring_energy(&q), None);
        let pd = Pd::new([2.0, 0.0], [0.0; 2], [1.0, 0.0]);
        let both = pd.plus(pd).saturated([0.1; 2]);
        assert_eq!(both.spring_energy(&q), Some(2.0));
        assert_eq!(both.torque(0.0, &q, &[0.0; 2]), [0.1, 0.0]);
    }
}
