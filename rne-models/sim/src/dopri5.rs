//! Adaptive Dormand–Prince 5(4) with step-size control and dense output: MATLAB's ode45, which
//! the thesis used at relative tolerance 1e-10 (section 6.1).

use super::controller::Controller;
use super::error::SimError;
use super::integrator::{derivative, validate_times, Integrator, Stats};
use super::state::State;
use rne_runtime::Dynamics;

// Dormand–Prince 5(4) tableau (Hairer–Nørsett–Wanner I, table II.5.2).
const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
// The 5th-order weights; also row 7 of the tableau (first same as last).
const B1: f64 = 35.0 / 384.0;
const B3: f64 = 500.0 / 1113.0;
const B4: f64 = 125.0 / 192.0;
const B5: f64 = -2187.0 / 6784.0;
const B6: f64 = 11.0 / 84.0;
// Differences of the 5th- and 4th-order weights: the local error estimate.
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
// The 4th-order continuous extension (Shampine 1986; Hairer's DOPRI5 `CONTD5`).
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

// Step-size controller constants, the defaults of Hairer's DOPRI5.
/// Safety factor.
const SAFE: f64 = 0.9;
/// Largest step decrease factor 1/FAC_MIN = 5 per step ...
const FAC_MIN: f64 = 0.2;
/// ... and largest increase factor.
const FAC_MAX: f64 = 10.0;
/// Exponent of the previous error in the PI controller (Lund stabilisation).
const BETA: f64 = 0.04;

/// Adaptive Dormand–Prince 5(4) (Hairer–Nørsett–Wanner, *Solving Ordinary Differential
/// Equations I*, sections II.4–II.6 and their code DOPRI5), the method of MATLAB's ode45 that the
/// thesis used at relative tolerance 1e-10 (section 6.1).
///
/// - **Method**: 7 stages, order 5 propagated (local extrapolation), embedded order-4 error
///   estimate; first same as last (FSAL), so an accepted step costs 6 evaluations of (6.2).
/// - **Error control**: err = ‖(y₅ − y₄)ᵢ / skᵢ‖ (root mean square over the 2N components of
///   (q, q̇)) with skᵢ = atol + rtol · max(|y₀ᵢ|, |y₁ᵢ|); a step is accepted when err ≤ 1.
/// - **Step-size control**: the PI controller of DOPRI5, h_new = h / fac with
///   fac = clamp(err^(1/5 − 0.75 β) / err_prev^β / 0.9, 1/10, 5), β = 0.04; after a rejection
///   the step may not grow. The initial step is Hairer's `HINIT` estimate unless given.
/// - **Dense output** (the default): the 4th-order continuous extension (Shampine's, Hairer's
///   `CONTD5`) evaluates the solution at every requested output time inside a step. Output
///   times never shorten a step; the steps taken, and so the final state, are identical for any
///   output grid (only the final time of the grid is stepped to exactly). The interpolant is
///   one order less accurate than the steps: on the released double pendulum at rtol 1e-12 the
///   energy error is 6e-10 J at the steps but up to 3.4e-9 J between them.
/// - **Stepping to the outputs** (`step_to_outputs`): every output time ends a step (a step
///   that would pass it is shortened, and the controller resumes from the step it had planned),
///   so every sample is a 5th-order step value. Costs up to one extra step per output time.
#[derive(Clone, Copy, Debug)]
pub struct Dopri5 {
    /// Relative tolerance (the thesis: 1e-10).
    pub rtol: f64,
    /// Absolute tolerance, in the units of each state component.
    pub atol: f64,
    /// First step size; `None` for Hairer's automatic estimate.
    pub initial_step: Option<f64>,
    /// Largest step size allowed.
    pub max_step: f64,
    /// Step budget (accepted plus rejected) before [`SimError::TooManySteps`].
    pub max_steps: u64,
    /// End a step at every output time instead of interpolating (see above).
    pub step_to_outputs: bool,
}

