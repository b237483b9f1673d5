//! Excitation trajectories: a finite Fourier series per joint (Swevers, Ganseman, Tükel,
//! De Schutter and Van Brussel, "Optimal robot excitation and identification", IEEE Trans.
//! Robotics and Automation 13(5), 1997, eq. (7)–(8)),
//!
//! ```text
//! q_i(t) = q_i0 + Σ_{l=1}^{N} a_il / (ω_f l) sin(ω_f l t) − b_il / (ω_f l) cos(ω_f l t)
//! q̇_i(t) = Σ a_il cos(ω_f l t) + b_il sin(ω_f l t)
//! q̈_i(t) = Σ −a_il ω_f l sin(ω_f l t) + b_il ω_f l cos(ω_f l t),      ω_f = 2π / period,
//! ```
//!
//! periodic, so that measurements can be averaged over periods, and with its bandwidth fixed by
//! N. With c_il = √(a_il² + b_il²), |q_i − q_i0| ≤ Σ c_il / (ω_f l), |q̇_i| ≤ Σ c_il and
//! |q̈_i| ≤ Σ c_il ω_f l hold for every t, so scaling a joint's coefficients to meet these
//! bounds keeps the whole trajectory within the limits.
//!
//! The coefficients are chosen, as Swevers et al. do, to minimise the condition number of the
//! stacked base regressor over one period; the search is a seeded (1+1) evolution strategy with
//! the one-fifth success rule (Rechenberg 1973; Beyer and Schwefel, "Evolution strategies",
//! Natural Computing 1, 2002) over the offsets (within half the position limit) and the
//! coefficients, each candidate scaled to its limits.

use crate::base::{BaseSet, State};
use crate::free_flyer::free_flyer_state;
use crate::least_squares::condition_number;
use crate::random::Random;
use crate::regressors::Regressors;
use crate::IdentifyError;

/// A finite Fourier series per joint.
#[derive(Clone, Debug, PartialEq)]
pub struct FourierTrajectory {
    /// The period 2π / ω_f, s.
    pub period: f64,
    /// q_i0 per joint.
    pub offsets: Vec<f64>,
    /// a_il: joint i, harmonic l + 1.
    pub a: Vec<Vec<f64>>,
    /// b_il: joint i, harmonic l + 1.
    pub b: Vec<Vec<f64>>,
}

impl FourierTrajectory {
    /// Number of joints.
    pub fn joints(&self) -> usize {
        self.offsets.len()
    }

    /// ω_f.
    fn omega(&self) -> f64 {
        std::f64::consts::TAU / self.period
    }

    /// q, q̇ and q̈ at time `t`.
    pub fn state(&self, t: f64) -> State {
        let w = self.omega();
        let n = self.joints();
        let (mut q, mut qd, mut qdd) = (self.offsets.clone(), vec![0.0; n], vec![0.0; n]);
        for i in 0..n {
            for (l, (a, b)) in self.a[i].iter().zip(&self.b[i]).enumerate() {
                let wl = w * (l + 1) as f64;
                let (s, c) = (wl * t).sin_cos();
                q[i] += (a * s - b * c) / wl;
                qd[i] += a * c + b * s;
                qdd[i] += wl * (b * c - a * s);
            }
        }
        (q, qd, qdd)
    }

    /// The bounds on |q_i − q_i0|, |q̇_i| and |q̈_i| over all t, per joint.
    pub fn bounds(&self) -> Vec<[f64; 3]> {
        let w = self.omega();
        (0..self.joints())
            .map(|i| {
                self.a[i].iter().zip(&self.b[i]).enumerate().fold(
                    [0.0; 3],
                    |[p, v, a], (l, (x, y))| {
                        let (c, wl) = (x.hypot(*y), w * (l + 1) as f64);
                        [p + c / wl, v + c, a + c * wl]
                    },
                )
            })
            .collect()
    }

    /// `count` states at t = k · duration / count, k = 0 … count − 1.
    pub fn states(&self, duration: f64, count: usize) -> Vec<(f64, State)> {
        (0..count)
            .map(|k| {
                let t = duration * k as f64 / count as f64;
                (t, self.state(t))
            })
            .collect()
    }
}

