//! A variational integrator on the configuration manifold: symplectic and exactly
//! momentum-conserving for floating-base robots, second order.

use rne_runtime::{Dynamics, Kernel};

use crate::configuration::Layout;
use crate::error::SimError;
use crate::fixed_point::converged;
use crate::integrator::{substeps, validate_times, Stats};
use crate::linalg::{cholesky, cholesky_solve, mat_t_vec, mat_vec};
use crate::manifold_state::ManifoldState;
use crate::model::{matrix, vector};
use crate::se3::{co_adjoint, dexp_transpose, Six};

/// The kernels [`LieVariational`] calls.
const NEEDED: [Kernel; 3] = [
    Kernel::MassMatrix,
    Kernel::CoriolisMatrix,
    Kernel::GravityTorques,
];

/// How far the initial quaternion's norm may be from 1 before it is refused rather than
/// normalised (a quaternion typed with four or five digits is accepted).
const QUATERNION_NORM_SLACK: f64 = 1e-4;

/// A Lie-group variational integrator for M(q) v̇ + C(q, v) v + g(q) = u on the configuration
/// manifold of [`Dynamics<NQ, NV>`] (floating base: SE(3) × ℝⁿ; fixed base: ℝⁿ).
///
/// **Scheme.** Discrete mechanics (Marsden and West, "Discrete mechanics and variational
/// integrators", Acta Numerica 10, 2001, sections 1.2–1.3 and 3.2 for forcing) on a Lie group
/// (Bou-Rabee and Marsden, "Hamilton–Pontryagin integrators on Lie groups, part I", Found.
/// Comput. Math. 9, 2009; Kobilarov, Crane and Desbrun, "Lie group integrators for animation
/// and control of vehicles", ACM Trans. Graph. 28(2), 2009, whose discrete Euler–Poincaré
/// equations with the exponential map are used here). A step of length h moves the base by
/// g_{k+1} = g_k exp(h ξ_k) and the joints by θ_{k+1} = θ_k + h θ̇_k, with one velocity
/// v_k = (ξ_k, θ̇_k) per step, and the discrete Lagrangian is
///
/// ```text
/// L_d = h · ½ v_kᵀ M(θ_{k+½}) v_k − h/2 · (V(q_k) + V(q_{k+1})),   θ_{k+½} = θ_k + h/2 θ̇_k
/// ```
///
/// (midpoint kinetic energy, trapezoidal potential). Its discrete Euler–Lagrange equations,
/// with the input u as a discrete Lagrange–d'Alembert force h/2 · u(t_k + h/2, q_{k+½}, v_k) at
/// each end of the step, give, from the node momentum P_k ≈ M(q_k) v(t_k):
///
/// ```text
/// P_k⁺ = P_k + h/2 (u − g(q_k))                                         (half kick)
/// M(θ_{k+½}) v_k = [dexp_{hξ_k}ᵀ P_k⁺ (base);  P_k⁺ + h/2 D_k (joints)]   (solved for v_k)
/// P_{k+1} = [Ad_{exp(hξ_k)}ᵀ P_k⁺ (base);  P_k⁺ + h D_k (joints)] + h/2 (u − g(q_{k+1}))
/// ```
///
/// where D_k = ∂(½ vᵀ M v)/∂θ at (θ_{k+½}, v_k) is the joint part of C(q, v)ᵀ v (docs/design.md
/// §4.2: Ṁ = C + Cᵀ), dexp_Xᵀ = Σ (ad_Xᵀ)ⁱ/(i+1)! and Ad_gᵀ the coadjoint action (see
/// `se3.rs`). The base momentum is carried from one end of the step to the other by the
/// coadjoint action of the very displacement the base makes: with no external wrench on the
/// base and no gravity, the world-frame momentum Ad_{g_k⁻¹}ᵀ P_k of
/// [`world_momentum`](crate::world_momentum) is the same at every node to rounding (the
/// discrete Noether theorem, Marsden–West section 1.3), whatever the joints do and whatever
/// the step. A naive update q += h v on the quaternion would break this (and the unit norm).
///
/// **Properties.** Symplectic and symmetric for u = 0, so the energy error stays bounded over
/// long runs instead of drifting (Hairer, Lubich and Wanner, *Geometric Numerical Integration*,
/// sections VI.6 and IX.8); second order in h. The implicit velocity equation is solved by
/// fixed-point iteration from the previous step's velocity (it contracts for h small against
/// the motion's time scale; otherwise [`SimError::NotConverged`]), stopping when the scaled
/// change stops decreasing below `tolerance` or its contraction predicts a remaining error
/// below the rounding unit, as [`GaussLegendre`](crate::GaussLegendre) does.
///
/// **Output.** The state at a node is (q_k, M(q_k)⁻¹ P_k). Steps are the smallest number of
/// equal steps not longer than `h` between consecutive output times.
///
/// Relative to [`GaussLegendre`](crate::GaussLegendre) (order 4, symplectic in canonical
/// coordinates of ℝⁿ, fixed base only) this method is of order 2, works on a floating base and
/// conserves momentum exactly; on a fixed base it is the midpoint variational integrator.
#[derive(Clone, Copy, Debug)]
pub struct LieVariational {
    /// The maximum step length h > 0 (s).
    pub h: f64,
    /// Largest scaled change of the step velocity accepted as the round-off floor.
    pub tolerance: f64,
    /// Iteration cap per step.
    pub max_iterations: u32,
}

