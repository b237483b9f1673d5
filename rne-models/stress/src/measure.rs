//! Summaries of error measures over many states, and the condition numbers of M. The error of
//! one evaluation against its double-double value is [`rne_figures::Deviation`].
//!
//! For an output vector (a matrix is taken row-major) computed as `c` with exact value `e`,
//! the normwise relative error is ‖c − e‖∞ / ‖e‖∞ (Higham, *Accuracy and Stability of
//! Numerical Algorithms*, 2nd ed., §1.2): it does not blow up on components that are small
//! only because of cancellation in the exact value, and it is what a user of τ, M or q̈ sees
//! as "digits lost". The error in ulps is ‖c − e‖∞ / ulp(‖e‖∞): 0.5 for a correctly rounded
//! largest component, and the number of representable steps the worst component is off, at the
//! scale of the largest one.

use nalgebra::DMatrix;
use rne_codegen::Kernel;
use rne_figures::Deviation;

/// The machine epsilon of `f64`, 2⁻⁵² (the gap between 1 and the next double).
pub const EPSILON: f64 = f64::EPSILON;

/// The largest and the median of a sample of errors.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Spread {
    /// The largest value (NaN if any value is NaN).
    pub max: f64,
    /// The median (the upper one for an even count).
    pub median: f64,
    /// The number of values.
    pub count: usize,
}

impl Spread {
    /// The spread of `values` (zeros for an empty sample).
    pub fn of(values: impl IntoIterator<Item = f64>) -> Spread {
        let mut sorted: Vec<f64> = values.into_iter().collect();
        // NaN sorts last under the total order, so it shows as the maximum.
        sorted.sort_by(|a, b| a.abs().total_cmp(&b.abs()));
        Spread {
            max: sorted.last().copied().unwrap_or(0.0),
            median: sorted.get(sorted.len() / 2).copied().unwrap_or(0.0),
            count: sorted.len(),
        }
    }
}

/// The errors of one kernel over a set of states.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KernelErrors {
    /// Normwise relative errors.
    pub relative: Spread,
    /// Errors in ulps of the largest component.
    pub ulps: Spread,
}

impl KernelErrors {
    /// The summary of `deviations`.
    pub fn of(deviations: &[Deviation]) -> KernelErrors {
        KernelErrors {
            relative: Spread::of(deviations.iter().map(|d| d.relative)),
            ulps: Spread::of(deviations.iter().map(|d| d.ulps)),
        }
    }
}

/// The errors of several kernels over the same states.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ErrorsByKernel(pub Vec<(Kernel, KernelErrors)>);

impl ErrorsByKernel {
    /// The errors of `kernel`, if it was measured.
    pub fn get(&self, kernel: Kernel) -> Option<KernelErrors> {
        self.0.iter().find(|(k, _)| *k == kernel).map(|(_, e)| *e)
    }

    /// The largest relative error of `kernel` (NaN if it was not measured).
    pub fn max(&self, kernel: Kernel) -> f64 {
        self.get(kernel).map_or(f64::NAN, |e| e.relative.max)
    }

    /// The median relative error of `kernel` (NaN if it was not measured).
    pub fn median(&self, kernel: Kernel) -> f64 {
        self.get(kernel).map_or(f64::NAN, |e| e.relative.median)
    }

    /// The largest error of `kernel` in ulps (NaN if it was not measured).
    pub fn max_ulps(&self, kernel: Kernel) -> f64 {
        self.get(kernel).map_or(f64::NAN, |e| e.ulps.max)
    }
}

/// The spectral condition number λ_max / λ_min of a symmetric matrix given row-major with
/// `n` columns (infinite when it is singular or indefinite, NaN when not finite).
pub fn condition(m: &[f64], n: usize) -> f64 {
    if m.iter().any(|x| !x.is_finite()) {
        return f64::NAN;
    }
    let eigenvalues = DMatrix::from_row_slice(n, n, m).symmetric_eigenvalues();
    let (lo, hi) = (eigenvalues.min(), eigenvalues.max());
    if lo > 0.0 {
        hi / lo
    } else {
        f64::INFINITY
    }
}

/// The condition number of D^(−1/2) M D^(−1/2), D = diag(M): what is left of cond(M) once
/// the scaling of the joints is taken out. A factorisation of M is invariant under this
/// diagonal scaling (van der Sluis 1969; Higham, §7.3 and §10.1), so its rounding errors
/// follow this number rather than cond(M).
pub fn scaled_condition(m: &[f64], n: usize) -> f64 {
    let scale: Vec<f64> = (0..n).map(|i| m[i * n + i].sqrt()).collect();
    let scaled: Vec<f64> = m
        .iter()
        .enumerate()
        .map(|(k, x)| x / (scale[k / n] * scale[k % n]))
        .collect();
    condition(&scaled, n)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spread reports the maximum, the (upper) median, and NaN as the maximum.
    #[test]
    fn spread_max_and_median() {
        let s = Spread::of([3.0, 1.0, 2.0, 4.0]);
        assert_eq!((s.max, s.median, s.count), (4.0, 3.0, 4));
        assert!(Spread::of([1.0, f64::NAN]).max.is_nan());
        assert_eq!(Spread::of([]).count, 0);
    }

    /// cond(diag(1, 1e-8)) = 1e8, which diagonal scaling removes entirely.
    #[test]
    fn condition_numbers() {
        let m = [1.0, 0.0, 0.0, 1e-8];
        assert!((condition(&m, 2) - 1e8).abs() < 1.0);
        assert!((scaled_condition(&m, 2) - 1.0).abs() < 1e-12);
        assert_eq!(condition(&[1.0, 1.0, 1.0, 1.0], 2), f64::INFINITY);
    }
}
