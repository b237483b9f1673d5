//! Kernel work-precision: for one robot and each kernel of [`BENCHED`], every implementation's
//! time per call and its error against the exact (double-double) value.
//!
//! The errors are measured over the whole sample, state by state: each implementation is
//! evaluated on its case's inputs, the exact value of that case computed once per state and
//! kernel ([`Cases::exact`]), and [`Deviation::between`] compares them. The implementations of one kernel
//! are then timed together by [`time_interleaved`] on the first states of the sample (the
//! timing pool), so that their ratios come from the same rounds.

use rne_codegen::{DoubleDouble, Kernel};

use super::error::BenchError;
use super::implementation::{Case, Implementation};
use super::precision::ErrorSummary;
use super::robots::{subjects, Candidate, Cases, BENCHED};
use super::timing::{time_interleaved, Plan, Timed, Timing};
use rne_figures::Deviation;

/// One implementation of one kernel.
#[derive(Clone, Debug, PartialEq)]
pub struct KernelRow {
    /// The kernel.
    pub kernel: Kernel,
    /// The implementation.
    pub implementation: Implementation,
    /// Its time per call.
    pub timing: Timing,
    /// Its time relative to the generated `f64` kernel's, as the median of the per-round
    /// ratios ([`Timing::ratio_to`]).
    pub relative_time: f64,
    /// Its errors over the sample.
    pub errors: ErrorSummary,
}

/// Every kernel and implementation of one robot.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotKernels {
    /// The built-in robot's name.
    pub robot: &'static str,
    /// Its number of joints.
    pub dof: usize,
    /// One row per kernel and implementation, kernels in [`BENCHED`] order.
    pub rows: Vec<KernelRow>,
}

/// Measures every kernel of [`BENCHED`] for the robot of `cases`, timing on the first `pool`
/// states.
pub fn measure(cases: &Cases, plan: &Plan, pool: usize) -> Result<RobotKernels, BenchError> {
    let mut rows = Vec::new();
    for kernel in BENCHED {
        let mut candidates = subjects(kernel, cases, pool)?;
        let errors = errors(cases, kernel, &mut candidates);
        let timings = time(&mut candidates, plan);
        let generated = candidates
            .iter()
            .position(|c| c.implementation == Implementation::Generated);
        for ((candidate, timing), errors) in candidates.iter().zip(&timings).zip(errors) {
            rows.push(KernelRow {
                kernel,
                implementation: candidate.implementation,
                relative_time: generated.map_or(f64::NAN, |g| timing.ratio_to(&timings[g])),
                timing: timing.clone(),
                errors,
            });
        }
    }
    Ok(RobotKernels {
        robot: cases.robot.name,
        dof: cases.model.dof(),
        rows,
    })
}

/// The errors of each candidate of `kernel` over the whole sample of `cases`.
pub fn errors(
    cases: &Cases,
    kernel: Kernel,
    candidates: &mut [Candidate<'_>],
) -> Vec<ErrorSummary> {
    errors_with(|case, k| cases.exact(case, kernel, k), candidates)
}

/// The errors of each candidate over the states of its calls, against `exact(case, k)`, the
/// exact value for the candidate's case at state `k` (computed once per case and state).
pub fn errors_with(
    exact: impl Fn(Case, usize) -> Vec<DoubleDouble>,
    candidates: &mut [Candidate<'_>],
) -> Vec<ErrorSummary> {
    let states = candidates
        .iter()
        .map(|c| c.calls.states())
        .min()
        .unwrap_or(0);
    let mut errors: Vec<Vec<Deviation>> = vec![Vec::with_capacity(states); candidates.len()];
    let mut result = Vec::new();
    for k in 0..states {
        let mut values: [Option<Vec<DoubleDouble>>; 5] = Default::default();
        for (candidate, errors) in candidates.iter_mut().zip(&mut errors) {
            let case: Case = candidate.implementation.case();
            let x = values[case.index()].get_or_insert_with(|| exact(case, k));
            candidate.calls.evaluate(k, &mut result);
            errors.push(Deviation::between(
                &result,
                x,
                candidate.implementation.format(),
            ));
        }
    }
    errors.iter().map(|e| ErrorSummary::of(e)).collect()
}

/// Times the candidates together ([`time_interleaved`]).
pub fn time(candidates: &mut [Candidate<'_>], plan: &Plan) -> Vec<Timing> {
    let mut subjects: Vec<&mut dyn Timed> =
        candidates.iter_mut().map(|c| c as &mut dyn Timed).collect();
    time_interleaved(&mut subjects, plan)
}
