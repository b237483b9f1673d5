//! The small real-number trait that expressions are evaluated in and generated kernels are
//! generic over, and [`OrderedReal`] for the scalars among them that are one ordered number.

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A real scalar, or several evaluated together: what the generic (`scalar: generic`) kernels
/// and the evaluation of expression graphs need. Implemented for `f32`, `f64`,
/// [`DoubleDouble`](crate::DoubleDouble) and, with the feature `simd`, the lane types
/// `F64x4` and `F32x8`, whose every operation acts lane by lane.
///
/// Lanes cannot be ordered, so `Real` has no comparison: what kernels need of one
/// ([`Real::abs`], [`Real::sign`]) is a method here, and code that compares values asks for
/// [`OrderedReal`].
pub trait Real:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
{
    /// The value nearest to `x` (in every lane).
    fn from_f64(x: f64) -> Self;
    /// `(sin self, cos self)`.
    fn sin_cos(self) -> (Self, Self);
    /// Square root.
    fn sqrt(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// The sign: 1 for positive values, −1 for negative ones, the value itself for ±0 and
    /// NaN (so sign(0) = 0, as Coulomb friction wants of a joint at rest).
    fn sign(self) -> Self;
    /// `(sin xᵢ, cos xᵢ)` of every element (bit for bit [`Real::sin_cos`] of each); the
    /// kernels call it once for all joint angles, which lets `f64` use vector instructions.
    fn sin_cos_array<const N: usize>(x: &[Self; N]) -> ([Self; N], [Self; N]) {
        let pairs = x.map(Self::sin_cos);
        (pairs.map(|p| p.0), pairs.map(|p| p.1))
    }
    /// `self · a + b`: what kernels generated with `fma: true` compute their products and
    /// sums with. Rounded once (one fused instruction) where the scalar type has fused
    /// multiply-add on the target — `f64`, `f32` and the lanes on x86-64 with the `fma`
    /// target feature (`-C target-cpu=native` on any x86-64 since 2013, or
    /// `-C target-feature=+fma`) — else a product and a sum, never slower than the two.
    #[inline]
    fn mul_add(self, a: Self, b: Self) -> Self {
        self * a + b
    }
    /// Sine.
    fn sin(self) -> Self {
        self.sin_cos().0
    }
    /// Cosine.
    fn cos(self) -> Self {
        self.sin_cos().1
    }
    /// Zero.
    fn zero() -> Self {
        Self::from_f64(0.0)
    }
    /// One.
    fn one() -> Self {
        Self::from_f64(1.0)
    }
}

/// A [`Real`] that is one number, not lanes: ordered, and convertible to `f64`. Implemented
/// for `f32`, `f64` and [`DoubleDouble`](crate::DoubleDouble).
pub trait OrderedReal: Real + PartialOrd {
    /// The `f64` nearest to `self`.
    fn to_f64(self) -> f64;
}

/// [`Real::sign`] of one ordered number.
#[inline]
pub(crate) fn sign_of<T: Real + PartialOrd>(x: T) -> T {
    if x > T::zero() {
        T::one()
    } else if x < T::zero() {
        -T::one()
    } else {
        x
    }
}

impl Real for f64 {
    #[inline]
    fn from_f64(x: f64) -> f64 {
        x
    }
    /// [`crate::trig::sin_cos`]: within 1 ulp on the joint-angle ranges of robots, branch-free
    /// there, and inlined into the kernels.
    #[inline]
    fn sin_cos(self) -> (f64, f64) {
        crate::trig::sin_cos(self)
    }
    #[inline]
    fn sin_cos_array<const N: usize>(x: &[f64; N]) -> ([f64; N], [f64; N]) {
        crate::trig::sin_cos_array(x)
    }
    #[inline]
    fn sqrt(self) -> f64 {
        crate::float::sqrt(self)
    }
    #[inline]
    fn mul_add(self, a: f64, b: f64) -> f64 {
        crate::float::mul_add(self, a, b)
    }
    /// The sign bit cleared.
    #[inline]
    fn abs(self) -> f64 {
        f64::from_bits(self.to_bits() & !(1 << 63))
    }
    #[inline]
    fn sign(self) -> f64 {
        sign_of(self)
    }
}

impl OrderedReal for f64 {
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
}

impl Real for f32 {
    #[inline]
    fn from_f64(x: f64) -> f32 {
        x as f32
    }
    /// Through the `f64` [`crate::trig::sin_cos`], rounded once to `f32`.
    #[inline]
    fn sin_cos(self) -> (f32, f32) {
        let (s, c) = crate::trig::sin_cos(self as f64);
        (s as f32, c as f32)
    }
    /// Through the vectorised `f64` [`crate::trig::sin_cos_array`], each rounded once to `f32`.
    #[inline]
    fn sin_cos_array<const N: usize>(x: &[f32; N]) -> ([f32; N], [f32; N]) {
        let (s, c) = crate::trig::sin_cos_array(&x.map(f64::from));
        (s.map(|v| v as f32), c.map(|v| v as f32))
    }
    /// The `f64` root rounded to `f32`: correctly rounded, since 53 ≥ 2·24 + 2 bits make
    /// the double rounding innocuous.
    #[inline]
    fn sqrt(self) -> f32 {
        crate::float::sqrt(f64::from(self)) as f32
    }
    #[inline]
    fn mul_add(self, a: f32, b: f32) -> f32 {
        crate::float::mul_add_f32(self, a, b)
    }
    /// The sign bit cleared.
    #[inline]
    fn abs(self) -> f32 {
        f32::from_bits(self.to_bits() & !(1 << 31))
    }
    #[inline]
    fn sign(self) -> f32 {
        sign_of(self)
    }
}

impl OrderedReal for f32 {
    #[inline]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
}

#[cfg(test)]
mod tests {
    use super::Real;
    use crate::DoubleDouble;