/// A node of the discrete trajectory: configuration, node momentum, gravity torques there.
struct Node<const NQ: usize, const NV: usize> {
    q: [f64; NQ],
    p: [f64; NV],
    g: [f64; NV],
}

/// What one converged step leaves for the end of the step.
struct StepEnd<const NV: usize> {
    /// P_k⁺.
    kicked: [f64; NV],
    /// D_k (joint rows used).
    d: [f64; NV],
    /// u at the step's midpoint.
    u: [f64; NV],
}

impl LieVariational {
    /// The integrator with step `h`, tolerance 1e-12 and at most 50 iterations per step.
    pub fn new(h: f64) -> Self {
        Self {
            h,
            tolerance: 1e-12,
            max_iterations: 50,
        }
    }

    /// Integrates from `x0` at `times[0]` to the last time, calling `sink` with the state at
    /// every output time (`x0` first). `input(t, q, v)` is the generalized force u: on a
    /// floating base its first six entries are an external wrench on the base (base frame, at
    /// the base origin), the rest joint torques; it must be allocation-free, as the step loop
    /// is.
    ///
    /// Errors: [`SimError::InvalidTimes`]; [`SimError::InvalidSetting`] for a non-positive step
    /// or tolerance, sizes that do not fit the model's base, or an initial quaternion whose
    /// norm is not 1 (within 1e-4; it is normalised); [`SimError::MissingKernel`] without
    /// the mass matrix, Coriolis matrix or gravity torques; [`SimError::NotConverged`],
    /// [`SimError::MassMatrixNotPositiveDefinite`] and [`SimError::NonFinite`] on the way.
    pub fn integrate<const NQ: usize, const NV: usize, D, U, F>(
        &self,
        model: &D,
        input: &U,
        x0: &ManifoldState<NQ, NV>,
        times: &[f64],
        mut sink: F,
    ) -> Result<Stats, SimError>
    where
        D: Dynamics<NQ, NV, Scalar = f64> + ?Sized,
        U: Fn(f64, &[f64; NQ], &[f64; NV]) -> [f64; NV] + ?Sized,
        F: FnMut(f64, &ManifoldState<NQ, NV>),
    {
        validate_times(times)?;
        if !(self.h > 0.0 && self.h.is_finite()) {
            return Err(SimError::InvalidSetting(
                "variational step h must be positive and finite",
            ));
        }
        if self.tolerance.is_nan() || self.tolerance <= 0.0 || self.max_iterations == 0 {
            return Err(SimError::InvalidSetting(
                "the variational integrator needs a positive tolerance and iteration cap",
            ));
        }
        let layout = Layout::of::<NQ, NV, D>()?;
        if let Some(kernel) = NEEDED.into_iter().find(|&k| !model.has(k)) {
            return Err(SimError::MissingKernel { kernel });
        }
        let mut q = x0.q;
        if layout.floating {
            let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
            let near_unit = (norm - 1.0).abs() <= QUATERNION_NORM_SLACK;
            if !near_unit {
                return Err(SimError::InvalidSetting(
                    "the initial base quaternion q[3..7] must have unit norm",
                ));
            }
            q[3..7].iter_mut().for_each(|x| *x /= norm);
        }
        let mut stats = Stats::default();
        let mut node = Node {
            q,
            p: mat_vec(&matrix(model.mass_matrix(&q)), &x0.v),
            g: vector(model.gravity_torques(&q)),
        };
        let mut v = x0.v;
        // The previous step's velocity and length, for the starting guess of the next one.
        let mut previous: Option<([f64; NV], f64)> = None;
        sink(times[0], x0);
        for w in times.windows(2) {
            let (t_a, t_b) = (w[0], w[1]);
            let n = substeps(t_a, t_b, self.h);
            let h = (t_b - t_a) / n as f64;
            for j in 0..n {
                let t = t_a + j as f64 * h;
                let current = v;
                // Linear extrapolation of the step velocities, v_k ≈ v_{k−1} + r (v_{k−1} − v_{k−2})
                // with r the ratio of the step midpoints' spacings.
                if let Some((before, h_before)) = previous {
                    let r = (h + h_before) / (2.0 * h_before);
                    v = std::array::from_fn(|i| current[i] + r * (current[i] - before[i]));
                }
                let end = self.solve(layout, model, input, t, &node, &mut v, h, &mut stats)?;
                previous = Some((current, h));
                node = Self::advance(layout, model, &node, &v, &end, h);
                stats.steps += 1;
                if !(node.q.iter().chain(&node.p).all(|x| x.is_finite())) {
                    return Err(SimError::NonFinite { t: t + h });
                }
            }
            let l = cholesky(&matrix(model.mass_matrix(&node.q)))
                .ok_or(SimError::MassMatrixNotPositiveDefinite { t: t_b })?;
            let state = ManifoldState::new(node.q, cholesky_solve(&l, &node.p));
            if !state.is_finite() {
                return Err(SimError::NonFinite { t: t_b });
            }
            sink(t_b, &state);
        }
        Ok(stats)
    }

