//! Double-double arithmetic: about 32 significant digits from a pair of `f64`.
//!
//! A [`DoubleDouble`] is the unevaluated sum `hi + lo` of two doubles with
//! `|lo| ≤ ulp(hi)/2`: 106 significant bits. It is the high-precision reference scalar of the
//! project (a [`Real`]): generated kernels and expression graphs evaluated in it carry about
//! 31–32 correct digits, against which `f64` kernels are measured.
//!
//! Everything rests on three error-free transformations, which return a rounded result
//! together with its exact rounding error:
//! - `two_sum` (Knuth; Møller 1965) for any two doubles,
//! - `fast_two_sum` (Dekker 1971) when the first operand is the larger in magnitude,
//! - `two_prod` (Dekker 1971), from Veltkamp's splitting (`core` has no fused
//!   multiply–add).
//!
//! See Shewchuk, "Adaptive precision floating-point arithmetic and fast robust geometric
//! predicates", Discrete Comput. Geom. 18 (1997). The double-double operations follow the QD
//! library (Hida, Li, Bailey, "Algorithms for quad-double precision floating point
//! arithmetic", ARITH-15, 2001) in the forms analysed by Joldes, Muller and Popescu, "Tight
//! and rigorous error bounds for basic building blocks of double-word arithmetic", ACM TOMS
//! 44(2), 2017 (JMP below).
//!
//! # Accuracy
//!
//! With u = 2⁻⁵³ (u² ≈ 1.23·10⁻³²), the relative errors checked by this module's tests
//! against exact expansion arithmetic, on random operands including heavy cancellation (the
//! largest errors seen over 300 000 operand pairs were 1.96u², 3.30u², 1.84u² and 2.87u²):
//!
//! | operation | algorithm | bound checked |
//! |-----------|-----------|---------------|
//! | `+`, `−`  | JMP Algorithm 6 (proved ≤ 3u² + 13u³) | 3u² |
//! | `×`       | JMP Algorithm 12, the cross terms without fused multiply–adds | 5u² |
//! | `÷`       | QD's three-quotient division | 3u² |
//! | `sqrt`    | one Newton step from the `f64` root | 4u² |
//!
//! `sin_cos` reduces its argument by π/2 held as three doubles (about 165 bits) and sums
//! Taylor series. For |x| ≤ 2⁵² (≈ 4.5·10¹⁵) the absolute error of sin and cos is below
//! 10⁻³¹, and the relative error below 8u² wherever the result is not tiny (tested from
//! 10⁻¹⁰ to 10¹⁵ against mpmath). Beyond 2⁵² the result is the `f64`
//! [`sin_cos`](crate::sin_cos) of `hi` alone (within 1 ulp for that double), the low part
//! ignored. Printing gives 32 significant digits
//! by default, the last one possibly off by one.
//!
//! # Special values
//!
//! Infinities and NaN behave as in `f64`: an operation whose `f64` counterpart on the high
//! parts would be infinite or NaN returns that value (with `lo = 0`); `sin` and `cos` of an
//! infinity are NaN; nothing panics or loops.

use core::cmp::Ordering;
use core::fmt;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use crate::eft::{fast_two_sum, two_prod, two_sum};
use crate::float;
use crate::real::{OrderedReal, Real};

/// A real number `hi + lo` held as two `f64` with `|lo| ≤ ulp(hi)/2`: about 32 significant
/// decimal digits (see the module documentation for the error bounds).
#[derive(Copy, Clone, Debug, Default)]
pub struct DoubleDouble {
    hi: f64,
    lo: f64,
}

/// π/2 as three doubles P₀ + P₁ + P₂ (from mpmath at 400 bits; the remainder is 5.6·10⁻⁵⁰).
const HALF_PI: [f64; 3] = [
    core::f64::consts::FRAC_PI_2,
    6.123233995736766e-17,
    -1.4973849048591698e-33,
];

/// Largest |x| whose quadrant count k = round(x / (π/2)) is exact in `f64`; beyond it
/// `sin_cos` falls back to `f64`.
const REDUCTION_LIMIT: f64 = 4_503_599_627_370_496.0;

impl DoubleDouble {
    /// Zero.
    pub const ZERO: DoubleDouble = DoubleDouble { hi: 0.0, lo: 0.0 };
    /// One.
    pub const ONE: DoubleDouble = DoubleDouble { hi: 1.0, lo: 0.0 };
    /// Not a number.
    pub const NAN: DoubleDouble = DoubleDouble {
        hi: f64::NAN,
        lo: 0.0,
    };
    /// u² = 2⁻¹⁰⁶, the unit roundoff of double-double arithmetic.
    pub const UNIT_ROUNDOFF: f64 = 1.232595164407831e-32;

    /// The double `x` exactly.
    #[inline]
    pub const fn from_f64(x: f64) -> DoubleDouble {
        DoubleDouble { hi: x, lo: 0.0 }
    }

