//! Running a model under an input with an integrator and recording the result.

use super::controller::Controller;
use rne_runtime::Dynamics;

use super::error::SimError;
use super::integrator::{validate_times, Integrator};
use super::model::{check_kernels, scalar};
use super::record::Record;
use super::state::State;

/// Simulates M(q) q̈ + C(q, q̇) q̇ + g(q) = u(t, q, q̇) from `x0` at `times[0]` to the last output
/// time and records every output time: the state, the input, the model's kinetic, potential and
/// total energy, and the Lyapunov function V = ½ q̇ᵀ M q̇ + ½ q̃ᵀ Kp q̃ of (6.57) when the input
/// has a PD term.
///
/// For the thesis's gravity-compensated PD runs (6.33), pass a gravity-free model (a generated
/// module with zero gravity or [`WithoutGravity`](crate::WithoutGravity)); the recorded energies
/// are then those of that model. The record is allocated once, before integrating. A model
/// without one of the kernels of [`SIMULATED`](crate::SIMULATED) is refused
/// ([`SimError::MissingKernel`]).
pub fn simulate<const N: usize, D, C, I>(
    model: &D,
    controller: &C,
    integrator: &I,
    x0: &State<N>,
    times: &[f64],
) -> Result<Record<N>, SimError>
where
    D: Dynamics<N, N, Scalar = f64> + ?Sized,
    C: Controller<N> + ?Sized,
    I: Integrator<N>,
{
    validate_times(times)?;
    check_kernels(model)?;
    let has_springs = controller.spring_energy(&x0.q).is_some();
    let mut record = Record::with_capacity(times.len(), has_springs);
    let stats = integrator.integrate(model, controller, x0, times, |t, x| {
        let kinetic = scalar(model.kinetic_energy(&x.q, &x.qd));
        let potential = scalar(model.potential_energy(&x.q));
        record.t.push(t);
        record.q.push(x.q);
        record.qd.push(x.qd);
        record.u.push(controller.torque(t, &x.q, &x.qd));
        record.kinetic.push(kinetic);
        record.potential.push(potential);
        record.total.push(kinetic + potential);
        if let (Some(v), Some(springs)) = (&mut record.lyapunov, controller.spring_energy(&x.q)) {
            v.push(kinetic + springs);
        }
    })?;
    record.stats = stats;
    Ok(record)
}

/// Uniform output times t₀, t₀ + dt, …, ending exactly at `t_end` (the last interval is
/// shorter if `t_end − t₀` is not a whole number of `dt`). Each time is computed as t₀ + k dt,
/// without accumulated rounding.
///
/// # Panics
/// If `dt` is not positive or `t_end < t0`.
pub fn output_times(t0: f64, t_end: f64, dt: f64) -> Vec<f64> {
    assert!(
        dt > 0.0 && t_end >= t0,
        "output_times needs dt > 0 and t_end >= t0"
    );
    let span = t_end - t0;
    let ratio = span / dt;
    // Intervals within rounding of a whole number of dt are not followed by a tiny last one.
    let whole = ratio.round();
    let n = if (ratio - whole).abs() <= 1e-9 * ratio.max(1.0) {
        whole
    } else {
        ratio.ceil()
    };
    // Truncation is intended: `n` is a non-negative integer-valued float.
    let n = n as usize;
    let mut times: Vec<f64> = (0..n).map(|k| t0 + k as f64 * dt).collect();
    times.push(t_end);
    times
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::{Pd, ZeroInput};
    use crate::dopri5::Dopri5;
    use crate::test_models::Pendulum;

    /// Property: the small-angle pendulum swings with the closed-form period 2π √(l/g) (to the
    /// amplitude correction θ₀²/16) and its energy −m g l cos θ₀ is conserved; the record holds
    /// one consistent sample per output time.
    #[test]
    fn pendulum_period_and_energy() {
        let (m, l, g) = (2.0, 0.5, 9.81);
        let p = Pendulum::new(m, l, g);
        let theta0 = 0.01;
        let times = output_times(0.0, 10.0, 1e-3);
        let r = simulate(
            &p,
            &ZeroInput,
            &Dopri5::new(1e-12, 1e-14),
            &State::at_rest([theta0]),
            &times,
        )
        .unwrap();
        assert_eq!(r.len(), 10_001);
        assert_eq!(r.t, times);
        assert!(r.lyapunov.is_none());
        // Upward zero crossings of q, located by linear interpolation.
        let crossings: Vec<f64> = (1..r.len())
            .filter(|&k| r.q[k - 1][0] < 0.0 && r.q[k][0] >= 0.0)
            .map(|k| {
                let (a, b) = (r.q[k - 1][0], r.q[k][0]);
                r.t[k - 1] + (r.t[k] - r.t[k - 1]) * (-a) / (b - a)
            })
            .collect();
        let measured =
            (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
        let small_angle = 2.0 * std::f64::consts::PI * (l / g).sqrt();
        assert!(((measured - small_angle) / small_angle).abs() < 2.0 * theta0 * theta0 / 16.0);
        assert!((measured - p.period(theta0)).abs() < 1e-7, "{measured}");
        let e0 = -m * g * l * theta0.cos();
        assert!((r.total[0] - e0).abs() < 1e-15);
        for k in 0..r.len() {
            assert_eq!(r.total[k], r.kinetic[k] + r.potential[k]);
            assert!((r.total[k] - e0).abs() < 1e-11, "{}", r.total[k] - e0);
        }
    }

    /// The Lyapunov column is V = T + ½ q̃ᵀ Kp q̃ when the input has a PD term.
    #[test]
    fn lyapunov_recorded_for_pd_inputs() {
        let p = Pendulum::new(1.0, 1.0, 0.0);
        let pd = Pd::new([4.0], [1.0], [0.5]);
        let r = simulate(
            &p,
            &pd,
            &Dopri5::new(1e-9, 1e-9),
            &State::new([0.0], [1.0]),
            &[0.0, 1.0],
        )
        .unwrap();
        let v = r.lyapunov.as_ref().unwrap();
        assert_eq!(v[0], 0.5 * 1.0 + 0.5 * 4.0 * 0.25);
        assert_eq!(r.u[0], [-4.0 * (0.0 - 0.5) - 1.0]);
    }

    /// Uniform output grids end exactly at t_end, with or without a shorter last interval.
    #[test]
    fn output_times_are_uniform_and_end_at_t_end() {
        let t = output_times(0.0, 70.0, 0.01);
        assert_eq!(t.len(), 7001);
        assert_eq!(t[7000], 70.0);
        assert!((t[123] - 1.23).abs() < 1e-15);
        assert_eq!(output_times(1.0, 2.05, 0.5), vec![1.0, 1.5, 2.0, 2.05]);
        assert_eq!(output_times(0.0, 0.0, 0.1), vec![0.0]);
    }
}