    /// Solves the step's velocity equation from `node` by fixed-point iteration, starting from
    /// and leaving the velocity in `v`.
    #[allow(clippy::too_many_arguments)]
    fn solve<const NQ: usize, const NV: usize, D, U>(
        &self,
        layout: Layout,
        model: &D,
        input: &U,
        t: f64,
        node: &Node<NQ, NV>,
        v: &mut [f64; NV],
        h: f64,
        stats: &mut Stats,
    ) -> Result<StepEnd<NV>, SimError>
    where
        D: Dynamics<NQ, NV, Scalar = f64> + ?Sized,
        U: Fn(f64, &[f64; NQ], &[f64; NV]) -> [f64; NV] + ?Sized,
    {
        let nb = layout.base_velocities();
        let scale: [f64; NV] = std::array::from_fn(|i| 1.0 / (1.0 + v[i].abs()));
        let mut previous = f64::INFINITY;
        let mut change = f64::INFINITY;
        for k in 1..=self.max_iterations {
            let (q_mid, _) = layout.displace(&node.q, &v.map(|x| 0.5 * h * x));
            let u = input(t + 0.5 * h, &q_mid, v);
            let kicked: [f64; NV] =
                std::array::from_fn(|i| node.p[i] + 0.5 * h * (u[i] - node.g[i]));
            let c = matrix(model.coriolis_matrix(&q_mid, v));
            let d = mat_t_vec(&c, v);
            let mut rhs = kicked;
            if layout.floating {
                let xi: Six = std::array::from_fn(|i| h * v[i]);
                let mu: Six = std::array::from_fn(|i| kicked[i]);
                rhs[..6].copy_from_slice(&dexp_transpose(&xi, &mu));
            }
            for i in nb..NV {
                rhs[i] += 0.5 * h * d[i];
            }
            let l = cholesky(&matrix(model.mass_matrix(&q_mid)))
                .ok_or(SimError::MassMatrixNotPositiveDefinite { t })?;
            let new = cholesky_solve(&l, &rhs);
            stats.evaluations += 1;
            stats.iterations += 1;
            change = (0..NV).fold(0.0_f64, |m, i| m.max((new[i] - v[i]).abs() * scale[i]));
            *v = new;
            if !change.is_finite() {
                return Err(SimError::NotConverged {
                    t,
                    iterations: k,
                    residual: change,
                });
            }
            if converged(k, change, previous, self.tolerance) {
                return Ok(StepEnd { kicked, d, u });
            }
            previous = change;
        }
        Err(SimError::NotConverged {
            t,
            iterations: self.max_iterations,
            residual: change,
        })
    }

