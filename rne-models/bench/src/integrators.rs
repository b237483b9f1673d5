//! Integrator work-precision: time to solution against final-state error and against energy
//! drift, for the integrators of [`rne_sim`] on two conservative runs of the thesis.
//!
//! # Problems
//! - **Double pendulum**: the planar elbow released from rest at q = 0 with no input (figures
//!   6.4–6.8), on its generated kernels ([`planar_elbow::Model`]); chaotic, so errors grow
//!   quickly with the duration.
//! - **IRB 140 joint-3 pendulum**: the IRB 140 with joints 1 and 2 locked at 0 (a `lock` scene,
//!   [`irb140_joint3::Model`]), link 3 released from rest at q₃ = 0 (figures 6.16–6.17).
//!
//! # Method
//! - **Settings**: RK4 at several steps h, Dormand–Prince 5(4) at several tolerances
//!   (rtol = atol), and the 2-stage (order-4) symplectic Gauss–Legendre method at several steps.
//!   Every step divides the output spacing, so fixed-step runs take equal steps.
//! - **Reference**: Dormand–Prince at rtol = atol = 10⁻¹³. Its own error is estimated by its
//!   distance to Gauss–Legendre with a step 100 times smaller than the finest benchmarked one;
//!   errors near that distance are not resolved.
//! - **Final-state error**: max over joints of |Δq| (rad) and |Δq̇| (rad/s) at the final time,
//!   against the reference.
//! - **Energy drift**: max over the output grid (every [`SAMPLE`] s) of |E(t) − E(0)| (J),
//!   from [`Record::energy_drift`](rne_sim::Record::energy_drift) of a recorded run with the
//!   same steps (Dormand–Prince interpolates the grid with its dense output, which does not
//!   change its steps; the fixed-step methods land on it).
//! - **Time to solution**: one integration from 0 to the final time with no intermediate
//!   output, timed by the harness of [`super::timing`]: all settings of a problem interleaved
//!   in rounds, median and interquartile range over rounds.

use super::error::BenchError;
use super::timing::{time_interleaved, Plan, Timed, Timing};
use rne_codegen::Dynamics;
use rne_models::generated::planar_elbow;
use rne_models::generated::scenes::irb140_joint3;
use rne_scenarios::parameters::SAMPLE;
use rne_sim::{
    output_times, simulate, Dopri5, GaussLegendre, Integrator, Method, Rk4, SimError, State, Stats,
    ZeroInput,
};

/// An integrator family.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Family {
    /// Classical Runge–Kutta, fixed step.
    Rk4,
    /// Dormand–Prince 5(4), adaptive.
    Dopri5,
    /// 2-stage Gauss–Legendre, symplectic, fixed step.
    GaussLegendre,
}

impl Family {
    /// Every family, in table order.
    pub const ALL: [Family; 3] = [Family::Rk4, Family::Dopri5, Family::GaussLegendre];

    /// The name in tables and legends.
    pub fn label(self) -> &'static str {
        match self {
            Family::Rk4 => "RK4",
            Family::Dopri5 => "Dormand–Prince 5(4)",
            Family::GaussLegendre => "Gauss–Legendre (2 stages)",
        }
    }

    /// The integrator with step or tolerance `parameter`.
    fn method(self, parameter: f64) -> Method {
        match self {
            Family::Rk4 => Method::Rk4(Rk4::new(parameter)),
            Family::Dopri5 => Method::Dopri5(Dopri5::new(parameter, parameter)),
            Family::GaussLegendre => Method::GaussLegendre(GaussLegendre::new(parameter)),
        }
    }

    /// What its parameter is.
    pub fn parameter_name(self) -> &'static str {
        match self {
            Family::Dopri5 => "rtol = atol",
            Family::Rk4 | Family::GaussLegendre => "h (s)",
        }
    }
}

/// The settings of one study.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Final time (s).
    pub duration: f64,
    /// Steps of RK4 (s).
    pub rk4: Vec<f64>,
    /// Tolerances of Dormand–Prince.
    pub dopri5: Vec<f64>,
    /// Steps of Gauss–Legendre (s).
    pub gauss_legendre: Vec<f64>,
}

impl Settings {
    /// (family, parameter) of every setting, in table order.
    fn all(&self) -> Vec<(Family, f64)> {
        let tag = |family: Family, v: &[f64]| -> Vec<(Family, f64)> {
            v.iter().map(|&p| (family, p)).collect()
        };
        [
            tag(Family::Rk4, &self.rk4),
            tag(Family::Dopri5, &self.dopri5),
            tag(Family::GaussLegendre, &self.gauss_legendre),
        ]
        .concat()
    }
}

/// The reference tolerance.
pub const REFERENCE_TOLERANCE: f64 = 1e-13;

/// One integrator setting on one problem.
#[derive(Clone, Debug, PartialEq)]
pub struct IntegratorRow {
    /// The family.
    pub family: Family,
    /// Its step (s) or tolerance.
    pub parameter: f64,
    /// The work of one integration.
    pub stats: Stats,
    /// Time to solution, ns per integration.
    pub timing: Timing,
    /// Final-state error against the reference.
    pub final_error: f64,
    /// Energy drift over the run (J).
    pub energy_drift: f64,
}