    /// `hi + lo` (any two doubles), renormalised so that `|lo| ≤ ulp(hi)/2`.
    #[inline]
    pub fn from_parts(hi: f64, lo: f64) -> DoubleDouble {
        let (s, e) = two_sum(hi, lo);
        DoubleDouble { hi: s, lo: e }.or_f64(hi + lo)
    }

    /// The high part: the `f64` nearest to the value.
    #[inline]
    pub fn hi(self) -> f64 {
        self.hi
    }

    /// The low part: the value minus `hi`.
    #[inline]
    pub fn lo(self) -> f64 {
        self.lo
    }

    /// The `f64` nearest to the value.
    #[inline]
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    /// Whether the value is neither infinite nor NaN.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.hi.is_finite()
    }

    /// Whether the value is NaN.
    #[inline]
    pub fn is_nan(self) -> bool {
        self.hi.is_nan()
    }

    /// Absolute value.
    #[inline]
    pub fn abs(self) -> DoubleDouble {
        if self.hi < 0.0 {
            -self
        } else {
            self
        }
    }

    /// `self^n` by repeated squaring (about log₂|n| roundings of ≤ 5u² each).
    pub fn powi(self, n: i32) -> DoubleDouble {
        let mut result = DoubleDouble::ONE;
        let mut base = self;
        let mut m = n.unsigned_abs();
        while m > 0 {
            if m & 1 == 1 {
                result *= base;
            }
            m >>= 1;
            if m > 0 {
                base *= base;
            }
        }
        if n < 0 {
            DoubleDouble::ONE / result
        } else {
            result
        }
    }

    /// Square root: one Newton step `y + (a − y²)/(2y)` from the `f64` root y, with `a − y²`
    /// computed exactly in double-double (`y²` is exact by `two_prod`) — the formulation of
    /// Karp and Markstein, as in QD. NaN for negative input, `sqrt(±0) = ±0`, `sqrt(∞) = ∞`.
    pub fn sqrt(self) -> DoubleDouble {
        if self.hi == 0.0 || !self.hi.is_finite() || self.hi < 0.0 {
            return DoubleDouble::from_f64(float::sqrt(self.hi));
        }
        let y = float::sqrt(self.hi);
        let (square_hi, square_lo) = two_prod(y, y);
        let residual = self
            - DoubleDouble {
                hi: square_hi,
                lo: square_lo,
            };
        DoubleDouble::from_f64(y).add_f64(residual.hi / (2.0 * y))
    }

    /// `(sin x, cos x)`.
    ///
    /// The argument is reduced to r = x − k π/2 with |r| ≤ π/4 (π/2 as three doubles; each
    /// product k·Pᵢ is exact by `two_prod`, and the subtractions are double-double), after
    /// which sin r and cos r are summed from their Taylor series until the terms fall below
    /// 2⁻¹¹⁰ of the sum. Accurate to 10⁻³¹ absolute for |x| ≤ 2⁵²; beyond, `f64` accuracy
    /// (see the module documentation). NaN for infinite or NaN x.
    pub fn sin_cos(self) -> (DoubleDouble, DoubleDouble) {
        if !self.hi.is_finite() {
            return (DoubleDouble::NAN, DoubleDouble::NAN);
        }
        if self.hi.abs() > REDUCTION_LIMIT {
            let (s, c) = crate::trig::sin_cos(self.hi);
            return (DoubleDouble::from_f64(s), DoubleDouble::from_f64(c));
        }
        let mut k = float::round(self.hi * core::f64::consts::FRAC_2_PI);
        let mut r = self.minus_half_pi_times(k);
        if r.hi.abs() > core::f64::consts::FRAC_PI_4 {
            // The f64 estimate of k can be off by one for large |x|.
            let correction = float::round(r.hi * core::f64::consts::FRAC_2_PI);
            r = r.minus_half_pi_times(correction);
            k += correction;
        }
        let (s, c) = r.taylor_sin_cos();
        // |k| ≤ 2⁵² · 2/π: an exact integer.
        match (k as i64).rem_euclid(4) {
            0 => (s, c),
            1 => (c, -s),
            2 => (-s, -c),
            _ => (-c, s),
        }
    }

    /// The first `digits` (1 to [`MAX_DIGITS`]) decimal digits of a positive finite value,
    /// rounded, and its decimal exponent.
    fn decimal_digits(self, digits: usize) -> (Digits, i32) {
        let mut exponent = float::floor_log10_estimate(self.hi);
        let mut y = if exponent > 0 {
            self / DoubleDouble::from_f64(10.0).powi(exponent)
        } else if exponent < -300 {
            self * DoubleDouble::from_f64(10.0).powi(300)
                * DoubleDouble::from_f64(10.0).powi(-exponent - 300)
        } else {
            self * DoubleDouble::from_f64(10.0).powi(-exponent)
        };
        if y.hi >= 10.0 {
            y = y.div_f64(10.0);
            exponent += 1;
        } else if y.hi < 1.0 {
            y = y.mul_f64(10.0);
            exponent -= 1;
        }
        // Two spare digits: one may be lost to a leading zero, one decides the rounding.
        let mut d = Digits::default();
        for _ in 0..digits + 2 {
            let mut digit = float::floor(y.hi);
            if digit == y.hi && y.lo < 0.0 {
                digit -= 1.0;
            }
            d.push(digit as i32);
            y = (y - DoubleDouble::from_f64(digit)).mul_f64(10.0);
        }
        d.carry();
        if d.as_slice()[0] == 0 {
            d.remove_first();
            exponent -= 1;
        }
        let round_up = d.as_slice()[digits] >= 5;
        d.truncate(digits);
        if round_up {
            d.digits[digits - 1] += 1;
            d.carry();
        }
        if d.digits[0] >= 10 {
            d.digits[0] -= 10;
            d.insert_first(1);
            d.truncate(digits);
            exponent += 1;
        }
        (d, exponent)
    }

    /// `self − k π/2` for an integer-valued `k`.
    fn minus_half_pi_times(self, k: f64) -> DoubleDouble {
        HALF_PI.iter().fold(self, |r, &p| {
            let (hi, lo) = two_prod(k, p);
            r - DoubleDouble { hi, lo }
        })
    }

    /// `(sin r, cos r)` for |r| ≤ π/4 (a little more is harmless) by Taylor series.
    fn taylor_sin_cos(self) -> (DoubleDouble, DoubleDouble) {
        let r2 = self * self;
        let series = |first: DoubleDouble, first_power: f64| {
            let mut sum = first;
            let mut term = first;
            let mut n = first_power;
            for _ in 0..40 {
                term = -(term * r2).div_f64((n + 1.0) * (n + 2.0));
                n += 2.0;
                sum += term;
                if term.hi.abs() <= TAYLOR_CUTOFF * sum.hi.abs() {
                    break;
                }
            }
            sum
        };
        (series(self, 1.0), series(DoubleDouble::ONE, 0.0))
    }

    /// `self + y` for a double y (JMP Algorithm 4, ≤ 2u²).
    #[inline]
    fn add_f64(self, y: f64) -> DoubleDouble {
        let (sh, sl) = two_sum(self.hi, y);
        let v = self.lo + sl;
        let (hi, lo) = fast_two_sum(sh, v);
        DoubleDouble { hi, lo }.or_f64(self.hi + y)
    }

    /// `self · y` for a double y (JMP Algorithm 9, its fused multiply–add as two roundings).
    #[inline]
    fn mul_f64(self, y: f64) -> DoubleDouble {
        let (ch, cl1) = two_prod(self.hi, y);
        let cl3 = self.lo * y + cl1;
        let (hi, lo) = fast_two_sum(ch, cl3);
        DoubleDouble { hi, lo }.or_f64(self.hi * y)
    }

    /// `self / y` for a double y (JMP Algorithm 15).
    #[inline]
    fn div_f64(self, y: f64) -> DoubleDouble {
        let th = self.hi / y;
        if !th.is_finite() || !y.is_finite() {
            return DoubleDouble::from_f64(th);
        }
        let (ph, pl) = two_prod(th, y);
        let delta = ((self.hi - ph) - pl) + self.lo;
        let (hi, lo) = fast_two_sum(th, delta / y);
        DoubleDouble { hi, lo }.or_f64(th)
    }

    /// `self · y` as `*` computes it (JMP Algorithm 12), given the exact product of the high
    /// parts, `(p, e)` with `p = fl(self.hi · y.hi)` and `p + e = self.hi · y.hi`: for a
    /// caller that forms it faster, e.g. `e = fma(self.hi, y.hi, −p)` where the processor has
    /// a fused multiply–add. An exact `e` gives the bits of `self * y`.
    #[inline]
    pub fn mul_given_product(self, y: DoubleDouble, (ch, cl1): (f64, f64)) -> DoubleDouble {
        let tl1 = self.hi * y.lo + self.lo * y.lo;
        let cl2 = self.lo * y.hi + tl1;
        let (hi, lo) = fast_two_sum(ch, cl1 + cl2);
        DoubleDouble { hi, lo }.or_f64(self.hi * y.hi)
    }

    /// `self` if finite, else `naive` (the `f64` result of the operation on the high parts),
    /// so that infinities and NaN come out as in `f64`.
    #[inline]
    fn or_f64(self, naive: f64) -> DoubleDouble {
        if self.hi.is_finite() {
            self
        } else {
            DoubleDouble::from_f64(naive)
        }
    }
}