    /// The node at the end of the step with velocity `v`: the configuration q_k ⊕ h v, the base
    /// momentum carried by the coadjoint action of the base's displacement, the joint momentum
    /// and the end half kick.
    fn advance<const NQ: usize, const NV: usize, D>(
        layout: Layout,
        model: &D,
        node: &Node<NQ, NV>,
        v: &[f64; NV],
        end: &StepEnd<NV>,
        h: f64,
    ) -> Node<NQ, NV>
    where
        D: Dynamics<NQ, NV, Scalar = f64> + ?Sized,
    {
        let (q, displacement) = layout.displace(&node.q, &v.map(|x| h * x));
        let g = vector(model.gravity_torques(&q));
        let mut p = [0.0; NV];
        if let Some(step) = displacement {
            let mu: Six = std::array::from_fn(|i| end.kicked[i]);
            p[..6].copy_from_slice(&co_adjoint(&step, &mu));
        }
        let nb = layout.base_velocities();
        for ((pi, kicked), d) in p[nb..].iter_mut().zip(&end.kicked[nb..]).zip(&end.d[nb..]) {
            *pi = kicked + h * d;
        }
        for ((pi, u), g) in p.iter_mut().zip(&end.u).zip(&g) {
            *pi += 0.5 * h * (u - g);
        }
        Node { q, p, g }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::momentum::world_momentum;
    use crate::output_times;
    use crate::test_models::{observed_order, FreeBody, Pendulum};

    /// A body with distinct principal inertias spun near its intermediate axis (the
    /// Dzhanibekov flip), moving through the origin's neighbourhood, without gravity.
    fn tumbling() -> (FreeBody, ManifoldState<7, 6>) {
        let body = FreeBody {
            m: 2.0,
            inertia: [0.1, 0.2, 0.3],
            gravity: [0.0; 3],
        };
        let s = (0.5f64).sqrt();
        let x0 = ManifoldState::new(
            [0.5, -0.3, 0.2, 0.0, s, 0.0, s],
            [0.3, -0.2, 0.1, 0.01, 3.0, 0.02],
        );
        (body, x0)
    }

    fn no_input(_: f64, _: &[f64; 7], _: &[f64; 6]) -> [f64; 6] {
        [0.0; 6]
    }

    /// Property (discrete Noether): the world-frame momentum of a free body is the same at
    /// every output to rounding while the body tumbles, whatever the step; the energy error is
    /// bounded (symplectic) and the quaternion stays unit.
    #[test]
    fn a_tumbling_body_keeps_its_world_momentum_and_a_bounded_energy_error() {
        let (body, x0) = tumbling();
        let h0 = world_momentum(&body, &x0.q, &x0.v).unwrap();
        let e0 = body.kinetic_energy(&x0.q, &x0.v).unwrap();
        let scale = h0
            .linear
            .iter()
            .chain(&h0.angular)
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let (mut drift, mut energy_error, mut norm_error) = (0.0f64, 0.0f64, 0.0f64);
        let mut flipped = false;
        let times = output_times(0.0, 30.0, 0.1);
        LieVariational::new(2e-3)
            .integrate(&body, &no_input, &x0, &times, |_, x| {
                let h = world_momentum(&body, &x.q, &x.v).unwrap();
                drift = drift.max(h.max_difference(&h0) / scale);
                let e = body.kinetic_energy(&x.q, &x.v).unwrap();
                energy_error = energy_error.max((e - e0).abs() / e0);
                let norm: f64 = x.q[3..7].iter().map(|c| c * c).sum();
                norm_error = norm_error.max((norm - 1.0).abs());
                flipped |= x.v[4] < -2.0;
            })
            .unwrap();
        assert!(
            flipped,
            "the body never turned over: the test would not see rotation"
        );
        assert!(drift < 1e-13, "momentum drift {drift:e}");
        assert!(energy_error < 1e-4, "energy error {energy_error:e}");
        assert!(norm_error < 1e-14, "quaternion norm error {norm_error:e}");
    }

    /// Property: second order, on the pendulum's closed-form quarter period, where it passes
    /// q = 0 at full speed (at the half period q̇ = 0 hides the O(h²) phase error; fixed base) and
    /// by self-convergence of the tumbling body's configuration and velocity (floating base,
    /// where a wrong dexp would leave first order).
    #[test]
    fn the_variational_integrator_is_of_order_two_on_both_bases() {
        let p = Pendulum::new(1.0, 1.0, 9.81);
        let t_quarter = 0.25 * p.period(1.0);
        let zero = |_: f64, _: &[f64; 1], _: &[f64; 1]| [0.0];
        let errors: Vec<f64> = [20u32, 40, 80, 160]
            .iter()
            .map(|&n| {
                let mut last = 0.0;
                LieVariational::new(t_quarter / f64::from(n))
                    .integrate(
                        &p,
                        &zero,
                        &ManifoldState::at_rest([1.0]),
                        &[0.0, t_quarter],
                        |_, x| last = x.q[0],
                    )
                    .unwrap();
                last.abs()
            })
            .collect();
        for order in observed_order(&errors) {
            assert!((order - 2.0).abs() < 0.1, "pendulum: {errors:?}");
        }
        let (body, x0) = tumbling();
        let run = |h: f64| {
            let mut last = x0;
            LieVariational::new(h)
                .integrate(&body, &no_input, &x0, &[0.0, 1.0], |_, x| last = *x)
                .unwrap();
            last
        };
        let exact = run(1e-2 / 64.0);
        let errors: Vec<f64> = [1e-2, 5e-3, 2.5e-3]
            .iter()
            .map(|&h| {
                let x = run(h);
                x.q.iter()
                    .chain(&x.v)
                    .zip(exact.q.iter().chain(&exact.v))
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            })
            .collect();
        for order in observed_order(&errors) {
            assert!((order - 2.0).abs() < 0.15, "free body: {errors:?}");
        }
    }

    /// Bad settings and models are refused with the reason, not a panic.
    #[test]
    fn invalid_settings_are_refused() {
        let (body, x0) = tumbling();
        let run = |method: LieVariational, x: &ManifoldState<7, 6>| {
            method.integrate(&body, &no_input, x, &[0.0, 1.0], |_, _| {})
        };
        assert!(matches!(
            run(LieVariational::new(0.0), &x0),
            Err(SimError::InvalidSetting(_))
        ));
        let mut bad = x0;
        bad.q[6] = 3.0;
        assert!(matches!(
            run(LieVariational::new(1e-2), &bad),
            Err(SimError::InvalidSetting(_))
        ));
        struct Massless;
        impl Dynamics<7, 6> for Massless {
            type Scalar = f64;
            const NAME: &'static str = "massless";
            const JOINTS: &'static [&'static str] = &[];
            const FLOATING_BASE: bool = true;
            const KERNELS: &'static [Kernel] = &[Kernel::MassMatrix];
        }
        assert_eq!(
            LieVariational::new(1e-2).integrate(&Massless, &no_input, &x0, &[0.0, 1.0], |_, _| {}),
            Err(SimError::MissingKernel {
                kernel: Kernel::CoriolisMatrix
            })
        );
    }
}