impl Dopri5 {
    /// Dormand–Prince with tolerances `rtol`, `atol`, automatic initial step, no step limit,
    /// a budget of 10⁸ steps and dense output.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Self {
            rtol,
            atol,
            initial_step: None,
            max_step: f64::INFINITY,
            max_steps: 100_000_000,
            step_to_outputs: false,
        }
    }

    /// Root-mean-square norm of `e` scaled by atol + rtol · max(|a|, |b|).
    fn error_norm<const N: usize>(&self, e: &State<N>, a: &State<N>, b: &State<N>) -> f64 {
        let sum: f64 = e
            .components()
            .zip(a.components().zip(b.components()))
            .map(|(ei, (ai, bi))| {
                let sk = self.atol + self.rtol * ai.abs().max(bi.abs());
                (ei / sk).powi(2)
            })
            .sum();
        (sum / (2 * N) as f64).sqrt()
    }

    /// Hairer's `HINIT`: a first step from the sizes of x, f(x) and an estimate of the second
    /// derivative. Costs one evaluation.
    fn initial_step_size<const N: usize, D, C>(
        &self,
        model: &D,
        controller: &C,
        t0: f64,
        x0: &State<N>,
        f0: &State<N>,
        span: f64,
    ) -> f64
    where
        D: Dynamics<N, N, Scalar = f64> + ?Sized,
        C: Controller<N> + ?Sized,
    {
        let scaled = |v: &State<N>| -> f64 {
            v.components()
                .zip(x0.components())
                .map(|(vi, xi)| (vi / (self.atol + self.rtol * xi.abs())).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        let (dnf, dny) = (scaled(f0), scaled(x0));
        let mut h = if dnf <= 1e-5 || dny <= 1e-5 {
            1e-6
        } else {
            0.01 * dny / dnf
        };
        h = h.min(self.max_step).min(span);
        let f1 = derivative(model, controller, t0 + h, &x0.add_scaled(h, f0));
        let diff = State {
            q: std::array::from_fn(|i| f1.q[i] - f0.q[i]),
            qd: std::array::from_fn(|i| f1.qd[i] - f0.qd[i]),
        };
        let der2 = scaled(&diff) / h;
        let der12 = der2.max(dnf);
        let h1 = if der12 <= 1e-15 {
            (h * 1e-3).max(1e-6)
        } else {
            (0.01 / der12).powf(0.2)
        };
        (100.0 * h).min(h1).min(self.max_step).min(span)
    }
}

/// The coefficients of the continuous extension over one accepted step [t, t + h]:
/// y(t + θh) = r₁ + θ (r₂ + (1 − θ) (r₃ + θ (r₄ + (1 − θ) r₅))).
struct DenseStep<const N: usize> {
    r: [State<N>; 5],
}

impl<const N: usize> DenseStep<N> {
    /// The extension from the step's start `y0`, end `y1`, and stages (k₁, k₃, …, k₇).
    #[allow(clippy::too_many_arguments)]
    fn new(
        h: f64,
        y0: &State<N>,
        y1: &State<N>,
        k1: &State<N>,
        k3: &State<N>,
        k4: &State<N>,
        k5: &State<N>,
        k6: &State<N>,
        k7: &State<N>,
    ) -> Self {
        let zero = State::at_rest([0.0; N]);
        let ydiff = zero.add_combination(1.0, &[(1.0, y1), (-1.0, y0)]);
        let bspl = zero.add_combination(1.0, &[(h, k1), (-1.0, &ydiff)]);
        let r4 = zero.add_combination(1.0, &[(1.0, &ydiff), (-h, k7), (-1.0, &bspl)]);
        let r5 = zero.add_combination(
            h,
            &[(D1, k1), (D3, k3), (D4, k4), (D5, k5), (D6, k6), (D7, k7)],
        );
        Self {
            r: [*y0, ydiff, bspl, r4, r5],
        }
    }

    /// The interpolated state at fraction `theta` ∈ [0, 1] of the step.
    fn eval(&self, theta: f64) -> State<N> {
        let t1 = 1.0 - theta;
        let [r1, r2, r3, r4, r5] = &self.r;
        let at = |a: f64, b: f64, c: f64, d: f64, e: f64| {
            a + theta * (b + t1 * (c + theta * (d + t1 * e)))
        };
        State {
            q: std::array::from_fn(|i| at(r1.q[i], r2.q[i], r3.q[i], r4.q[i], r5.q[i])),
            qd: std::array::from_fn(|i| at(r1.qd[i], r2.qd[i], r3.qd[i], r4.qd[i], r5.qd[i])),
        }
    }
}

/// One trial step of the embedded pair from `(t, x)` with first stage `k1`: the other six
/// stages, the fifth-order solution and the difference between the two orders' solutions.
struct Trial<const N: usize> {
    k: [State<N>; 6],
    y1: State<N>,
    error: State<N>,
}

impl<const N: usize> Trial<N> {
    /// The stages k₂ … k₇ of a step of size `h` from `(t, x)`, k₇ at `t_new` (t + h, or the
    /// output the step was shortened to land on exactly).
    fn new(
        f: &impl Fn(f64, &State<N>) -> State<N>,
        (t, x, k1): (f64, &State<N>, &State<N>),
        h: f64,
        t_new: f64,
    ) -> Self {
        let k2 = f(t + C2 * h, &x.add_combination(h, &[(A21, k1)]));
        let k3 = f(t + C3 * h, &x.add_combination(h, &[(A31, k1), (A32, &k2)]));
        let k4 = f(
            t + C4 * h,
            &x.add_combination(h, &[(A41, k1), (A42, &k2), (A43, &k3)]),
        );
        let k5 = f(
            t + C5 * h,
            &x.add_combination(h, &[(A51, k1), (A52, &k2), (A53, &k3), (A54, &k4)]),
        );
        let k6 = f(
            t + h,
            &x.add_combination(
                h,
                &[(A61, k1), (A62, &k2), (A63, &k3), (A64, &k4), (A65, &k5)],
            ),
        );
        let y1 = x.add_combination(h, &[(B1, k1), (B3, &k3), (B4, &k4), (B5, &k5), (B6, &k6)]);
        let k7 = f(t_new, &y1);
        let zero = State::at_rest([0.0; N]);
        let error = zero.add_combination(
            h,
            &[
                (E1, k1),
                (E3, &k3),
                (E4, &k4),
                (E5, &k5),
                (E6, &k6),
                (E7, &k7),
            ],
        );
        Trial {
            k: [k2, k3, k4, k5, k6, k7],
            y1,
            error,
        }
    }

    /// The continuous extension over the accepted step from `x` with first stage `k1`.
    fn dense(&self, h: f64, x: &State<N>, k1: &State<N>) -> DenseStep<N> {
        let [_, k3, k4, k5, k6, k7] = &self.k;
        DenseStep::new(h, x, &self.y1, k1, k3, k4, k5, k6, k7)
    }
}

/// Where the integration stands between steps: time, state, first stage of the next step
/// (the last stage of the previous one: first same as last) and the next step size.
struct Position<const N: usize> {
    t: f64,
    x: State<N>,
    k1: State<N>,
    h: f64,
}

/// The step-size controller's memory (Hairer, Nørsett and Wanner's DOPRI5 with Gustafsson's
/// PI control): the previous accepted error and whether the last trial was rejected.
struct Control {
    fac_old: f64,
    last_rejected: bool,
}

impl Control {
    /// The step after an accepted step of size `h` whose error factor proposes `h_new`; `h` was
    /// shortened from `h_planned` to land on an output when `clipped`.
    fn after_accept(&mut self, h_new: f64, h: f64, h_planned: f64, clipped: bool, max: f64) -> f64 {
        let (mut h_new, mut h_done) = (h_new, h);
        if clipped {
            // A step shortened to land on an output says little about the scale of the
            // solution: resume from the step planned before shortening.
            h_done = h.max(h_planned);
            h_new = h_new.max(h_planned);
        }
        h_new = h_new.min(max);
        if self.last_rejected {
            h_new = h_new.min(h_done);
        }
        self.last_rejected = false;
        h_new
    }

    /// Records a rejected trial and returns the step to try instead.
    fn after_reject(&mut self, h_retry: f64, stats: &mut Stats) -> f64 {
        stats.rejected += 1;
        self.last_rejected = true;
        h_retry
    }
}

/// Hands `sink` every output time the accepted step from `t` to `t_new` (of size `h`) reaches:
/// its end as computed, the times inside it from the continuous extension.
fn emit_outputs<const N: usize>(
    times: &[f64],
    next_out: &mut usize,
    (t, t_new, h): (f64, f64, f64),
    (y1, dense): (&State<N>, &DenseStep<N>),
    sink: &mut impl FnMut(f64, &State<N>),
) {
    while *next_out < times.len() && times[*next_out] <= t_new {
        let t_out = times[*next_out];
        if t_out == t_new {
            sink(t_out, y1);
        } else {
            sink(t_out, &dense.eval((t_out - t) / h));
        }
        *next_out += 1;
    }
}

impl Dopri5 {
    /// The settings' error: tolerances negative or both zero, a step bound or initial step
    /// that is not positive.
    fn check_settings(&self) -> Result<(), SimError> {
        let tolerances_ok = self.rtol >= 0.0 && self.atol >= 0.0 && self.rtol + self.atol > 0.0;
        if !tolerances_ok || self.max_step.is_nan() || self.max_step <= 0.0 {
            return Err(SimError::InvalidSetting(
                "Dormand-Prince needs rtol, atol >= 0 (not both 0) and max_step > 0",
            ));
        }
        if self
            .initial_step
            .is_some_and(|h| !(h > 0.0 && h.is_finite()))
        {
            return Err(SimError::InvalidSetting(
                "Dormand-Prince initial step must be positive",
            ));
        }
        Ok(())
    }

    /// The error that ends the integration before a step from `t` of size `h`: too many
    /// steps, or a step too small to move `t`.
    fn check_progress(&self, stats: &Stats, t: f64, h: f64) -> Result<(), SimError> {
        if stats.steps + stats.rejected >= self.max_steps {
            return Err(SimError::TooManySteps {
                t,
                steps: self.max_steps,
            });
        }
        if 0.1 * h.abs() <= t.abs() * f64::EPSILON {
            return Err(SimError::StepSizeTooSmall { t, h });
        }
        Ok(())
    }

    /// Steps from `at` to the last of `times`, accepting or rejecting each trial by its error
    /// and handing `sink` the state at every output time after the first.
    fn march<const N: usize>(
        &self,
        f: &impl Fn(f64, &State<N>) -> State<N>,
        times: &[f64],
        mut at: Position<N>,
        mut stats: Stats,
        sink: &mut impl FnMut(f64, &State<N>),
    ) -> Result<Stats, SimError> {
        let t_end = times[times.len() - 1];
        let expo1 = 0.2 - BETA * 0.75;
        let mut control = Control {
            fac_old: 1e-4,
            last_rejected: false,
        };
        let mut next_out = 1;
        loop {
            self.check_progress(&stats, at.t, at.h)?;
            // The time this step must not pass: the next output, or the end.
            let target = if self.step_to_outputs {
                times[next_out]
            } else {
                t_end
            };
            let h_planned = at.h;
            let clipped = at.t + 1.01 * at.h >= target;
            let h = if clipped { target - at.t } else { at.h };
            let t_new = if clipped { target } else { at.t + h };
            let trial = Trial::new(f, (at.t, &at.x, &at.k1), h, t_new);
            stats.evaluations += 6;
            let err = self.error_norm(&trial.error, &at.x, &trial.y1);
            if !err.is_finite() {
                // A blown-up stage: retreat hard and try again.
                at.h = control.after_reject(h * FAC_MIN, &mut stats);
                continue;
            }
            let fac11 = err.powf(expo1);
            if err > 1.0 {
                at.h = control.after_reject(h / (fac11 / SAFE).min(1.0 / FAC_MIN), &mut stats);
                continue;
            }
            let fac =
                (fac11 / control.fac_old.powf(BETA) / SAFE).clamp(1.0 / FAC_MAX, 1.0 / FAC_MIN);
            control.fac_old = err.max(1e-4);
            stats.steps += 1;
            let dense = trial.dense(h, &at.x, &at.k1);
            emit_outputs(
                times,
                &mut next_out,
                (at.t, t_new, h),
                (&trial.y1, &dense),
                sink,
            );
            (at.t, at.x, at.k1) = (t_new, trial.y1, trial.k[5]);
            if at.t == t_end {
                return Ok(stats);
            }
            at.h = control.after_accept(h / fac, h, h_planned, clipped, self.max_step);
        }
    }
}

impl<const N: usize> Integrator<N> for Dopri5 {
    fn integrate<D, C, F>(
        &self,
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
        validate_times(times)?;
        self.check_settings()?;
        let mut stats = Stats::default();
        let (t0, t_end) = (times[0], times[times.len() - 1]);
        sink(t0, x0);
        if times.len() == 1 {
            return Ok(stats);
        }
        let f = |t: f64, x: &State<N>| derivative(model, controller, t, x);
        let k1 = f(t0, x0);
        stats.evaluations += 1;
        if !(x0.is_finite() && k1.is_finite()) {
            return Err(SimError::NonFinite { t: t0 });
        }
        let h = match self.initial_step {
            Some(h) => h.min(self.max_step),
            None => {
                stats.evaluations += 1;
                self.initial_step_size(model, controller, t0, x0, &k1, t_end - t0)
            }
        };
        let at = Position {
            t: t0,
            x: *x0,
            k1,
            h,
        };
        self.march(&f, times, at, stats, &mut sink)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::ZeroInput;
    use crate::test_models::{observed_order, Oscillator, Pendulum};

    /// Property: with error control switched off (a fixed step far inside the tolerance), the
    /// Dormand–Prince tableau converges at order 5 at a time it steps to, and so does its dense
    /// output half-way through a step: the continuous extension has order 4, i.e. local error
    /// O(h⁵), the size of the propagated error (a cubic Hermite interpolant, which drops the
    /// D-coefficient term, would show order 4 here). Exact reference: the pendulum reaches −θ₀
    /// at rest at half its closed-form period; between steps, a run at tolerance 1e-14.
    #[test]
    fn dopri5_converges_at_order_five_with_dense_output() {
        let p = Pendulum::new(1.0, 1.0, 9.81);
        let theta0 = 1.0;
        let t_half = 0.5 * p.period(theta0);
        let mut node_err = Vec::new();
        let mut dense_err = Vec::new();
        for n in [40u32, 80, 160, 320] {
            let h = t_half / f64::from(n);
            let fixed = Dopri5 {
                initial_step: Some(h),
                max_step: h,
                ..Dopri5::new(1.0, 1.0)
            };
            // Output at the end, and once just before the end inside the last step: the
            // interpolation error there dominates the propagated one.
            let mut out = Vec::new();
            let stats = fixed
                .integrate(
                    &p,
                    &ZeroInput,
                    &State::at_rest([theta0]),
                    &[0.0, t_half - 0.5 * h, t_half],
                    |t, x| out.push((t, *x)),
                )
                .unwrap();
            assert_eq!(stats.rejected, 0);
            let end = out[2].1;
            node_err.push((end.q[0] + theta0).abs().max(end.qd[0].abs()));
            // Reference at the interior time: a very accurate adaptive run.
            let mut reference = State::at_rest([0.0]);
            Dopri5::new(1e-14, 1e-14)
                .integrate(
                    &p,
                    &ZeroInput,
                    &State::at_rest([theta0]),
                    &[0.0, out[1].0],
                    |_, x| reference = *x,
                )
                .unwrap();
            let mid = out[1].1;
            dense_err.push((mid.q[0] - reference.q[0]).abs());
        }
        let node_orders = observed_order(&node_err);
        for &o in &node_orders {
            assert!((4.7..5.4).contains(&o), "{node_err:?} {node_orders:?}");
        }
        let dense_orders = observed_order(&dense_err);
        for &o in &dense_orders {
            assert!((4.6..5.5).contains(&o), "{dense_err:?} {dense_orders:?}");
        }
    }

    /// Property: the adaptive error is proportional to the tolerance (tolerance
    /// proportionality), and the accepted steps grow like rtol^(−1/5) for a 5th-order pair.
    #[test]
    fn dopri5_error_tracks_tolerance() {
        let osc = Oscillator { omega: 2.0 };
        let t_end: f64 = 10.0;
        let exact = (2.0 * t_end).cos();
        let mut results = Vec::new();
        for tol in [1e-6, 1e-8, 1e-10] {
            let mut last = State::at_rest([0.0]);
            let stats = Dopri5::new(tol, tol)
                .integrate(
                    &osc,
                    &ZeroInput,
                    &State::at_rest([1.0]),
                    &[0.0, t_end],
                    |_, x| last = *x,
                )
                .unwrap();
            results.push(((last.q[0] - exact).abs(), stats.steps as f64));
        }
        for w in results.windows(2) {
            let (e0, s0) = w[0];
            let (e1, s1) = w[1];
            // 100x tighter tolerance: error down by 30x to 300x, steps up by 100^(1/5) ≈ 2.5.
            assert!((30.0..300.0).contains(&(e0 / e1)), "{results:?}");
            assert!((2.0..3.2).contains(&(s1 / s0)), "{results:?}");
        }
        assert!(results[2].0 < 1e-8, "{results:?}");
    }

    /// Property: output times never influence the steps taken. The final state is bitwise the
    /// same with 2 or 1000 output times, and every dense-output sample of the oscillator is
    /// accurate to the tolerance level.
    #[test]
    fn dopri5_dense_output_is_independent_of_the_output_grid() {
        let osc = Oscillator { omega: 3.0 };
        let dp = Dopri5::new(1e-10, 1e-10);
        let x0 = State::at_rest([1.0]);
        let mut coarse = Vec::new();
        let s_coarse = dp
            .integrate(&osc, &ZeroInput, &x0, &[0.0, 7.0], |t, x| {
                coarse.push((t, *x))
            })
            .unwrap();
        let times: Vec<f64> = (0..=1000).map(|i| 7.0 * f64::from(i) / 1000.0).collect();
        let mut fine = Vec::new();
        let s_fine = dp
            .integrate(&osc, &ZeroInput, &x0, &times, |t, x| fine.push((t, *x)))
            .unwrap();
        assert_eq!(s_coarse, s_fine);
        assert_eq!(coarse[1].1, fine[1000].1);
        assert_eq!(fine.len(), 1001);
        assert!(s_fine.steps < 1000, "dense output must not force steps");
        let worst = fine
            .iter()
            .map(|(t, x)| (x.q[0] - (3.0 * t).cos()).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-8, "worst dense-output error {worst:e}");
        assert_eq!(s_fine.evaluations, 2 + 6 * (s_fine.steps + s_fine.rejected));
    }

    /// Property: with `step_to_outputs` every output time ends a step. Samples are then exactly
    /// what a run ending at that time gives (same steps), each output costs at most one extra
    /// step, and the samples are at least as accurate as the interpolated ones.
    #[test]
    fn dopri5_can_step_to_every_output() {
        let osc = Oscillator { omega: 3.0 };
        let x0 = State::at_rest([1.0]);
        let stepping = Dopri5 {
            step_to_outputs: true,
            ..Dopri5::new(1e-9, 1e-9)
        };
        let times: Vec<f64> = (0..=70).map(|i| 0.1 * f64::from(i)).collect();
        let mut all = Vec::new();
        let s_all = stepping
            .integrate(&osc, &ZeroInput, &x0, &times, |t, x| all.push((t, *x)))
            .unwrap();
        let mut alone = None;
        stepping
            .integrate(&osc, &ZeroInput, &x0, &times[..=35], |_, x| {
                alone = Some(*x)
            })
            .unwrap();
        assert_eq!(alone.unwrap(), all[35].1);
        let mut dense_err = 0.0_f64;
        let s_dense = Dopri5::new(1e-9, 1e-9)
            .integrate(&osc, &ZeroInput, &x0, &times, |t, x| {
                dense_err = dense_err.max((x.q[0] - (3.0 * t).cos()).abs())
            })
            .unwrap();
        assert!(
            s_all.steps >= 70 && s_all.steps <= s_dense.steps + 70,
            "{s_all:?} {s_dense:?}"
        );
        let step_err = all
            .iter()
            .map(|(t, x)| (x.q[0] - (3.0 * t).cos()).abs())
            .fold(0.0, f64::max);
        assert!(step_err <= dense_err, "{step_err:e} vs {dense_err:e}");
    }

    /// The step-size guard reports a singular problem instead of looping forever:
    /// q̇ = q² blows up at t = 1 from q(0) = 1.
    #[test]
    fn dopri5_reports_blow_up() {
        let blow_up = |_: f64, q: &[f64; 1], _: &[f64; 1]| [q[0] * q[0]];
        // M = 1, g = 0: q̈ = u = q², a finite-time blow-up.
        let osc = Oscillator { omega: 0.0 };
        let r = Dopri5::new(1e-8, 1e-8).integrate(
            &osc,
            &blow_up,
            &State::new([1.0], [1.0]),
            &[0.0, 10.0],
            |_, _| {},
        );
        assert!(
            matches!(
                r,
                Err(SimError::StepSizeTooSmall { .. } | SimError::NonFinite { .. })
            ),
            "{r:?}"
        );
    }
}