/// 2⁻¹¹⁰: the Taylor series stop once a term falls below this fraction of the sum.
const TAYLOR_CUTOFF: f64 = 7.703_719_777_548_943e-34;

/// The most significant digits printing gives.
pub const MAX_DIGITS: usize = 40;

/// Decimal digits in a fixed buffer (printing allocates nothing), most significant first;
/// entries may leave 0..=9 transiently during rounding.
#[derive(Clone, Copy)]
struct Digits {
    digits: [i32; MAX_DIGITS + 2],
    len: usize,
}

impl Default for Digits {
    fn default() -> Digits {
        Digits {
            digits: [0; MAX_DIGITS + 2],
            len: 0,
        }
    }
}

impl Digits {
    fn as_slice(&self) -> &[i32] {
        &self.digits[..self.len]
    }

    fn push(&mut self, d: i32) {
        self.digits[self.len] = d;
        self.len += 1;
    }

    fn truncate(&mut self, len: usize) {
        self.len = self.len.min(len);
    }

    fn remove_first(&mut self) {
        self.digits.copy_within(1..self.len, 0);
        self.len -= 1;
    }

    /// Puts `d` in front (the last digit is dropped if the buffer is full).
    fn insert_first(&mut self, d: i32) {
        let kept = self.len.min(MAX_DIGITS + 1);
        self.digits.copy_within(0..kept, 1);
        self.digits[0] = d;
        self.len = kept + 1;
    }

