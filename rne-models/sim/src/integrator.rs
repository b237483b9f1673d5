//! The common interface of the integrators, their statistics and the first-order form (6.2).

use super::controller::Controller;
use super::dopri5::Dopri5;
use super::error::SimError;
use super::gauss_legendre::GaussLegendre;
use super::model::vector;
use super::rk4::Rk4;
use super::state::State;
use rne_runtime::Dynamics;

/// Work done by one integration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps (adaptive integrators only).
    pub rejected: u64,
    /// Evaluations of the right-hand side: calls of `forward_dynamics` for the explicit
    /// methods; evaluations of the canonical vector field (one M, C, g and Cholesky solve each)
    /// for Gauss–Legendre; evaluations of the velocity equation (one M, C and Cholesky solve
    /// each) for [`LieVariational`](crate::LieVariational).
    pub evaluations: u64,
    /// Fixed-point iterations on the implicit stage equations (Gauss–Legendre) or velocity
    /// equation (LieVariational); zero for the explicit methods.
    pub iterations: u64,
}

/// A time integrator for M(q) q̈ + C(q, q̇) q̇ + g(q) = u(t, q, q̇).
///
/// `integrate` starts from `x0` at `times[0]`, advances to the last time and calls `sink` once
/// per entry of `times`, in order, with the state at exactly that time (`x0` itself first).
/// The step loop does not allocate. The model must have the kernels of
/// [`SIMULATED`](crate::SIMULATED) ([`simulate`](crate::simulate) checks it); a missing one
/// gives NaN, which stops the run with an error.
pub trait Integrator<const N: usize> {
    /// Integrates from `times[0]` to the last time, reporting the state at every output time.
    ///
    /// `times` must be non-empty, finite and strictly increasing ([`SimError::InvalidTimes`]).
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
        F: FnMut(f64, &State<N>);
}

/// One of the integrators, chosen at run time (e.g. from a scenario file).
#[derive(Clone, Copy, Debug)]
pub enum Method {
    /// Classical fixed-step Runge–Kutta of order 4.
    Rk4(Rk4),
    /// Adaptive Dormand–Prince 5(4) with dense output (the thesis's ode45).
    Dopri5(Dopri5),
    /// Symplectic Gauss–Legendre collocation in canonical coordinates.
    GaussLegendre(GaussLegendre),
}

impl<const N: usize> Integrator<N> for Method {
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
        match self {
            Self::Rk4(m) => m.integrate(model, controller, x0, times, sink),
            Self::Dopri5(m) => m.integrate(model, controller, x0, times, sink),
            Self::GaussLegendre(m) => m.integrate(model, controller, x0, times, sink),
        }
    }
}

/// Checks that output times are non-empty, finite and strictly increasing.
pub(crate) fn validate_times(times: &[f64]) -> Result<(), SimError> {
    let finite = times.iter().all(|t| t.is_finite());
    let increasing = times.windows(2).all(|w| w[0] < w[1]);
    if times.is_empty() || !finite || !increasing {
        return Err(SimError::InvalidTimes);
    }
    Ok(())
}

/// The first-order right-hand side (6.6)–(6.11): ẋ = (q̇, q̈) with q̈ from (6.2) at u(t, q, q̇).
#[inline]
pub(crate) fn derivative<const N: usize, D, C>(
    model: &D,
    controller: &C,
    t: f64,
    x: &State<N>,
) -> State<N>
where
    D: Dynamics<N, N, Scalar = f64> + ?Sized,
    C: Controller<N> + ?Sized,
{
    let u = controller.torque(t, &x.q, &x.qd);
    State {
        q: x.qd,
        qd: vector(model.forward_dynamics(&x.q, &x.qd, &u)),
    }
}

/// The number of equal steps of length at most `h` (up to rounding) that cover `[t_a, t_b]`.
///
/// Fixed-step integrators take these equal steps between consecutive output times, so they
/// land on every output time exactly; on a uniform output grid the step is constant, which the
/// symplectic integrator needs for its long-time energy behaviour.
pub(crate) fn substeps(t_a: f64, t_b: f64, h: f64) -> u64 {
    let ratio = (t_b - t_a) / h;
    // Without the slack, an interval of exactly k·h that rounds to k(1 + ε) would get k + 1 steps.
    let n = (ratio * (1.0 - 1e-12)).ceil();
    // Truncation is intended: `n` is a small positive integer-valued float.
    (n as u64).max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Output times must be usable; intervals that are whole multiples of h are not split further.
    #[test]
    fn output_time_validation_and_substeps() {
        assert_eq!(validate_times(&[]), Err(SimError::InvalidTimes));
        assert_eq!(validate_times(&[0.0, 0.0]), Err(SimError::InvalidTimes));
        assert_eq!(
            validate_times(&[0.0, f64::NAN]),
            Err(SimError::InvalidTimes)
        );
        assert_eq!(validate_times(&[1.0, 0.5]), Err(SimError::InvalidTimes));
        assert_eq!(validate_times(&[0.0]), Ok(()));
        assert_eq!(substeps(0.0, 0.3, 0.1), 3);
        assert_eq!(substeps(0.7, 1.0, 0.1), 3);
        assert_eq!(substeps(0.0, 0.31, 0.1), 4);
        assert_eq!(substeps(0.0, 0.01, 0.1), 1);
    }
}
