//! The error measures every report uses: units in the last place, and the normwise relative
//! error of a computed vector (a matrix read row by row) against its value.
//!
//! For a result `c` with value `e`, the normwise relative error is ‖c − e‖∞ / ‖e‖∞ (Higham,
//! *Accuracy and Stability of Numerical Algorithms*, 2nd ed., §1.2), the absolute error when
//! e = 0: it does not blow up on components that are small only because of cancellation in
//! the value, and it is what a user of τ, M or q̈ sees as "digits lost". The error in ulps is
//! ‖c − e‖∞ / ulp(‖e‖∞): 0.5 for a correctly rounded largest component, and the number of
//! representable steps the worst component is off, at the scale of the largest one.

use rne_runtime::DoubleDouble;

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
    /// p significand bits, the smallest subnormal below the normal range (and for zero), NaN
    /// for non-finite x.
    pub fn ulp(self, x: f64) -> f64 {
        let (bits, min_exponent) = match self {
            Format::F64 => (53, -1022),
            Format::F32 => (24, -126),
        };
        let x = x.abs();
        if !x.is_finite() {
            return f64::NAN;
        }
        let exponent = if x > 0.0 {
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

/// The unit in the last place of |x| in `f64`: the gap between |x| and the next larger double
/// (2⁻¹⁰⁷⁴ for zero and subnormals, NaN for non-finite x).
pub fn ulp(x: f64) -> f64 {
    Format::F64.ulp(x)
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

/// Normwise relative error ‖a − b‖∞ / ‖b‖∞ of `a` against `b` in `f64` (absolute when b is
/// zero).
pub fn relative_error(a: &[f64], b: &[f64]) -> f64 {
    let (diff, scale) = (max_difference(a, b), max_magnitude(b));
    if scale > 0.0 {
        diff / scale
    } else {
        diff
    }
}

/// ‖a − b‖∞ / max(‖b‖∞, floor): [`relative_error`], absolute (in units of `floor`) where `b`
/// is smaller than `floor`: for quantities that can vanish, where the reference holds only
/// rounding noise.
pub fn relative_error_floor(a: &[f64], b: &[f64], floor: f64) -> f64 {
    max_difference(a, b) / max_magnitude(b).max(floor)
}

/// max |aᵢ − bᵢ|.
fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// max |bᵢ|.
fn max_magnitude(b: &[f64]) -> f64 {
    b.iter().map(|y| y.abs()).fold(0.0, f64::max)
}

/// The error of one result against its double-double value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Deviation {
    /// Normwise relative error (the absolute error when the value is zero).
    pub relative: f64,
    /// The error in ulps of the value's largest component, in the result's format.
    pub ulps: f64,
}

impl Deviation {
    /// The error of `computed` (in `format`) against `exact`. The difference is formed in
    /// double-double, so it carries no rounding of its own. NaN when a value is not finite or
    /// the lengths differ; for a zero value the error in ulps is 0 or infinite.
    pub fn between(computed: &[f64], exact: &[DoubleDouble], format: Format) -> Deviation {
        let finite = computed.iter().all(|c| c.is_finite()) && exact.iter().all(|e| e.is_finite());
        if !finite || computed.len() != exact.len() {
            return Deviation {
                relative: f64::NAN,
                ulps: f64::NAN,
            };
        }
        let difference = computed
            .iter()
            .zip(exact)
            .map(|(&c, &e)| (DoubleDouble::from_f64(c) - e).abs().to_f64())
            .fold(0.0, f64::max);
        let scale = exact.iter().map(|e| e.abs().to_f64()).fold(0.0, f64::max);
        if scale > 0.0 {
            Deviation {
                relative: difference / scale,
                ulps: difference / format.ulp(scale),
            }
        } else {
            Deviation {
                relative: difference,
                ulps: if difference == 0.0 {
                    0.0
                } else {
                    f64::INFINITY
                },
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ulps follow the binade of the value in each format.
    #[test]
    fn ulps_follow_the_binade() {
        assert_eq!(Format::F64.ulp(1.0), f64::EPSILON);
        assert_eq!(Format::F64.ulp(1.5), f64::EPSILON);
        assert_eq!(Format::F64.ulp(2.0), 2.0 * f64::EPSILON);
        assert_eq!(Format::F64.ulp(-0.75), f64::EPSILON / 2.0);
        assert_eq!(Format::F32.ulp(1.0), f64::from(f32::EPSILON));
        assert_eq!(Format::F32.ulp(100.0), 64.0 * f64::from(f32::EPSILON));
        assert_eq!(ulp(0.0), f64::from_bits(1));
        assert_eq!(ulp(1e-310), f64::from_bits(1));
        assert_eq!(ulp(f64::MIN_POSITIVE), f64::from_bits(1));
        assert_eq!(
            ulp(f64::MAX),
            f64::MAX - f64::from_bits(f64::MAX.to_bits() - 1)
        );
        assert!(ulp(f64::INFINITY).is_nan());
        assert_eq!(Format::F64.unit_roundoff(), f64::EPSILON / 2.0);
    }

    /// The difference is exact, so an error below an f64 ulp of the result is seen; NaN,
    /// lengths and zero values are handled.
    #[test]
    fn deviation_against_double_double() {
        let third = DoubleDouble::from_f64(1.0) / DoubleDouble::from_f64(3.0);
        let e = Deviation::between(&[1.0 / 3.0], &[third], Format::F64);
        assert!(e.relative > 0.0 && e.relative < f64::EPSILON, "{e:?}");
        assert!(e.ulps > 0.0 && e.ulps <= 0.5, "{e:?}");
        let exact = [DoubleDouble::from_f64(4.0), DoubleDouble::from_f64(-8.0)];
        let e = Deviation::between(&[4.0, -8.0 + 8.0 * f64::EPSILON], &exact, Format::F64);
        assert_eq!(e.relative, f64::EPSILON);
        assert_eq!(e.ulps, 1.0);
        assert!(Deviation::between(&[f64::NAN, 1.0], &exact, Format::F64)
            .relative
            .is_nan());
        assert!(Deviation::between(&[1.0], &exact, Format::F64)
            .relative
            .is_nan());
        let zero = [DoubleDouble::from_f64(0.0)];
        assert_eq!(Deviation::between(&[0.0], &zero, Format::F64).ulps, 0.0);
        assert_eq!(
            Deviation::between(&[1e-300], &zero, Format::F64).ulps,
            f64::INFINITY
        );
    }

    /// The f64 relative error is normwise and absolute against a zero value.
    #[test]
    fn relative_error_is_normwise() {
        assert_eq!(relative_error(&[1.0, 2.5], &[1.0, 2.0]), 0.25);
        assert_eq!(relative_error(&[1e-3], &[0.0]), 1e-3);
    }

    /// Below the floor the error is measured against the floor.
    #[test]
    fn the_floor_bounds_the_scale_from_below() {
        assert_eq!(relative_error_floor(&[1.0, 2.5], &[1.0, 2.0], 1.0), 0.25);
        assert_eq!(relative_error_floor(&[1.0, 2.5], &[1.0, 2.0], 5.0), 0.1);
        assert_eq!(relative_error_floor(&[1e-3], &[0.0], 1e-2), 0.1);
    }
}