    /// Moves out-of-range digits (from rounding in the digit loop) into their neighbours.
    fn carry(&mut self) {
        let d = &mut self.digits[..self.len];
        for i in (1..d.len()).rev() {
            while d[i] < 0 {
                d[i] += 10;
                d[i - 1] -= 1;
            }
            while d[i] > 9 {
                d[i] -= 10;
                d[i - 1] += 1;
            }
        }
    }
}

impl From<f64> for DoubleDouble {
    #[inline]
    fn from(x: f64) -> DoubleDouble {
        DoubleDouble::from_f64(x)
    }
}

impl Add for DoubleDouble {
    type Output = DoubleDouble;
    /// JMP Algorithm 6 ("AccurateDWPlusDW"): relative error ≤ 3u² + 13u³.
    #[inline]
    fn add(self, y: DoubleDouble) -> DoubleDouble {
        let (sh, sl) = two_sum(self.hi, y.hi);
        let (th, tl) = two_sum(self.lo, y.lo);
        let (vh, vl) = fast_two_sum(sh, sl + th);
        let (hi, lo) = fast_two_sum(vh, tl + vl);
        DoubleDouble { hi, lo }.or_f64(self.hi + y.hi)
    }
}

impl Sub for DoubleDouble {
    type Output = DoubleDouble;
    #[inline]
    fn sub(self, y: DoubleDouble) -> DoubleDouble {
        self + -y
    }
}

impl Mul for DoubleDouble {
    type Output = DoubleDouble;
    /// JMP Algorithm 12 ("DWTimesDW3"): the exact product of the high parts plus the cross
    /// terms (accumulated with a multiplication and an addition where JMP fuse them; `core`
    /// has no fused multiply–add).
    #[inline]
    fn mul(self, y: DoubleDouble) -> DoubleDouble {
        self.mul_given_product(y, two_prod(self.hi, y.hi))
    }
}

impl Div for DoubleDouble {
    type Output = DoubleDouble;
    /// QD's accurate division: three successive quotient digits q₁ + q₂ + q₃, each from the
    /// remainder of the previous ones.
    #[inline]
    fn div(self, y: DoubleDouble) -> DoubleDouble {
        let q1 = self.hi / y.hi;
        if !q1.is_finite() || !y.hi.is_finite() || q1 == 0.0 {
            return DoubleDouble::from_f64(q1);
        }
        let r = self - y.mul_f64(q1);
        let q2 = r.hi / y.hi;
        let r = r - y.mul_f64(q2);
        let q3 = r.hi / y.hi;
        let (hi, lo) = fast_two_sum(q1, q2);
        DoubleDouble { hi, lo }.add_f64(q3).or_f64(q1)
    }
}

