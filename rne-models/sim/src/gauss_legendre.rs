//! Symplectic Gauss–Legendre Runge–Kutta (implicit midpoint, or 2 stages of order 4) in the
//! canonical coordinates (q, p), p = M(q) q̇, for energy-respecting long runs.

use super::controller::Controller;
use super::fixed_point::converged;
use rne_runtime::Dynamics;

use super::error::SimError;
use super::integrator::{substeps, validate_times, Integrator, Stats};
use super::linalg::{cholesky, cholesky_solve, mat_t_vec, mat_vec};
use super::model::{matrix, vector};
use super::state::State;

/// √3 / 6, the offset of the 2-stage Gauss nodes from ½.
const SQRT3_6: f64 = 0.288_675_134_594_812_87;

/// Which Gauss–Legendre method to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stages {
    /// 1 stage: the implicit midpoint rule, order 2.
    One,
    /// 2 stages: nodes ½ ∓ √3/6, order 4.
    Two,
}

/// Gauss–Legendre collocation (Hairer–Lubich–Wanner, *Geometric Numerical Integration*,
/// sections II.1.3 and VI.4; Hairer–Nørsett–Wanner I, section II.7) on the canonical form of
/// M(q) q̈ + C(q, q̇) q̇ + g(q) = u:
///
/// ```text
/// q̇ = M(q)⁻¹ p,          ṗ = d/dt (M q̇) = C(q, q̇)ᵀ q̇ − g(q) + u(t, q, q̇),
/// ```
///
/// obtained from (6.2) with Ṁ = C + Cᵀ (Christoffel C). For u = 0 this is Hamilton's system of
/// H(q, p) = ½ pᵀ M(q)⁻¹ p + V(q), since (Cᵀ q̇)ₖ = ½ q̇ᵀ (∂M/∂qₖ) q̇ = −∂/∂qₖ (½ pᵀ M⁻¹ p).
///
/// - **Order**: 2s for s stages: 2 (implicit midpoint) or 4.
/// - **Why symplectic**: Gauss methods satisfy bᵢ aᵢⱼ + bⱼ aⱼᵢ = bᵢ bⱼ, so they conserve every
///   quadratic invariant and their step map preserves the canonical 2-form dq ∧ dp of any
///   Hamiltonian system (Hairer–Lubich–Wanner, theorems IV.2.1 and VI.4.3). This holds only in
///   canonical coordinates: in (q, q̇) the equations are not in canonical Hamiltonian form (the
///   conserved 2-form is d(M q̇) ∧ dq, which depends on q), and a Runge–Kutta method applied
///   there is not symplectic. Hence the integration in (q, p), with q̇ = M⁻¹ p from a fixed-size
///   Cholesky factorisation at every evaluation.
/// - **Energy**: with a constant step, the numerical solution is (up to exponentially small
///   terms) the exact flow of a modified Hamiltonian H + O(h²ˢ), so the energy error stays
///   bounded, O(h²ˢ), over exponentially long times instead of drifting (backward error
///   analysis, Hairer–Lubich–Wanner, theorem IX.8.1). The method is also symmetric (time
///   reversible). With a non-zero input (damping, PD control) it is an ordinary order-2s
///   method.
/// - **Stage equations**: Zᵢ = h Σⱼ aᵢⱼ F(t + cⱼ h, y₀ + Zⱼ), solved by fixed-point iteration
///   from the extrapolated collocation polynomial of the previous step
///   (Hairer–Lubich–Wanner VIII.6), until the scaled change maxᵢ |ΔZᵢ| / (1 + |y₀ᵢ|) vanishes,
///   stops decreasing below `tolerance` (the round-off floor), or the observed contraction
///   predicts a remaining error below the rounding unit; the update
///   y₁ = y₀ + h Σ bᵢ F(Yᵢ) is added with compensated summation (Hairer–Lubich–Wanner VIII.5).
///   Fixed-point iteration contracts for h · L · ‖A‖ < 1 (L a Lipschitz constant of F); if the
///   iteration cap is reached first the integration stops with [`SimError::NotConverged`].
///
/// Steps: like [`Rk4`](super::Rk4), the smallest number of equal steps not longer than `h`
/// between consecutive output times; use a uniform output grid whose spacing is a multiple of
/// `h` so that the step is constant, which the energy bound assumes.
#[derive(Clone, Copy, Debug)]
pub struct GaussLegendre {
    /// The maximum step length h > 0 (s).
    pub h: f64,
    /// One stage (implicit midpoint) or two.
    pub stages: Stages,
    /// Largest scaled change of the stage values accepted as the round-off floor.
    pub tolerance: f64,
    /// Iteration cap per step.
    pub max_iterations: u32,
}

