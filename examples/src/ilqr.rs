//! Iterative LQR with control limits: Li & Todorov, "Iterative linear quadratic regulator
//! design for nonlinear biological movement systems", ICINCO 2004, with the regularisation
//! schedule and line search of Tassa, Erez & Todorov, "Synthesis and stabilization of complex
//! behaviors through online trajectory optimization", IROS 2012, and the box-constrained
//! backward pass of Tassa, Mansard & Todorov, ICRA 2014.
//!
//! Each iteration linearises the discrete dynamics along the current trajectory (the
//! [`Discretisation`]'s Jacobians: here the generated derivative kernels), sweeps backwards for
//! gains ([`backward_pass`]), and rolls the gains out forwards with a backtracking step α;
//! a step is taken only when the cost falls by a fair share of the predicted reduction, so
//! the accepted costs decrease strictly.

use std::time::{Duration, Instant};

use nalgebra::SVector;

use crate::backward_pass::{backward_pass, Bounds, Gains};
use crate::box_qp::NotPositiveDefinite;
use crate::cost::QuadraticCost;
use crate::discretisation::{Discretisation, Linearisation};
use crate::error::Error;

/// The settings of the optimiser.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Iterations at most (accepted or not).
    pub max_iterations: usize,
    /// Stop when an accepted step lowers the cost by less than this fraction of it.
    pub cost_tolerance: f64,
    /// Stop when the feedforward steps are this small relative to the controls
    /// ([`Gains::relative_step`]) with a regularisation below [`Options::converged_regularisation`].
    pub step_tolerance: f64,
    /// The regularisation below which a small step means convergence.
    pub converged_regularisation: f64,
    /// The regularisation μ of the first iteration.
    pub initial_regularisation: f64,
    /// Below this μ the regularisation becomes zero.
    pub min_regularisation: f64,
    /// Give up when μ must exceed this.
    pub max_regularisation: f64,
    /// Δ₀ of the regularisation schedule, > 1.
    pub regularisation_factor: f64,
    /// The steps α tried by the line search, largest first.
    pub line_search: Vec<f64>,
    /// Accept a step when actual / predicted cost reduction exceeds this, in (0, 1).
    pub acceptance: f64,
}

impl Default for Options {
    /// The values of Tassa, Erez & Todorov 2012: Δ₀ = 2, μ_min = 10⁻⁶, α ∈ 10^[0, −3] in 11
    /// steps; c₁ = 0.1.
    fn default() -> Self {
        Options {
            max_iterations: 500,
            cost_tolerance: 1e-7,
            step_tolerance: 1e-4,
            converged_regularisation: 1e-5,
            initial_regularisation: 1.0,
            min_regularisation: 1e-6,
            max_regularisation: 1e10,
            regularisation_factor: 2.0,
            line_search: (0..11).map(|i| 10f64.powf(-0.3 * f64::from(i))).collect(),
            acceptance: 0.1,
        }
    }
}

/// A finite-horizon optimal control problem: minimise `cost` over controls within `bounds`,
/// from `initial_state`, subject to `dynamics`.
#[derive(Clone, Debug)]
pub struct Problem<'a, D, const NX: usize, const NU: usize> {
    /// x_{k+1} = f(x_k, u_k).
    pub dynamics: &'a D,
    /// The cost J.
    pub cost: &'a QuadraticCost<NX, NU>,
    /// The control limits.
    pub bounds: Bounds<NU>,
    /// x₀.
    pub initial_state: SVector<f64, NX>,
}

/// States x₀ … x_N and controls u₀ … u_{N−1}.
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory<const NX: usize, const NU: usize> {
    /// N + 1 states.
    pub states: Vec<SVector<f64, NX>>,
    /// N controls.
    pub controls: Vec<SVector<f64, NU>>,
}

/// Where one iteration spent its time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timings {
    /// Linearising the dynamics, [`Timings::derivative_kernels`] included.
    pub linearisation: Duration,
    /// Inside the model's derivative kernels.
    pub derivative_kernels: Duration,
    /// The number of derivative-kernel calls [`Timings::derivative_kernels`] covers.
    pub derivative_kernel_calls: usize,
    /// The backward pass.
    pub backward_pass: Duration,
    /// The line search's rollouts.
    pub forward_pass: Duration,
    /// The whole iteration.
    pub total: Duration,
}

