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

use rne_codegen::{DoubleDouble, Kernel};

use super::sample::StateRef;
use crate::interpreted::Interpreted;

/// A floating-point format, for errors in ulps.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Format {
    /// IEEE binary64: 53-bit significands.
    F64,
    /// IEEE binary32: 24-bit significands.
    F32,
}

impl Format {
    /// The spacing of the format's numbers at |x|: 2^(e − p + 1) for 2^e ≤ |x| < 2^(e+1) and
    /// p significand bits, and the smallest subnormal for x below the normal range (or zero).
    pub fn ulp(self, x: f64) -> f64 {
        let (bits, min_exponent) = match self {
            Format::F64 => (53, -1022),
            Format::F32 => (24, -126),
        };
        let x = x.abs();
        let exponent = if x > 0.0 && x.is_finite() {
            exponent_of(x).max(min_exponent)
        } else {
            min_exponent
        };
        power_of_two(exponent - bits + 1)
    }

    /// The unit roundoff 2^−p (half an ulp at 1).
    pub fn unit_roundoff(self) -> f64 {
        self.ulp(1.0) / 2.0
    }
}

/// 2^k exactly, for k from −1074 (the smallest subnormal) to 1023; `powi` rounds the
/// reciprocal of 2^1074 to zero.
fn power_of_two(k: i32) -> f64 {
    if k >= -1022 {
        f64::from_bits(((k + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (k + 1074))
    }
}

/// e with 2^e ≤ x < 2^(e+1), for finite x > 0.
fn exponent_of(x: f64) -> i32 {
    let biased = ((x.to_bits() >> 52) & 0x7ff) as i32;
    if biased == 0 {
        // Subnormal: scale into the normal range first.
        exponent_of(x * 2f64.powi(64)) - 64
    } else {
        biased - 1023
    }
}

/// The error of one result.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Error {
    /// Normwise relative error.
    pub relative: f64,
    /// Error in ulps of the largest exact component.
    pub ulps: f64,
}

/// The error of `result` against `exact` (see the module documentation); NaN when a value is
/// not finite or the lengths differ.
pub fn error(result: &[f64], exact: &[DoubleDouble], format: Format) -> Error {
    if result.len() != exact.len() {
        return Error {
            relative: f64::NAN,
            ulps: f64::NAN,
        };
    }
    let mut difference = 0.0f64;
    let mut size = 0.0f64;
    for (&a, &x) in result.iter().zip(exact) {
        let d = (DoubleDouble::from_f64(a) - x).to_f64().abs();
        if d.is_nan() || d > difference {
            difference = d;
        }
        size = size.max(x.to_f64().abs());
        if difference.is_nan() {
            break;
        }
    }
    Error {
        relative: if size > 0.0 {
            difference / size
        } else {
            difference
        },
        ulps: difference / format.ulp(size),
    }
}

/// The exact value of `kernel` of `program`'s model at `state` (the program in double-double).
pub fn exact(program: &Interpreted, kernel: Kernel, state: StateRef<'_>) -> Vec<DoubleDouble> {
    let dd = |v: &[f64]| -> Vec<DoubleDouble> { v.iter().map(|&x| x.into()).collect() };
    program.eval_in(
        kernel,
        &dd(state.q),
        &dd(state.qd),
        &dd(state.qdd),
        &dd(state.tau),
    )
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
    pub fn of(errors: &[Error]) -> ErrorSummary {
        let sorted = |f: fn(&Error) -> f64| -> Vec<f64> {
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

    /// ulps follow the binade of the value in each format.
    #[test]
    fn ulps() {
        assert_eq!(Format::F64.ulp(1.0), f64::EPSILON);
        assert_eq!(Format::F64.ulp(1.5), f64::EPSILON);
        assert_eq!(Format::F64.ulp(2.0), 2.0 * f64::EPSILON);
        assert_eq!(Format::F64.ulp(-0.75), f64::EPSILON / 2.0);
        assert_eq!(Format::F32.ulp(1.0), f64::from(f32::EPSILON));
        assert_eq!(Format::F32.ulp(100.0), 64.0 * f64::from(f32::EPSILON));
        assert_eq!(Format::F64.ulp(0.0), f64::from_bits(1));
        assert_eq!(Format::F64.ulp(1e-310), f64::from_bits(1));
        assert_eq!(Format::F64.ulp(f64::MIN_POSITIVE), f64::from_bits(1));
        assert_eq!(Format::F64.unit_roundoff(), f64::EPSILON / 2.0);
    }

    /// The difference is exact, so an error below an f64 ulp of the result is seen.
    #[test]
    fn errors_against_double_double() {
        let third = DoubleDouble::from_f64(1.0) / DoubleDouble::from_f64(3.0);
        let e = error(&[1.0 / 3.0], &[third], Format::F64);
        assert!(e.relative > 0.0 && e.relative < f64::EPSILON, "{e:?}");
        assert!(e.ulps > 0.0 && e.ulps <= 0.5, "{e:?}");
        let exact = [DoubleDouble::from_f64(4.0), DoubleDouble::from_f64(-8.0)];
        let e = error(&[4.0, -8.0 + 8.0 * f64::EPSILON], &exact, Format::F64);
        assert_eq!(e.relative, f64::EPSILON);
        assert_eq!(e.ulps, 1.0);
        assert!(error(&[f64::NAN, 1.0], &exact, Format::F64)
            .relative
            .is_nan());
        assert!(error(&[1.0], &exact, Format::F64).relative.is_nan());
        let summary = ErrorSummary::of(&[
            Error {
                relative: 1e-16,
                ulps: 0.5,
            },
            Error {
                relative: 3e-16,
                ulps: 1.5,
            },
            Error {
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