impl GaussLegendre {
    /// The 2-stage, order-4 method with step `h`, tolerance 1e-12 and at most 50 iterations.
    pub fn new(h: f64) -> Self {
        Self {
            h,
            stages: Stages::Two,
            tolerance: 1e-12,
            max_iterations: 50,
        }
    }

    /// The implicit midpoint rule (order 2) with step `h`.
    pub fn midpoint(h: f64) -> Self {
        Self {
            stages: Stages::One,
            ..Self::new(h)
        }
    }
}

/// A point (q, p) of phase space, or a tangent vector (q̇, ṗ).
#[derive(Clone, Copy, Debug)]
struct Canonical<const N: usize> {
    q: [f64; N],
    p: [f64; N],
}

impl<const N: usize> Canonical<N> {
    const ZERO: Self = Self {
        q: [0.0; N],
        p: [0.0; N],
    };

    fn plus(&self, other: &Self) -> Self {
        Self {
            q: std::array::from_fn(|i| self.q[i] + other.q[i]),
            p: std::array::from_fn(|i| self.p[i] + other.p[i]),
        }
    }

    /// h Σⱼ wⱼ fⱼ.
    fn combination<const S: usize>(h: f64, w: &[f64; S], f: &[Self; S]) -> Self {
        let mut out = Self::ZERO;
        for (wj, fj) in w.iter().zip(f) {
            for i in 0..N {
                out.q[i] += h * wj * fj.q[i];
                out.p[i] += h * wj * fj.p[i];
            }
        }
        out
    }

    fn is_finite(&self) -> bool {
        self.q.iter().chain(&self.p).all(|v| v.is_finite())
    }
}

/// A Butcher tableau with `S` stages.
struct Tableau<const S: usize> {
    a: [[f64; S]; S],
    b: [f64; S],
    c: [f64; S],
}

const MIDPOINT: Tableau<1> = Tableau {
    a: [[0.5]],
    b: [1.0],
    c: [0.5],
};

const GAUSS4: Tableau<2> = Tableau {
    a: [[0.25, 0.25 - SQRT3_6], [0.25 + SQRT3_6, 0.25]],
    b: [0.5, 0.5],
    c: [0.5 - SQRT3_6, 0.5 + SQRT3_6],
};

impl<const S: usize> Tableau<S> {
    /// The Lagrange basis polynomial j (1-based among the nodes 0, c₁, …, c_S) at θ.
    fn lagrange(&self, j: usize, theta: f64) -> f64 {
        let node = |m: usize| if m == 0 { 0.0 } else { self.c[m - 1] };
        (0..=S)
            .filter(|&m| m != j)
            .map(|m| (theta - node(m)) / (node(j) - node(m)))
            .product()
    }
}

/// The velocities q̇ = M(q)⁻¹ p.
fn velocities<const N: usize, D: Dynamics<N, N, Scalar = f64> + ?Sized>(
    model: &D,
    t: f64,
    y: &Canonical<N>,
) -> Result<[f64; N], SimError> {
    let l = cholesky(&matrix(model.mass_matrix(&y.q)))
        .ok_or(SimError::MassMatrixNotPositiveDefinite { t })?;
    Ok(cholesky_solve(&l, &y.p))
}

/// The canonical vector field (q̇, ṗ) = (M⁻¹ p, Cᵀ q̇ − g + u).
fn vector_field<const N: usize, D, C>(
    model: &D,
    controller: &C,
    t: f64,
    y: &Canonical<N>,
) -> Result<Canonical<N>, SimError>
where
    D: Dynamics<N, N, Scalar = f64> + ?Sized,
    C: Controller<N> + ?Sized,
{
    let qd = velocities(model, t, y)?;
    let ctq = mat_t_vec(&matrix(model.coriolis_matrix(&y.q, &qd)), &qd);
    let g = vector(model.gravity_torques(&y.q));
    let u = controller.torque(t, &y.q, &qd);
    Ok(Canonical {
        q: qd,
        p: std::array::from_fn(|i| ctq[i] - g[i] + u[i]),
    })
}