/// What one iteration did.
#[derive(Clone, Debug, PartialEq)]
pub struct Iteration {
    /// The cost after the iteration.
    pub cost: f64,
    /// The step α taken; `None` when the iteration took none: rejected (the backward pass met
    /// a Q_uu that is not positive definite, or no step reduced the cost enough) or converged
    /// ([`Stop::StepConverged`]).
    pub step: Option<f64>,
    /// The regularisation μ the iteration's backward pass used.
    pub regularisation: f64,
    /// The predicted cost reduction of the step taken (or of α = 1 when none was).
    pub expected_reduction: f64,
    /// Where its time went.
    pub timings: Timings,
}

/// Why the optimiser stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// An accepted step lowered the cost by less than [`Options::cost_tolerance`].
    CostConverged,
    /// The proposed steps became smaller than [`Options::step_tolerance`].
    StepConverged,
    /// [`Options::max_iterations`] were done.
    IterationLimit,
    /// The regularisation would have to exceed [`Options::max_regularisation`].
    RegularisationLimit,
}

/// The optimised trajectory and the history that led to it.
#[derive(Clone, Debug)]
pub struct Solution<const NX: usize, const NU: usize> {
    /// The final trajectory.
    pub trajectory: Trajectory<NX, NU>,
    /// The cost of the initial controls' rollout.
    pub initial_cost: f64,
    /// Every iteration, in order.
    pub iterations: Vec<Iteration>,
    /// Why the optimiser stopped.
    pub stop: Stop,
}

impl<const NX: usize, const NU: usize> Solution<NX, NU> {
    /// The cost of the final trajectory.
    pub fn cost(&self) -> f64 {
        self.iterations
            .last()
            .map_or(self.initial_cost, |iteration| iteration.cost)
    }

    /// The costs before the first iteration and after each one.
    pub fn cost_history(&self) -> Vec<f64> {
        std::iter::once(self.initial_cost)
            .chain(self.iterations.iter().map(|i| i.cost))
            .collect()
    }

    /// The timings summed over all iterations.
    pub fn total_timings(&self) -> Timings {
        self.iterations.iter().map(|i| i.timings).sum()
    }
}

impl Timings {
    /// Each phase's shorter time of two measurements of the same work.
    pub fn fastest(self, other: Timings) -> Timings {
        Timings {
            linearisation: self.linearisation.min(other.linearisation),
            derivative_kernels: self.derivative_kernels.min(other.derivative_kernels),
            derivative_kernel_calls: self.derivative_kernel_calls,
            backward_pass: self.backward_pass.min(other.backward_pass),
            forward_pass: self.forward_pass.min(other.forward_pass),
            total: self.total.min(other.total),
        }
    }
}

impl std::ops::Add for Timings {
    type Output = Timings;

    fn add(self, other: Timings) -> Timings {
        Timings {
            linearisation: self.linearisation + other.linearisation,
            derivative_kernels: self.derivative_kernels + other.derivative_kernels,
            derivative_kernel_calls: self.derivative_kernel_calls + other.derivative_kernel_calls,
            backward_pass: self.backward_pass + other.backward_pass,
            forward_pass: self.forward_pass + other.forward_pass,
            total: self.total + other.total,
        }
    }
}

impl std::iter::Sum for Timings {
    fn sum<I: Iterator<Item = Timings>>(iter: I) -> Timings {
        iter.fold(Timings::default(), |sum, t| sum + t)
    }
}

/// μ and its rate Δ (Tassa, Erez & Todorov 2012, section II-F): on failure
/// Δ ← max(Δ₀, Δ Δ₀), μ ← max(μ_min, μ Δ); on success Δ ← min(1/Δ₀, Δ/Δ₀),
/// μ ← μ Δ, or 0 when that falls below μ_min.
#[derive(Clone, Copy, Debug)]
struct Regularisation {
    mu: f64,
    rate: f64,
}

impl Regularisation {
    fn increase(&mut self, options: &Options) {
        let factor = options.regularisation_factor;
        self.rate = factor.max(self.rate * factor);
        self.mu = options.min_regularisation.max(self.mu * self.rate);
    }

    fn decrease(&mut self, options: &Options) {
        let factor = options.regularisation_factor;
        self.rate = (1.0 / factor).min(self.rate / factor);
        let mu = self.mu * self.rate;
        self.mu = if mu > options.min_regularisation {
            mu
        } else {
            0.0
        };
    }
}

