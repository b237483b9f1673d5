//! Errors against the double-double value of the same model.
//!
//! The exact value of a kernel is its optimised straight-line program (the one
//! `derive_dynamics!` emits, [`Interpreted`]) evaluated in [`DoubleDouble`] arithmetic: about
//! 32 significant digits, so its own error (≈ 1e-31 relative, more only where the program
//! itself cancels that many digits) is far below any `f64` rounding error. The constants of the
//! program are the `f64` numbers the generator folded, so the measure isolates the rounding
//! error of each implementation's arithmetic from the (shared) rounding of the model data.
//!
//! For a result `a` and the exact value `x` (vectors, or matrices read row by row), the
//! difference `a − x` is formed in double-double (so it carries no rounding of its own), and
//! - the **normwise relative error** is ‖a − x‖∞ / ‖x‖∞ (the absolute error when x = 0);
//! - the **error in ulps** is ‖a − x‖∞ / ulp(‖x‖∞): the error in units in the last place of the
//!   result's largest component, in the implementation's own format (`f64` or `f32`). An
//!   implementation that rounds its result's largest component correctly and nothing else
//!   scores at most 0.5.
//!
//! Both are [`Deviation::between`], shared with the stress report.

use rne_codegen::{DoubleDouble, Kernel};
use rne_figures::Deviation;
use rne_interpreted::{Interpreted, StateRef};

/// The exact value of `kernel` of `program`'s model at `state` (the program in double-double).
pub fn exact(program: &Interpreted, kernel: Kernel, state: StateRef<'_>) -> Vec<DoubleDouble> {
    let dd = |v: &[f64]| -> Vec<DoubleDouble> { v.iter().map(|&x| x.into()).collect() };
    let (q, qd, qdd, tau) = (dd(state.q), dd(state.qd), dd(state.qdd), dd(state.tau));
    let state = StateRef {
        q: &q,
        qd: &qd,
        qdd: &qdd,
        tau: &tau,
    };
    program.eval(kernel, state).unwrap_or_default()
}

/// Errors over a sample: the largest and the median.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ErrorSummary {
    /// Number of states.
    pub states: usize,
    /// Largest normwise relative error (NaN if any error is NaN).
    pub max_relative: f64,
    /// Median normwise relative error.
    pub median_relative: f64,
    /// Largest error in ulps.
    pub max_ulps: f64,
    /// Median error in ulps.
    pub median_ulps: f64,
}

impl ErrorSummary {
    /// Summarises `errors` (NaN sorts above every number, so a NaN error is the maximum).
    pub fn of(errors: &[Deviation]) -> ErrorSummary {
        let sorted = |f: fn(&Deviation) -> f64| -> Vec<f64> {
            let mut v: Vec<f64> = errors.iter().map(f).map(f64::abs).collect();
            v.sort_by(f64::total_cmp);
            v
        };
        let relative = sorted(|e| e.relative);
        let ulps = sorted(|e| e.ulps);
        let max = |v: &[f64]| v.last().copied().unwrap_or(f64::NAN);
        let median = |v: &[f64]| v.get(v.len() / 2).copied().unwrap_or(f64::NAN);
        ErrorSummary {
            states: errors.len(),
            max_relative: max(&relative),
            median_relative: median(&relative),
            max_ulps: max(&ulps),
            median_ulps: median(&ulps),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The summary gives the largest and the (upper) median of each measure.
    #[test]
    fn summary_of_errors() {
        let summary = ErrorSummary::of(&[
            Deviation {
                relative: 1e-16,
                ulps: 0.5,
            },
            Deviation {
                relative: 3e-16,
                ulps: 1.5,
            },
            Deviation {
                relative: 2e-16,
                ulps: 1.0,
            },
        ]);
        assert_eq!(summary.max_relative, 3e-16);
        assert_eq!(summary.median_relative, 2e-16);
        assert_eq!(summary.max_ulps, 1.5);
        assert_eq!(summary.states, 3);
    }
}