/// Per-joint limits: `|q_i| ≤ position[i]`, `|q̇_i| ≤ velocity[i]`, `|q̈_i| ≤ acceleration[i]`
/// (infinite for none).
#[derive(Clone, Debug, PartialEq)]
pub struct Limits {
    /// Position limits, rad or m, symmetric about zero.
    pub position: Vec<f64>,
    /// Velocity limits.
    pub velocity: Vec<f64>,
    /// Acceleration limits.
    pub acceleration: Vec<f64>,
}

/// What to optimise and how long.
#[derive(Clone, Debug, PartialEq)]
pub struct Design {
    /// The period, s.
    pub period: f64,
    /// Harmonics N per joint.
    pub harmonics: usize,
    /// The limits.
    pub limits: Limits,
    /// Candidates the search evaluates after the initial ones.
    pub iterations: usize,
    /// States per period at which the condition number is evaluated.
    pub criterion_states: usize,
    /// The seed.
    pub seed: u64,
}

/// An optimised trajectory and the condition number it reached.
#[derive(Clone, Debug, PartialEq)]
pub struct Excitation {
    /// The trajectory.
    pub trajectory: FourierTrajectory,
    /// The condition number of the stacked base regressor over `criterion_states` states of
    /// one period.
    pub condition: f64,
}

/// Random candidates drawn before the evolution strategy starts from the best of them.
const INITIAL_CANDIDATES: usize = 8;

/// Designs an excitation trajectory for `reference` and its base set: one Fourier series per
/// entry of v, the first six moving a floating base ([`free_flyer_state`]; their limits are
/// those of the base's position, m, and of its three angles, rad).
pub fn design<R: Regressors + ?Sized>(
    reference: &mut R,
    base: &BaseSet,
    design: &Design,
) -> Result<Excitation, IdentifyError> {
    design_with_progress(reference, base, design, |_| {})
}

/// The candidate trajectories [`design_with_progress`] evaluates for `design`.
pub fn candidates(design: &Design) -> usize {
    INITIAL_CANDIDATES + design.iterations
}

/// [`design()`], calling `progress` with the number of each candidate trajectory (1 up to
/// [`candidates`]) as its evaluation starts.
pub fn design_with_progress<R: Regressors + ?Sized>(
    reference: &mut R,
    base: &BaseSet,
    design: &Design,
    mut progress: impl FnMut(usize),
) -> Result<Excitation, IdentifyError> {
    let n = reference.nv();
    let floating = reference.nq() != n;
    let limits = &design.limits;
    for (name, values) in [
        ("position", &limits.position),
        ("velocity", &limits.velocity),
        ("acceleration", &limits.acceleration),
    ] {
        if values.len() != n || values.iter().any(|v| v.is_nan() || *v <= 0.0) {
            return Err(IdentifyError::Model(format!(
                "{name} limits: {n} positive values needed, got {values:?}"
            )));
        }
    }
    if design.harmonics == 0 || design.period <= 0.0 || !design.period.is_finite() {
        return Err(IdentifyError::Model(
            "an excitation needs at least one harmonic and a positive period".into(),
        ));
    }
    let size = n * (1 + 2 * design.harmonics);
    let mut random = Random::new(design.seed);
    let mut evaluated = 0;
    let mut cost = |x: &[f64]| -> Result<f64, IdentifyError> {
        evaluated += 1;
        progress(evaluated);
        let trajectory = decode(x, design);
        let states: Vec<State> = trajectory
            .states(trajectory.period, design.criterion_states)
            .into_iter()
            .map(|(_, s)| if floating { free_flyer_state(&s) } else { s })
            .collect();
        let w = base.stack(
            reference,
            states
                .iter()
                .map(|(q, qd, qdd)| (q.as_slice(), qd.as_slice(), qdd.as_slice())),
        )?;
        let c = condition_number(&w);
        Ok(if c.is_finite() { c.log10() } else { f64::MAX })
    };
    let mut best = random.vector(size, 1.0);
    let mut best_cost = cost(&best)?;
    for _ in 1..INITIAL_CANDIDATES {
        let x = random.vector(size, 1.0);
        let c = cost(&x)?;
        if c < best_cost {
            (best, best_cost) = (x, c);
        }
    }
    let mut step = 0.3;
    for _ in 0..design.iterations {
        let x: Vec<f64> = best.iter().map(|v| v + step * random.normal()).collect();
        let c = cost(&x)?;
        if c < best_cost {
            (best, best_cost) = (x, c);
            step *= 1.5;
        } else {
            step *= 1.5f64.powf(-0.25);
        }
        step = step.clamp(1e-4, 2.0);
    }
    Ok(Excitation {
        trajectory: decode(&best, design),
        condition: 10f64.powf(best_cost),
    })
}

