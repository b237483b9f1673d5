//! Summary figures of a run for reports: settling time, overshoot, steady-state error, energy
//! drift and peak torque.
//!
//! All figures are computed from the recorded samples, so their time resolution is the output
//! spacing.

use super::record::Record;

/// The band of the settling time, as a fraction of the step size.
pub const SETTLING_BAND: f64 = 0.02;

/// The report figures of one set-point run (section 6.2.5: "marginal overshooting and no
/// steady-state error ... steady states are reached in 3-4 seconds").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary<const N: usize> {
    /// Per joint, see [`Record::settling_time`].
    pub settling_time: [Option<f64>; N],
    /// Per joint, see [`Record::overshoot`].
    pub overshoot: [f64; N],
    /// Per joint, see [`Record::steady_state_error`].
    pub steady_state_error: [f64; N],
    /// See [`Record::energy_drift`].
    pub energy_drift: f64,
    /// Per joint, see [`Record::max_abs_torque`].
    pub max_abs_torque: [f64; N],
}

impl<const N: usize> Record<N> {
    /// The 2 % settling time of each joint towards `q_ref`.
    ///
    /// Definition: with the step size Δᵢ = |q_ref,i − qᵢ(t₀)| and the band bᵢ =
    /// [`SETTLING_BAND`] · Δᵢ, the settling time is the earliest recorded time tₛ such that
    /// |qᵢ(t) − q_ref,i| ≤ bᵢ at every recorded t ≥ tₛ, measured from t₀ (so tₛ − t₀ is
    /// reported). `None` if the last sample is outside the band (not settled within the run).
    pub fn settling_time(&self, q_ref: &[f64; N]) -> [Option<f64>; N] {
        std::array::from_fn(|i| {
            let t0 = *self.t.first()?;
            let band = SETTLING_BAND * (q_ref[i] - self.q[0][i]).abs();
            let inside = |k: usize| (self.q[k][i] - q_ref[i]).abs() <= band;
            let mut first_inside = None;
            for k in (0..self.len()).rev() {
                if !inside(k) {
                    break;
                }
                first_inside = Some(k);
            }
            first_inside.map(|k| self.t[k] - t0)
        })
    }

    /// The overshoot of each joint past `q_ref`, as a fraction of the step size
    /// |q_ref,i − qᵢ(t₀)| (0.05 is 5 %): the largest excursion beyond the set-point in the
    /// direction of the step, or 0 if the joint never crosses it (or the step is zero).
    pub fn overshoot(&self, q_ref: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|i| {
            let Some(first) = self.q.first() else {
                return 0.0;
            };
            let step = q_ref[i] - first[i];
            if step == 0.0 {
                return 0.0;
            }
            let beyond = self
                .q
                .iter()
                .map(|q| (q[i] - q_ref[i]) * step.signum())
                .fold(0.0, f64::max);
            beyond / step.abs()
        })
    }

    /// The steady-state error |qᵢ(t_end) − q_ref,i| of each joint at the last sample.
    pub fn steady_state_error(&self, q_ref: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|i| self.q.last().map_or(f64::NAN, |q| (q[i] - q_ref[i]).abs()))
    }

    /// The energy drift maxₜ |E(t) − E(t₀)| of the total energy over the run (J): zero for an
    /// exact integration of a conservative run (figure 6.8); the thesis saw about 2 J for the
    /// IRB 140 pendulum (figure 6.17).
    pub fn energy_drift(&self) -> f64 {
        let Some(&e0) = self.total.first() else {
            return 0.0;
        };
        self.total
            .iter()
            .map(|e| (e - e0).abs())
            .fold(0.0, f64::max)
    }

    /// The largest |uᵢ| of each joint over the run (N·m): never above the saturation limits.
    pub fn max_abs_torque(&self) -> [f64; N] {
        std::array::from_fn(|i| self.u.iter().map(|u| u[i].abs()).fold(0.0, f64::max))
    }

    /// All report figures of a set-point run towards `q_ref`.
    pub fn summary(&self, q_ref: &[f64; N]) -> Summary<N> {
        Summary {
            settling_time: self.settling_time(q_ref),
            overshoot: self.overshoot(q_ref),
            steady_state_error: self.steady_state_error(q_ref),
            energy_drift: self.energy_drift(),
            max_abs_torque: self.max_abs_torque(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hand-made response: q₁ steps 0 → 1 with a 10 % overshoot at t = 1 and enters the 2 %
    /// band for good at t = 3; q₂ never moves towards its set-point.
    fn response() -> Record<2> {
        let mut r = Record::with_capacity(6, false);
        let q1 = [0.0, 1.1, 0.97, 1.01, 0.995, 1.0];
        for (k, &q) in q1.iter().enumerate() {
            r.t.push(k as f64);
            r.q.push([q, 0.0]);
            r.qd.push([0.0; 2]);
            r.u.push([-2.0 * q, 0.5]);
            r.kinetic.push(0.0);
            r.potential.push(0.0);
            r.total.push([1.0, 1.5, 0.25, 1.0, 1.0, 1.0][k]);
        }
        r
    }

    /// Settling time, overshoot, steady-state error, energy drift and peak torque follow
    /// their documented definitions.
    #[test]
    fn summary_figures_follow_their_definitions() {
        let s = response().summary(&[1.0, 1.0]);
        assert_eq!(s.settling_time, [Some(3.0), None]);
        assert!((s.overshoot[0] - 0.1).abs() < 1e-12);
        assert_eq!(s.overshoot[1], 0.0);
        assert_eq!(s.steady_state_error, [0.0, 1.0]);
        assert_eq!(s.energy_drift, 0.75);
        assert_eq!(s.max_abs_torque, [2.2, 0.5]);
        // A step downwards overshoots below the set-point.
        let mut down = response();
        down.q.iter_mut().for_each(|q| q[0] = -q[0]);
        assert!((down.overshoot(&[-1.0, 0.0])[0] - 0.1).abs() < 1e-12);
    }
}