/// Minimises the problem's cost from `initial_controls` (clamped into the bounds first).
pub fn solve<D: Discretisation<NX, NU>, const NX: usize, const NU: usize>(
    problem: &Problem<'_, D, NX, NU>,
    initial_controls: &[SVector<f64, NU>],
    options: &Options,
) -> Result<Solution<NX, NU>, Error> {
    check(problem, initial_controls, options)?;
    let controls: Vec<_> = initial_controls
        .iter()
        .map(|u| problem.bounds.clamp(u))
        .collect();
    let trajectory = Trajectory {
        states: rollout(problem.dynamics, &problem.initial_state, &controls)
            .ok_or(Error::DivergentInitialRollout)?,
        controls,
    };
    let initial_cost = problem.cost.total(&trajectory.states, &trajectory.controls);
    let mut search = Search {
        warm_start: vec![SVector::zeros(); trajectory.controls.len()],
        trajectory,
        cost: initial_cost,
        regularisation: Regularisation {
            mu: options.initial_regularisation,
            rate: 1.0,
        },
        linearisation: None,
        iterations: Vec::new(),
    };
    let stop = (0..options.max_iterations)
        .find_map(|_| search.iterate(problem, options))
        .unwrap_or(Stop::IterationLimit);
    Ok(Solution {
        trajectory: search.trajectory,
        initial_cost,
        iterations: search.iterations,
        stop,
    })
}

/// The optimisation between iterations: the current trajectory and its cost, the
/// regularisation, the dynamics' Jacobians along the trajectory (until it changes), the
/// feedforward of the last backward pass (its next warm start) and the iterations so far.
struct Search<const NX: usize, const NU: usize> {
    trajectory: Trajectory<NX, NU>,
    cost: f64,
    regularisation: Regularisation,
    linearisation: Option<Linearisation<NX, NU>>,
    warm_start: Vec<SVector<f64, NU>>,
    iterations: Vec<Iteration>,
}

impl<const NX: usize, const NU: usize> Search<NX, NU> {
    /// One iteration (Tassa, Erez & Todorov 2012, section II): the backward pass at the
    /// current regularisation, then the line search; `Some` with the reason when the
    /// optimiser stops.
    fn iterate<D: Discretisation<NX, NU>>(
        &mut self,
        problem: &Problem<'_, D, NX, NU>,
        options: &Options,
    ) -> Option<Stop> {
        let started = Instant::now();
        let mut timings = Timings::default();
        let mu = self.regularisation.mu;
        let at = (started, mu);
        let Ok(gains) = self.gains(problem, &mut timings) else {
            self.record(at, None, 0.0, self.cost, timings);
            return self.increase(options);
        };
        self.warm_start.clone_from(&gains.feedforward);
        if gains.relative_step(&self.trajectory.controls) < options.step_tolerance
            && mu < options.converged_regularisation
        {
            self.record(at, None, gains.expected_reduction(1.0), self.cost, timings);
            return Some(Stop::StepConverged);
        }
        let start = Instant::now();
        let accepted = line_search(problem, &self.trajectory, &gains, self.cost, options);
        timings.forward_pass = start.elapsed();
        let Some((alpha, next, next_cost)) = accepted else {
            self.record(at, None, gains.expected_reduction(1.0), self.cost, timings);
            return self.increase(options);
        };
        let reduction = gains.expected_reduction(alpha);
        self.record(at, Some(alpha), reduction, next_cost, timings);
        let reduction = self.cost - next_cost;
        self.trajectory = next;
        self.cost = next_cost;
        self.linearisation = None;
        self.regularisation.decrease(options);
        (reduction < options.cost_tolerance * self.cost.abs()).then_some(Stop::CostConverged)
    }

    /// The backward pass's gains along the current trajectory at the current
    /// regularisation, linearising the dynamics first when the trajectory has changed; the
    /// time each step takes goes to `timings`.
    fn gains<D: Discretisation<NX, NU>>(
        &mut self,
        problem: &Problem<'_, D, NX, NU>,
        timings: &mut Timings,
    ) -> Result<Gains<NX, NU>, NotPositiveDefinite> {
        let trajectory = &self.trajectory;
        let jacobians = self.linearisation.get_or_insert_with(|| {
            let start = Instant::now();
            let l = problem
                .dynamics
                .linearise(&trajectory.states, &trajectory.controls);
            timings.linearisation = start.elapsed();
            timings.derivative_kernels = l.derivative_kernels;
            timings.derivative_kernel_calls = l.derivative_kernel_calls;
            l
        });
        let start = Instant::now();
        let gains = backward_pass(
            jacobians,
            &trajectory.states,
            &trajectory.controls,
            problem.cost,
            &problem.bounds,
            self.regularisation.mu,
            &self.warm_start,
        );
        timings.backward_pass = start.elapsed();
        gains
    }