/// The study of one problem.
#[derive(Clone, Debug, PartialEq)]
pub struct IntegratorStudy {
    /// Short name, used in file names.
    pub name: &'static str,
    /// What is integrated.
    pub title: &'static str,
    /// Final time (s).
    pub duration: f64,
    /// Estimated error of the reference (its distance to a fine Gauss–Legendre run).
    pub reference_error: f64,
    /// Energy drift of the reference run (J).
    pub reference_drift: f64,
    /// One row per setting.
    pub rows: Vec<IntegratorRow>,
}

/// The double pendulum study with `settings`.
pub fn double_pendulum(settings: &Settings, plan: &Plan) -> Result<IntegratorStudy, BenchError> {
    study(
        "double-pendulum",
        "double pendulum: planar elbow released from q = 0",
        &planar_elbow::Model,
        State::at_rest([0.0; 2]),
        settings,
        plan,
    )
}

/// The IRB 140 joint-3 pendulum study with `settings`.
pub fn irb140_pendulum(settings: &Settings, plan: &Plan) -> Result<IntegratorStudy, BenchError> {
    study(
        "irb140-pendulum",
        "IRB 140 joint-3 pendulum: joints 1–2 locked, released from q3 = 0",
        &irb140_joint3::Model,
        State::at_rest([0.0]),
        settings,
        plan,
    )
}

/// One integration from rest to the final time with no intermediate output, timed as a whole.
struct Run<'a, const N: usize, D> {
    model: &'a D,
    method: Method,
    x0: State<N>,
    times: [f64; 2],
}

impl<const N: usize, D: Dynamics<N, N, Scalar = f64>> Run<'_, N, D> {
    /// Integrates once: the final state and the integrator's work.
    fn integrate(&self) -> Result<(State<N>, Stats), SimError> {
        let mut last = self.x0;
        let stats =
            self.method
                .integrate(self.model, &ZeroInput, &self.x0, &self.times, |_, x| {
                    last = *x
                })?;
        Ok((last, stats))
    }
}

impl<const N: usize, D: Dynamics<N, N, Scalar = f64>> Timed for Run<'_, N, D> {
    fn run(&mut self, calls: u64) {
        for _ in 0..calls {
            std::hint::black_box(self.integrate().ok());
        }
    }
}

/// max over joints of |Δq| and |Δq̇|.
fn distance<const N: usize>(a: &State<N>, b: &State<N>) -> f64 {
    a.q.iter()
        .zip(&b.q)
        .chain(a.qd.iter().zip(&b.qd))
        .map(|(x, y)| (x - y).abs())
        .fold(
            0.0,
            |m: f64, d| if d.is_nan() { f64::NAN } else { m.max(d) },
        )
}

/// Runs the study of `model` from `x0` (see the module documentation).
fn study<const N: usize, D: Dynamics<N, N, Scalar = f64>>(
    name: &'static str,
    title: &'static str,
    model: &D,
    x0: State<N>,
    settings: &Settings,
    plan: &Plan,
) -> Result<IntegratorStudy, BenchError> {
    let duration = settings.duration;
    let simulation = SimError::in_run;
    let run = |method: Method| Run {
        model,
        method,
        x0,
        times: [0.0, duration],
    };
    let grid = output_times(0.0, duration, SAMPLE);
    let reference_method = Family::Dopri5.method(REFERENCE_TOLERANCE);
    let (reference, _) = run(reference_method)
        .integrate()
        .map_err(simulation(format!("{name}: reference")))?;
    let finest = settings
        .rk4
        .iter()
        .chain(&settings.gauss_legendre)
        .fold(SAMPLE, |m: f64, &h| m.min(h));
    let (check, _) = run(Family::GaussLegendre.method(finest / 100.0))
        .integrate()
        .map_err(simulation(format!("{name}: reference check")))?;
    let reference_drift = simulate(model, &ZeroInput, &reference_method, &x0, &grid)
        .map_err(simulation(format!("{name}: reference")))?
        .energy_drift();

    let all = settings.all();
    let mut runs = Vec::new();
    let mut partial = Vec::new();
    for &(family, parameter) in &all {
        let what = format!("{name}: {} at {parameter:e}", family.label());
        let method = family.method(parameter);
        let one = run(method);
        let (last, stats) = one.integrate().map_err(simulation(what.clone()))?;
        let drift = simulate(model, &ZeroInput, &method, &x0, &grid)
            .map_err(simulation(what))?
            .energy_drift();
        partial.push((family, parameter, stats, distance(&last, &reference), drift));
        runs.push(one);
    }
    let mut subjects: Vec<&mut dyn Timed> = runs.iter_mut().map(|r| r as &mut dyn Timed).collect();
    let timings = time_interleaved(&mut subjects, plan);
    let rows = partial
        .into_iter()
        .zip(timings)
        .map(
            |((family, parameter, stats, final_error, energy_drift), timing)| IntegratorRow {
                family,
                parameter,
                stats,
                timing,
                final_error,
                energy_drift,
            },
        )
        .collect();
    Ok(IntegratorStudy {
        name,
        title,
        duration,
        reference_error: distance(&reference, &check),
        reference_drift,
        rows,
    })
}