    #[test]
    fn signs_are_one_minus_one_or_the_zero_itself() {
        fn check<T: Real + PartialOrd>(from: impl Fn(f64) -> T) {
            for (x, expected) in [(2.5, 1.0), (1e-30, 1.0), (-0.1, -1.0), (-7e20, -1.0)] {
                assert!(from(x).sign() == from(expected), "sign({x})");
            }
            assert!(from(0.0).sign() == from(0.0));
            assert!(
                from(f64::NAN).sign() != from(f64::NAN).sign(),
                "NaN stays NaN"
            );
        }
        check(|x| x);
        check(|x| x as f32);
        check(DoubleDouble::from_f64);
        assert_eq!((-0.0f64).sign().to_bits(), (-0.0f64).to_bits());
    }

    #[test]
    fn absolute_values_clear_the_sign() {
        for x in [-3.5, 3.5, -0.0, 0.0, f64::NEG_INFINITY, -1e-310] {
            assert_eq!(Real::abs(x).to_bits(), x.abs().to_bits(), "|{x}|");
            let single = x as f32;
            assert_eq!(Real::abs(single).to_bits(), single.abs().to_bits(), "|{x}|");
        }
        assert_eq!(Real::abs(DoubleDouble::from_f64(-2.0)).hi(), 2.0);
    }

    #[test]
    fn f32_square_roots_are_correctly_rounded() {
        // Every 997th positive finite f32, subnormals included.
        for bits in (0..0x7f80_0000_u32).step_by(997) {
            let v = f32::from_bits(bits);
            assert_eq!(Real::sqrt(v).to_bits(), v.sqrt().to_bits(), "sqrt({v:e})");
        }
    }

    #[test]
    fn f32_arrays_give_the_scalar_results_bit_for_bit() {
        let xs: [f32; 7] = [0.3, -2.0, 7.5, 1e3, -0.0, 3.0e5, f32::NAN];
        let (s, c) = Real::sin_cos_array(&xs);
        for (i, &x) in xs.iter().enumerate() {
            let (es, ec) = Real::sin_cos(x);
            let same = |a: f32, b: f32| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
            assert!(same(s[i], es) && same(c[i], ec), "sin_cos({x})");
        }
        assert!(s[0] > 0.29 && c[0] > 0.95, "the values are those of 0.3");
    }
}