impl GaussLegendre {
    /// Solves the stage equations of one step of length `h` from `(t, y)`, starting from `z`,
    /// which holds the converged stage increments afterwards. Returns h Σ bᵢ F(Yᵢ).
    #[allow(clippy::too_many_arguments)]
    fn step<const N: usize, const S: usize, D, C>(
        &self,
        tab: &Tableau<S>,
        model: &D,
        controller: &C,
        t: f64,
        y: &Canonical<N>,
        z: &mut [Canonical<N>; S],
        h: f64,
        stats: &mut Stats,
    ) -> Result<Canonical<N>, SimError>
    where
        D: Dynamics<N, N, Scalar = f64> + ?Sized,
        C: Controller<N> + ?Sized,
    {
        let scale = Canonical::<N> {
            q: std::array::from_fn(|i| 1.0 / (1.0 + y.q[i].abs())),
            p: std::array::from_fn(|i| 1.0 / (1.0 + y.p[i].abs())),
        };
        let mut f = [Canonical::ZERO; S];
        let mut previous = f64::INFINITY;
        let mut change = f64::INFINITY;
        for k in 1..=self.max_iterations {
            for ((fi, zi), ci) in f.iter_mut().zip(z.iter()).zip(&tab.c) {
                *fi = vector_field(model, controller, t + ci * h, &y.plus(zi))?;
            }
            stats.evaluations += S as u64;
            stats.iterations += 1;
            change = 0.0_f64;
            for (zi, ai) in z.iter_mut().zip(&tab.a) {
                let new = Canonical::combination(h, ai, &f);
                for c in 0..N {
                    change = change
                        .max((new.q[c] - zi.q[c]).abs() * scale.q[c])
                        .max((new.p[c] - zi.p[c]).abs() * scale.p[c]);
                }
                *zi = new;
            }
            if !change.is_finite() {
                // The iteration diverged (h too large for fixed-point iteration).
                return Err(SimError::NotConverged {
                    t,
                    iterations: k,
                    residual: change,
                });
            }
            if converged(k, change, previous, self.tolerance) {
                return Ok(Canonical::combination(h, &tab.b, &f));
            }
            previous = change;
        }
        Err(SimError::NotConverged {
            t,
            iterations: self.max_iterations,
            residual: change,
        })
    }

    /// The integration loop for an `S`-stage tableau.
    fn run<const N: usize, const S: usize, D, C, F>(
        &self,
        tab: &Tableau<S>,
        model: &D,
        controller: &C,
        x0: &State<N>,
        times: &[f64],
        mut sink: F,
    ) -> Result<Stats, SimError>
    where
        D: Dynamics<N, N, Scalar = f64> + ?Sized,
        C: Controller<N> + ?Sized,
        F: FnMut(f64, &State<N>),
    {
        let mut stats = Stats::default();
        let mut y = Canonical {
            q: x0.q,
            p: mat_vec(&matrix(model.mass_matrix(&x0.q)), &x0.qd),
        };
        // Low-order bits lost when adding increments to y (compensated summation).
        let mut carry = Canonical::<N>::ZERO;
        let mut z = [Canonical::<N>::ZERO; S];
        let mut h_prev: Option<f64> = None;
        sink(times[0], x0);
        for w in times.windows(2) {
            let (t_a, t_b) = (w[0], w[1]);
            let n = substeps(t_a, t_b, self.h);
            let dt = (t_b - t_a) / n as f64;
            for j in 0..n {
                let t = t_a + j as f64 * dt;
                // Starting guess: the previous step's collocation polynomial u (u(0) = 0,
                // u(cᵢ) = Zᵢ) extrapolated, Zᵢ ≈ u(1 + r cᵢ) − u(1) with r = h / h_prev.
                if let Some(hp) = h_prev {
                    let r = dt / hp;
                    let old = z;
                    for (i, zi) in z.iter_mut().enumerate() {
                        let w: [f64; S] = std::array::from_fn(|m| {
                            tab.lagrange(m + 1, 1.0 + r * tab.c[i]) - tab.lagrange(m + 1, 1.0)
                        });
                        *zi = Canonical::combination(1.0, &w, &old);
                    }
                }
                let delta = self.step(tab, model, controller, t, &y, &mut z, dt, &mut stats)?;
                for i in 0..N {
                    kahan_add(&mut y.q[i], &mut carry.q[i], delta.q[i]);
                    kahan_add(&mut y.p[i], &mut carry.p[i], delta.p[i]);
                }
                stats.steps += 1;
                h_prev = Some(dt);
                if !y.is_finite() {
                    return Err(SimError::NonFinite { t: t + dt });
                }
            }
            let qd = velocities(model, t_b, &y)?;
            sink(t_b, &State { q: y.q, qd });
        }
        Ok(stats)
    }
}