    /// Records an iteration started at `at.0` with regularisation `at.1`: its step (`None`
    /// when none was taken), the reduction its gains predicted, the cost after it and where
    /// its time went.
    fn record(
        &mut self,
        (started, mu): (Instant, f64),
        step: Option<f64>,
        expected_reduction: f64,
        cost: f64,
        mut timings: Timings,
    ) {
        timings.total = started.elapsed();
        self.iterations.push(Iteration {
            cost,
            step,
            regularisation: mu,
            expected_reduction,
            timings,
        });
    }

    /// Raises the regularisation after a failed iteration; `Some` when it passes its limit.
    fn increase(&mut self, options: &Options) -> Option<Stop> {
        self.regularisation.increase(options);
        (self.regularisation.mu > options.max_regularisation).then_some(Stop::RegularisationLimit)
    }
}

/// The first step α of the line search whose rollout of
/// u_k = clamp(ū_k + α k_k + K_k (x_k − x̄_k)) lowers the cost by more than
/// [`Options::acceptance`] times the predicted reduction (Tassa, Erez & Todorov 2012,
/// section II-G), with that trajectory and its cost.
fn line_search<D: Discretisation<NX, NU>, const NX: usize, const NU: usize>(
    problem: &Problem<'_, D, NX, NU>,
    current: &Trajectory<NX, NU>,
    gains: &Gains<NX, NU>,
    cost: f64,
    options: &Options,
) -> Option<(f64, Trajectory<NX, NU>, f64)> {
    options.line_search.iter().find_map(|&alpha| {
        let expected = gains.expected_reduction(alpha);
        if expected <= 0.0 {
            return None;
        }
        let candidate = feedback_rollout(problem, current, gains, alpha)?;
        let candidate_cost = problem.cost.total(&candidate.states, &candidate.controls);
        ((cost - candidate_cost) / expected > options.acceptance).then_some((
            alpha,
            candidate,
            candidate_cost,
        ))
    })
}

/// The trajectory of the policy u_k = clamp(ū_k + α k_k + K_k (x_k − x̄_k)); `None` when it
/// leaves the finite numbers.
fn feedback_rollout<D: Discretisation<NX, NU>, const NX: usize, const NU: usize>(
    problem: &Problem<'_, D, NX, NU>,
    current: &Trajectory<NX, NU>,
    gains: &Gains<NX, NU>,
    alpha: f64,
) -> Option<Trajectory<NX, NU>> {
    let steps = current.controls.len();
    let mut states = Vec::with_capacity(steps + 1);
    let mut controls = Vec::with_capacity(steps);
    let mut x = problem.initial_state;
    states.push(x);
    for k in 0..steps {
        let u = problem.bounds.clamp(
            &(current.controls[k]
                + gains.feedforward[k] * alpha
                + gains.feedback[k] * (x - current.states[k])),
        );
        x = problem.dynamics.step(&x, &u);
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
        states.push(x);
        controls.push(u);
    }
    Some(Trajectory { states, controls })
}

/// The states of the open-loop controls from x₀; `None` when they leave the finite numbers.
fn rollout<D: Discretisation<NX, NU>, const NX: usize, const NU: usize>(
    dynamics: &D,
    initial_state: &SVector<f64, NX>,
    controls: &[SVector<f64, NU>],
) -> Option<Vec<SVector<f64, NX>>> {
    let mut states = vec![*initial_state];
    let mut x = *initial_state;
    for u in controls {
        x = dynamics.step(&x, u);
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
        states.push(x);
    }
    Some(states)
}

/// The problem and options make sense: a horizon, finite ordered bounds that the optimiser can
/// keep, a finite initial state, a usable schedule.
fn check<D, const NX: usize, const NU: usize>(
    problem: &Problem<'_, D, NX, NU>,
    initial_controls: &[SVector<f64, NU>],
    options: &Options,
) -> Result<(), Error> {
    if initial_controls.is_empty() {
        return Err(Error::EmptyHorizon);
    }
    let bounds = &problem.bounds;
    if let Some(index) = (0..NU).find(|&i| {
        let (lo, hi) = (bounds.lower[i], bounds.upper[i]);
        !(lo.is_finite() && hi.is_finite() && lo <= hi)
    }) {
        return Err(Error::InvalidBounds {
            control: index,
            lower: bounds.lower[index],
            upper: bounds.upper[index],
        });
    }
    if !problem.initial_state.iter().all(|x| x.is_finite()) {
        return Err(Error::NonFiniteInitialState);
    }
    let valid = options.regularisation_factor > 1.0
        && options.acceptance > 0.0
        && options.acceptance < 1.0
        && !options.line_search.is_empty()
        && options.line_search.iter().all(|&a| a > 0.0 && a <= 1.0);
    if !valid {
        return Err(Error::InvalidOptions);
    }
    Ok(())
}