/// The trajectory of search point `x`: per joint an offset in [−1, 1] (times half the
/// position limit) and 2N raw coefficients, scaled so that the joint reaches one of its
/// limits and exceeds none.
fn decode(x: &[f64], design: &Design) -> FourierTrajectory {
    let (harmonics, limits) = (design.harmonics, &design.limits);
    let n = limits.position.len();
    let stride = 1 + 2 * harmonics;
    let mut trajectory = FourierTrajectory {
        period: design.period,
        offsets: (0..n)
            .map(|i| 0.5 * limits.position[i] * x[i * stride].clamp(-1.0, 1.0))
            .collect(),
        a: (0..n)
            .map(|i| x[i * stride + 1..i * stride + 1 + harmonics].to_vec())
            .collect(),
        b: (0..n)
            .map(|i| x[i * stride + 1 + harmonics..(i + 1) * stride].to_vec())
            .collect(),
    };
    for (i, [p, v, a]) in trajectory.bounds().into_iter().enumerate() {
        let room = limits.position[i] - trajectory.offsets[i].abs();
        let scale = (room / p)
            .min(limits.velocity[i] / v)
            .min(limits.acceleration[i] / a);
        let scale = if scale.is_finite() { scale } else { 0.0 };
        trajectory.a[i].iter_mut().for_each(|c| *c *= scale);
        trajectory.b[i].iter_mut().for_each(|c| *c *= scale);
    }
    trajectory
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trajectory() -> FourierTrajectory {
        FourierTrajectory {
            period: 4.0,
            offsets: vec![0.1, -0.2],
            a: vec![vec![0.3, -0.2], vec![0.1, 0.05]],
            b: vec![vec![-0.1, 0.4], vec![0.2, -0.3]],
        }
    }

    /// q̇ and q̈ are the time derivatives of q (central differences), the series repeats
    /// after a period, and the analytic bounds hold at 4000 points of a period.
    #[test]
    fn derivatives_periodicity_and_bounds() {
        let f = trajectory();
        let h = 1e-5;
        for k in 0..40 {
            let t = 0.1 * k as f64;
            let (q, qd, qdd) = f.state(t);
            let (before, after) = (f.state(t - h), f.state(t + h));
            let later = f.state(t + f.period);
            for i in 0..2 {
                assert!(((after.0[i] - before.0[i]) / (2.0 * h) - qd[i]).abs() < 1e-8);
                assert!(((after.1[i] - before.1[i]) / (2.0 * h) - qdd[i]).abs() < 1e-8);
                assert!((later.0[i] - q[i]).abs() < 1e-12);
            }
        }
        let bounds = f.bounds();
        for (_, (q, qd, qdd)) in f.states(f.period, 4000) {
            for i in 0..2 {
                let [p, v, a] = bounds[i];
                assert!((q[i] - f.offsets[i]).abs() <= p && qd[i].abs() <= v && qdd[i].abs() <= a);
            }
        }
    }

    /// A decoded search point meets every limit and reaches at least one per joint.
    #[test]
    fn decoded_trajectories_fit_their_limits() {
        let design = Design {
            period: 5.0,
            harmonics: 3,
            limits: Limits {
                position: vec![1.0, 2.0],
                velocity: vec![0.5, 3.0],
                acceleration: vec![f64::INFINITY, 1.0],
            },
            iterations: 0,
            criterion_states: 10,
            seed: 0,
        };
        let mut random = Random::new(3);
        for _ in 0..50 {
            let f = decode(&random.vector(14, 2.0), &design);
            for (i, [p, v, a]) in f.bounds().into_iter().enumerate() {
                let room = design.limits.position[i] - f.offsets[i].abs();
                let used = [
                    p / room,
                    v / design.limits.velocity[i],
                    a / design.limits.acceleration[i],
                ];
                let most = used.iter().copied().fold(0.0, f64::max);
                assert!((most - 1.0).abs() < 1e-12, "joint {i}: {used:?}");
            }
        }
    }
}