/// `sum += delta` with the rounding error kept in `carry` and fed back next time
/// (compensated summation, Hairer–Lubich–Wanner VIII.5).
fn kahan_add(sum: &mut f64, carry: &mut f64, delta: f64) {
    let a = *sum;
    let d = delta + *carry;
    *sum = a + d;
    *carry = (a - *sum) + d;
}

impl<const N: usize> Integrator<N> for GaussLegendre {
    fn integrate<D, C, F>(
        &self,
        model: &D,
        controller: &C,
        x0: &State<N>,
        times: &[f64],
        sink: F,
    ) -> Result<Stats, SimError>
    where
        D: Dynamics<N, N, Scalar = f64> + ?Sized,
        C: Controller<N> + ?Sized,
        F: FnMut(f64, &State<N>),
    {
        validate_times(times)?;
        if !(self.h > 0.0 && self.h.is_finite()) {
            return Err(SimError::InvalidSetting(
                "Gauss-Legendre step h must be positive and finite",
            ));
        }
        if self.tolerance.is_nan() || self.tolerance <= 0.0 || self.max_iterations == 0 {
            return Err(SimError::InvalidSetting(
                "Gauss-Legendre needs a positive tolerance and iteration cap",
            ));
        }
        match self.stages {
            Stages::One => self.run(&MIDPOINT, model, controller, x0, times, sink),
            Stages::Two => self.run(&GAUSS4, model, controller, x0, times, sink),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::{Damping, ZeroInput};
    use crate::test_models::{observed_order, Pendulum};

    /// The tableaux are the Gauss methods: the symplecticity condition bᵢaᵢⱼ + bⱼaⱼᵢ = bᵢbⱼ
    /// holds, and the row sums are the nodes.
    #[test]
    fn tableaux_satisfy_the_symplecticity_condition() {
        fn check<const S: usize>(t: &Tableau<S>) {
            for i in 0..S {
                let row: f64 = t.a[i].iter().sum();
                assert!((row - t.c[i]).abs() < 1e-16);
                for j in 0..S {
                    let m = t.b[i] * t.a[i][j] + t.b[j] * t.a[j][i] - t.b[i] * t.b[j];
                    assert!(m.abs() < 1e-16, "({i}, {j}): {m}");
                }
            }
            assert!((SQRT3_6 - 3f64.sqrt() / 6.0).abs() < 1e-17);
        }
        check(&MIDPOINT);
        check(&GAUSS4);
    }

    /// Property: order 4 for two stages and 2 for the midpoint rule, on the closed-form
    /// half-period of the pendulum.
    #[test]
    fn gauss_legendre_converges_at_orders_four_and_two() {
        let p = Pendulum::new(1.0, 1.0, 9.81);
        let theta0 = 1.0;
        let t_half = 0.5 * p.period(theta0);
        for (method, expected) in [
            (GaussLegendre::new(1.0), 4.0),
            (GaussLegendre::midpoint(1.0), 2.0),
        ] {
            let errors: Vec<f64> = [20u32, 40, 80, 160]
                .iter()
                .map(|&n| {
                    let mut last = State::at_rest([0.0]);
                    let gl = GaussLegendre {
                        h: t_half / f64::from(n),
                        ..method
                    };
                    gl.integrate(
                        &p,
                        &ZeroInput,
                        &State::at_rest([theta0]),
                        &[0.0, t_half],
                        |_, x| last = *x,
                    )
                    .unwrap();
                    (last.q[0] + theta0).abs().max(last.qd[0].abs())
                })
                .collect();
            for o in observed_order(&errors) {
                assert!((o - expected).abs() < 0.25, "{method:?}: {errors:?}");
            }
        }
    }

    /// Property: the iteration cap is a clear error, not a silently wrong step. A stiff damping
    /// (h · Kd / m l² = 50) makes fixed-point iteration diverge.
    #[test]
    fn gauss_legendre_flags_non_convergence() {
        let p = Pendulum::new(1.0, 1.0, 9.81);
        let r = GaussLegendre::new(0.5).integrate(
            &p,
            &Damping::new([100.0]),
            &State::at_rest([1.0]),
            &[0.0, 1.0],
            |_, _| {},
        );
        assert!(matches!(r, Err(SimError::NotConverged { .. })), "{r:?}");
        let bad = GaussLegendre::new(-1.0).integrate(
            &p,
            &ZeroInput,
            &State::at_rest([1.0]),
            &[0.0, 1.0],
            |_, _| {},
        );
        assert!(matches!(bad, Err(SimError::InvalidSetting(_))));
    }
}