impl Neg for DoubleDouble {
    type Output = DoubleDouble;
    #[inline]
    fn neg(self) -> DoubleDouble {
        DoubleDouble {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl AddAssign for DoubleDouble {
    #[inline]
    fn add_assign(&mut self, y: DoubleDouble) {
        *self = *self + y;
    }
}

impl SubAssign for DoubleDouble {
    #[inline]
    fn sub_assign(&mut self, y: DoubleDouble) {
        *self = *self - y;
    }
}

impl MulAssign for DoubleDouble {
    #[inline]
    fn mul_assign(&mut self, y: DoubleDouble) {
        *self = *self * y;
    }
}

impl DivAssign for DoubleDouble {
    #[inline]
    fn div_assign(&mut self, y: DoubleDouble) {
        *self = *self / y;
    }
}

impl PartialEq for DoubleDouble {
    #[inline]
    fn eq(&self, other: &DoubleDouble) -> bool {
        self.hi == other.hi && self.lo == other.lo
    }
}

impl PartialOrd for DoubleDouble {
    /// Compares the high parts, then the low parts (the representation is normalised, so
    /// this is the order of the values). `None` when either is NaN.
    #[inline]
    fn partial_cmp(&self, other: &DoubleDouble) -> Option<Ordering> {
        match self.hi.partial_cmp(&other.hi)? {
            Ordering::Equal => self.lo.partial_cmp(&other.lo),
            unequal => Some(unequal),
        }
    }
}

impl fmt::Display for DoubleDouble {
    /// Scientific notation with the formatter's precision as the number of significant
    /// digits (1 to [`MAX_DIGITS`], about 32 meaningful), 32 by default:
    /// `format!("{:.5}", x)` gives `3.1416e0`; `NaN`, `inf`, `-inf` for the special values.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let digits = f.precision().unwrap_or(32).clamp(1, MAX_DIGITS);
        if self.hi.is_nan() {
            return f.write_str("NaN");
        }
        if self.hi.is_sign_negative() {
            f.write_str("-")?;
        }
        if self.hi.is_infinite() {
            return f.write_str("inf");
        }
        let (mantissa, exponent) = if self.hi == 0.0 {
            let mut zeros = Digits::default();
            (0..digits).for_each(|_| zeros.push(0));
            (zeros, 0)
        } else {
            self.abs().decimal_digits(digits)
        };
        for (i, d) in mantissa.as_slice().iter().enumerate() {
            if i == 1 {
                f.write_str(".")?;
            }
            fmt::Write::write_char(f, char::from(b'0' + *d as u8))?;
        }
        write!(f, "e{exponent}")
    }
}

impl Real for DoubleDouble {
    #[inline]
    fn from_f64(x: f64) -> DoubleDouble {
        DoubleDouble::from_f64(x)
    }
    fn sin_cos(self) -> (DoubleDouble, DoubleDouble) {
        DoubleDouble::sin_cos(self)
    }
    #[inline]
    fn sqrt(self) -> DoubleDouble {
        DoubleDouble::sqrt(self)
    }
    #[inline]
    fn abs(self) -> DoubleDouble {
        DoubleDouble::abs(self)
    }
    #[inline]
    fn sign(self) -> DoubleDouble {
        crate::real::sign_of(self)
    }
}

impl OrderedReal for DoubleDouble {
    #[inline]
    fn to_f64(self) -> f64 {
        DoubleDouble::to_f64(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::format;
    use std::string::{String, ToString};
    use std::vec::Vec;

    /// `x` printed with `digits` significant digits.
    fn to_string_digits(x: DoubleDouble, digits: usize) -> String {
        format!("{x:.digits$}")
    }

    const U2: f64 = DoubleDouble::UNIT_ROUNDOFF;

    /// An exact sum of doubles as a nonoverlapping expansion, smallest component first
    /// (Shewchuk 1997, Grow-Expansion with zero elimination): the oracle the error bounds
    /// are checked against.
    #[derive(Default)]
    struct Expansion(Vec<f64>);

    impl Expansion {
        fn add(&mut self, b: f64) -> &mut Expansion {
            let mut q = b;
            let mut out = Vec::with_capacity(self.0.len() + 1);
            for &e in &self.0 {
                let (s, h) = two_sum(q, e);
                if h != 0.0 {
                    out.push(h);
                }
                q = s;
            }
            out.push(q);
            self.0 = out;
            self
        }

        fn add_dd(&mut self, x: DoubleDouble, sign: f64) -> &mut Expansion {
            self.add(sign * x.lo).add(sign * x.hi)
        }

        fn add_product(&mut self, x: DoubleDouble, y: DoubleDouble, sign: f64) -> &mut Expansion {
            for (a, b) in [(x.hi, y.hi), (x.hi, y.lo), (x.lo, y.hi), (x.lo, y.lo)] {
                let (p, e) = two_prod(a, b);
                self.add(sign * e).add(sign * p);
            }
            self
        }

        /// The value, to about one `f64` rounding.
        fn value(&self) -> f64 {
            self.0.iter().sum()
        }
    }

    fn dd(hi: f64, lo: f64) -> DoubleDouble {
        DoubleDouble::from_parts(hi, lo)
    }

    /// Random double-doubles with exponents in ±2⁴⁰ and a random low part.
    fn double_double() -> impl Strategy<Value = DoubleDouble> {
        (1.0f64..2.0, -40i32..40, any::<bool>(), -0.5f64..0.5).prop_map(
            |(m, e, negative, fraction)| {
                let hi = if negative { -m } else { m } * 2f64.powi(e);
                dd(hi, fraction * 2f64.powi(e - 52))
            },
        )
    }

    fn relative_error_of_sum(x: DoubleDouble, y: DoubleDouble) -> f64 {
        let sum = x + y;
        let exact = Expansion::default().add_dd(x, 1.0).add_dd(y, 1.0).value();
        let error = Expansion::default()
            .add_dd(sum, 1.0)
            .add_dd(x, -1.0)
            .add_dd(y, -1.0)
            .value();
        if exact == 0.0 {
            error.abs()
        } else {
            (error / exact).abs()
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        #[test]
        fn addition_is_within_3u2(x in double_double(), y in double_double()) {
            prop_assert!(relative_error_of_sum(x, y) <= 3.0 * U2);
            prop_assert!(relative_error_of_sum(x, -y) <= 3.0 * U2);
        }

        #[test]
        fn addition_with_cancellation_is_within_3u2(x in double_double(), y in double_double(), k in 0i32..110) {
            let nearly_minus_x = -x + y * DoubleDouble::from_f64(2f64.powi(-k));
            prop_assert!(relative_error_of_sum(x, nearly_minus_x) <= 3.0 * U2);
        }

        #[test]
        fn multiplication_is_within_5u2(x in double_double(), y in double_double()) {
            let product = x * y;
            let exact = Expansion::default().add_product(x, y, 1.0).value();
            let error = Expansion::default().add_dd(product, 1.0).add_product(x, y, -1.0).value();
            prop_assert!((error / exact).abs() <= 5.0 * U2, "{}", (error / exact).abs() / U2);
        }

        #[test]
        fn division_is_within_3u2(x in double_double(), y in double_double()) {
            // q = x/y (1 + δ) exactly when q y − x = δ x.
            let q = x / y;
            let residual = Expansion::default().add_product(q, y, 1.0).add_dd(x, -1.0).value();
            prop_assert!((residual / x.to_f64()).abs() <= 3.0 * U2, "{}", (residual / x.to_f64()).abs() / U2);
        }

        #[test]
        fn square_root_is_within_4u2(x in double_double()) {
            // s = √x (1 + δ) gives s² − x ≈ 2 δ x.
            let x = x.abs();
            let s = x.sqrt();
            let residual = Expansion::default().add_product(s, s, 1.0).add_dd(x, -1.0).value();
            prop_assert!((residual / (2.0 * x.to_f64())).abs() <= 4.0 * U2);
        }
    }

    #[test]
    fn one_third_times_three_is_one() {
        let third = DoubleDouble::ONE / DoubleDouble::from_f64(3.0);
        let one = third * DoubleDouble::from_f64(3.0);
        assert!((one - DoubleDouble::ONE).abs().to_f64() <= 1e-31);
        assert!(third.lo() != 0.0);
        assert_eq!(
            to_string_digits(third, 32),
            "3.3333333333333333333333333333333e-1"
        );
    }

    #[test]
    fn square_root_of_two_squares_to_two() {
        let two = DoubleDouble::from_f64(2.0);
        let root = two.sqrt();
        assert!((root * root - two).abs().to_f64() <= 4.0 * U2 * 2.0);
        // mpmath: sqrt(2) = 1.41421356237309504880168872420969807857
        assert_eq!(
            to_string_digits(root, 32),
            "1.4142135623730950488016887242097e0"
        );
        assert_eq!(DoubleDouble::from_f64(0.0).sqrt(), DoubleDouble::ZERO);
        assert_eq!(DoubleDouble::from_f64(1e-300).sqrt().to_f64(), 1e-150);
    }

    /// (x_hi, x_lo, (sin_hi, sin_lo), (cos_hi, cos_lo)).
    type Reference = (f64, f64, (f64, f64), (f64, f64));

    /// (x_hi, x_lo, (sin_hi, sin_lo), (cos_hi, cos_lo)) with the sine and cosine of the exact
    /// argument x_hi + x_lo rounded to double-double, computed with Python's mpmath at 400
    /// bits (`mp.prec = 400; hi = float(v); lo = float(v - mpf(hi))` for v = sin(x), cos(x)).
    // Some arguments and values are, bit for bit, std constants (π/4, π/2, 1/√2); they are
    // kept as printed by mpmath so that the table reads as the script's output.
    #[allow(clippy::approx_constant)]
    const REFERENCE: [Reference; 26] = [
        (
            0.1,
            0.0,
            (0.09983341664682815, 3.08001512929492e-18),
            (0.9950041652780258, -5.50210156918377e-17),
        ),
        (
            0.5,
            0.0,
            (0.479425538604203, -5.103969860556013e-18),
            (0.8775825618903728, -4.2623149864279997e-17),
        ),
        (
            -0.75,
            0.0,
            (-0.6816387600233341, -4.410467313197903e-17),
            (0.7316888688738209, -1.0475824306512768e-17),
        ),
        (
            0.7853981633974483,
            0.0,
            (0.7071067811865475, 4.1036934489363755e-17),
            (0.7071067811865476, -2.6687565161377232e-17),
        ),
        (
            1.0,
            0.0,
            (0.8414709848078965, 1.776845092935536e-18),
            (0.5403023058681398, -4.760954612604417e-17),
        ),
        (
            1.5707963267948966,
            0.0,
            (1.0, -1.874699728327322e-33),
            (6.123233995736766e-17, -1.4973849048591698e-33),
        ),
        (
            2.0,
            0.0,
            (0.9092974268256817, -1.4020906557816256e-17),
            (-0.4161468365471424, 1.990596398957495e-17),
        ),
        (
            -2.5,
            0.0,
            (-0.5984721441039565, 5.521403334082375e-17),
            (-0.8011436155469337, -1.8674742705085553e-17),
        ),
        (
            3.141592653589793,
            0.0,
            (1.2246467991473532e-16, -2.99476980971834e-33),
            (-1.0, 7.498798913309288e-33),
        ),
        (
            4.0,
            0.0,
            (-0.7568024953079282, -4.892224089158451e-17),
            (-0.6536436208636119, 2.5846614087018284e-17),
        ),
        (
            7.0,
            0.0,
            (0.6569865987187891, 2.937261786543214e-17),
            (0.7539022543433046, 3.728245359710072e-17),
        ),
        (
            10.0,
            0.0,
            (-0.5440211108893698, -3.8949898668223557e-17),
            (-0.8390715290764524, -1.4147119988953418e-17),
        ),
        (
            100.0,
            0.0,
            (-0.5063656411097588, -3.050947053792115e-18),
            (0.8623188722876839, 4.334809858136501e-17),
        ),
        (
            1000.5,
            0.0,
            (0.9952739571052135, 5.1293231726011145e-17),
            (0.09710690144438526, 3.9534046844460945e-18),
        ),
        (
            1000.0,
            0.0,
            (0.8268795405320025, 3.867581909641312e-17),
            (0.5623790762907029, 5.1611423543848204e-17),
        ),
        (
            12345.678,
            0.0,
            (-0.7040813137533816, -1.9646969196301474e-17),
            (0.7101193587160628, -2.4815747415365305e-17),
        ),
        (
            1000000.0,
            0.0,
            (-0.34999350217129294, -1.5952848809323968e-17),
            (0.9367521275331447, 4.637088260214747e-17),
        ),
        (
            -1000000.25,
            0.0,
            (0.10735686657997945, -6.704237685268381e-19),
            (0.9942205505812725, -2.4564732493524537e-17),
        ),
        (
            1e9,
            0.0,
            (0.5458434494486996, 6.1757333566640775e-18),
            (0.8378871813639024, -5.4718713289282437e-17),
        ),
        (
            1e12,
            0.0,
            (-0.6112387023768895, -1.1491613964488177e-17),
            (0.7914463018528902, 4.843622374857678e-17),
        ),
        (
            1e15,
            0.0,
            (0.8582727931702359, -2.372639689262412e-17),
            (-0.5131937377869703, 5.3179977268261675e-17),
        ),
        (
            1e-10,
            0.0,
            (1e-10, -1.6666666666666669e-31),
            (1.0, -5.0000000000000005e-21),
        ),
        (
            3.141592653589793,
            1.2246467991473532e-16,
            (-2.9947698097183397e-33, 1.1124542208633653e-49),
            (-1.0, 4.4843231066002096e-66),
        ),
        (
            1.5707963267948966,
            6.123233995736766e-17,
            (1.0, -1.1210807766500524e-66),
            (-1.4973849048591698e-33, 5.562271104316826e-50),
        ),
        (
            1000000.0,
            1e-11,
            (-0.34999350216192543, -1.4477746206560629e-18),
            (0.9367521275366447, 3.3074178878568244e-18),
        ),
        (
            0.5,
            1e-20,
            (0.479425538604203, -5.095194034937109e-18),
            (0.8775825618903728, -4.262794411966604e-17),
        ),
    ];

    #[test]
    fn sine_and_cosine_match_mpmath_to_1e_31() {
        for (x_hi, x_lo, (s_hi, s_lo), (c_hi, c_lo)) in REFERENCE {
            let (s, c) = dd(x_hi, x_lo).sin_cos();
            for (got, hi, lo, what) in [(s, s_hi, s_lo, "sin"), (c, c_hi, c_lo, "cos")] {
                let error = (got - dd(hi, lo)).abs().to_f64();
                assert!(error <= 1e-31, "{what}({x_hi} + {x_lo}): error {error:e}");
                // Relative accuracy where the value is not tiny, and up to x = 1e6 also where it is.
                if hi.abs() > 1e-3 || x_hi.abs() <= 1e6 && hi.abs() > 1e-20 {
                    assert!(
                        error <= 8.0 * U2 * hi.abs(),
                        "{what}({x_hi} + {x_lo}): relative {:e}",
                        error / hi.abs()
                    );
                }
            }
        }
    }

    #[test]
    fn pythagoras_holds_to_1e_30_over_a_grid() {
        let mut arguments: Vec<DoubleDouble> = (-400..=400)
            .map(|k| dd(f64::from(k) * 0.137, f64::from(k) * 1e-19))
            .collect();
        arguments.extend([1e3, 1e6, -1e6, 3.7e9, 1e12, 4.5e15].map(DoubleDouble::from_f64));
        for x in arguments {
            let (s, c) = x.sin_cos();
            let defect = (s * s + c * c - DoubleDouble::ONE).abs().to_f64();
            assert!(defect <= 1e-30, "x = {x}: {defect:e}");
        }
    }

    #[test]
    fn sine_is_odd_and_periodic_in_double_double() {
        let two_pi = dd(HALF_PI[0], HALF_PI[1]).mul_f64(4.0);
        for k in 1..50 {
            let x = dd(f64::from(k) * 0.61, 1e-18);
            let (s, c) = x.sin_cos();
            let (sn, cn) = (-x).sin_cos();
            assert_eq!(sn, -s);
            assert_eq!(cn, c);
            // x + 2π is rounded; sin(x + 2π + δ) = sin x + δ cos x + O(δ²).
            let shifted = x + two_pi;
            let delta = (shifted - x - two_pi).to_f64();
            let (sp, _) = shifted.sin_cos();
            let error = (sp - s - c.mul_f64(delta)).abs().to_f64();
            assert!(error <= 2e-31, "k = {k}: {error:e}");
        }
    }

    #[test]
    fn arguments_beyond_the_reduction_limit_fall_back_to_f64() {
        for x in [1e16, -3e20, 1e300, f64::MAX] {
            let (s, c) = DoubleDouble::from_f64(x).sin_cos();
            assert_eq!((s.to_f64(), c.to_f64()), crate::sin_cos(x));
        }
    }

    #[test]
    fn special_values_propagate_as_in_f64() {
        let (inf, nan, one) = (
            DoubleDouble::from_f64(f64::INFINITY),
            DoubleDouble::NAN,
            DoubleDouble::ONE,
        );
        let zero = DoubleDouble::ZERO;
        assert_eq!(one / zero, inf);
        assert_eq!(-one / zero, -inf);
        assert!((zero / zero).is_nan());
        assert_eq!(one / inf, zero);
        assert!((inf / inf).is_nan());
        assert_eq!(inf + one, inf);
        assert!((inf - inf).is_nan());
        assert_eq!(inf * DoubleDouble::from_f64(2.0), inf);
        assert!((inf * zero).is_nan());
        assert_eq!(inf.sqrt(), inf);
        assert!(DoubleDouble::from_f64(-1.0).sqrt().is_nan());
        assert!(nan.sqrt().is_nan());
        let big = DoubleDouble::from_f64(f64::MAX);
        assert_eq!(big + big, inf);
        assert_eq!(big * big, inf);
        for x in [inf, -inf, nan] {
            let (s, c) = x.sin_cos();
            assert!(s.is_nan() && c.is_nan());
            assert!((x + one).to_f64().is_nan() == x.is_nan());
        }
        assert!(nan != nan && nan.partial_cmp(&one).is_none());
        assert_eq!(nan.to_string(), "NaN");
        assert_eq!(inf.to_string(), "inf");
        assert_eq!((-inf).to_string(), "-inf");
        assert_eq!(dd(f64::INFINITY, 1.0), inf);
    }

    #[test]
    fn order_uses_the_low_part() {
        let one = DoubleDouble::ONE;
        let slightly_more = dd(1.0, 1e-20);
        assert!(slightly_more > one);
        assert!(one < slightly_more);
        assert!(-slightly_more < -one);
        assert_eq!(
            slightly_more.partial_cmp(&slightly_more),
            Some(Ordering::Equal)
        );
        assert_eq!(slightly_more.to_f64(), 1.0);
    }

    #[test]
    fn printing_gives_rounded_significant_digits() {
        // mpmath: the double-double pi = 3.141592653589793238462643383279505878967...
        let pi = dd(core::f64::consts::PI, 1.2246467991473532e-16);
        assert_eq!(pi.to_string(), "3.1415926535897932384626433832795e0");
        assert_eq!(format!("{pi:.5}"), "3.1416e0");
        assert_eq!(to_string_digits(-pi, 3), "-3.14e0");
        let two_thirds = DoubleDouble::from_f64(2.0) / DoubleDouble::from_f64(3.0);
        assert_eq!(to_string_digits(two_thirds, 5), "6.6667e-1");
        assert_eq!(
            to_string_digits(DoubleDouble::from_f64(9.9999), 3),
            "1.00e1"
        );
        assert_eq!(
            to_string_digits(DoubleDouble::from_f64(1e300), 4),
            "1.000e300"
        );
        assert_eq!(
            to_string_digits(
                DoubleDouble::from_f64(1e-300) / DoubleDouble::from_f64(3.0),
                6
            ),
            "3.33333e-301"
        );
        assert_eq!(
            to_string_digits(DoubleDouble::from_f64(5e-324), 2),
            "4.9e-324"
        );
        assert_eq!(to_string_digits(DoubleDouble::ZERO, 3), "0.00e0");
        assert_eq!(to_string_digits(DoubleDouble::from_f64(12345.0), 1), "1e4");
        assert_eq!(
            to_string_digits(DoubleDouble::from_f64(0.1), 40),
            "1.000000000000000055511151231257827021182e-1"
        );
    }

    #[test]
    fn powers_and_assign_operators() {
        let ten = DoubleDouble::from_f64(10.0);
        assert_eq!(ten.powi(22).to_f64(), 1e22);
        assert_eq!(
            to_string_digits(ten.powi(-3), 32),
            "1.0000000000000000000000000000000e-3"
        );
        let mut x = DoubleDouble::from_f64(1.5);
        x += DoubleDouble::ONE;
        x -= DoubleDouble::from_f64(0.5);
        x *= DoubleDouble::from_f64(3.0);
        x /= DoubleDouble::from_f64(4.0);
        assert_eq!(x, DoubleDouble::from_f64(1.5));
    }

    #[test]
    fn is_a_real() {
        let generic_abs = <DoubleDouble as Real>::abs(DoubleDouble::from_f64(-2.0));
        assert_eq!(generic_abs, DoubleDouble::from_f64(2.0));
        assert_eq!(
            <DoubleDouble as Real>::sin(DoubleDouble::ZERO),
            DoubleDouble::ZERO
        );
    }
}
