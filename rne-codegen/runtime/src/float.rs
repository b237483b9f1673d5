//! The `f64` operations the runtime needs that `core` does not provide (`sqrt`, `floor`,
//! `round`), implemented without the standard library.
//!
//! Each gives the bit pattern `std` gives: `sqrt` is correctly rounded (IEEE 754), `floor`
//! and `round` are exact by construction.

/// Bits of an `f64`'s significand field.
const FRACTION_BITS: u32 = 52;
/// Mask of the significand field.
const FRACTION_MASK: u64 = (1 << FRACTION_BITS) - 1;
/// The exponent bias.
const BIAS: i32 = 1023;

/// Correctly rounded square root, bit for bit `f64::sqrt`: NaN for negative arguments and
/// NaN, `sqrt(±0) = ±0`, `sqrt(∞) = ∞`. On x86_64 it is the SSE2 instruction; elsewhere
/// [`sqrt_software`].
#[inline]
pub fn sqrt(x: f64) -> f64 {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        use core::arch::x86_64::{_mm_cvtsd_f64, _mm_set_sd, _mm_sqrt_pd};
        // SAFETY: the intrinsics need SSE2, which this block is compiled only with (it is
        // part of the x86_64 baseline); they touch no memory.
        unsafe { _mm_cvtsd_f64(_mm_sqrt_pd(_mm_set_sd(x))) }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
    {
        sqrt_software(x)
    }
}

/// `x · y + z`: rounded once, by the fused multiply-add instruction, on x86-64 with the `fma`
/// target feature (bit for bit `f64::mul_add` there); elsewhere a product and a sum, each
/// rounded ([`Real::mul_add`](crate::Real::mul_add)).
#[inline]
pub fn mul_add(x: f64, y: f64, z: f64) -> f64 {
    #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
    {
        use core::arch::x86_64::{_mm_cvtsd_f64, _mm_fmadd_sd, _mm_set_sd};
        // SAFETY: the intrinsic needs FMA, which this block is compiled only with; the
        // intrinsics touch no memory.
        unsafe { _mm_cvtsd_f64(_mm_fmadd_sd(_mm_set_sd(x), _mm_set_sd(y), _mm_set_sd(z))) }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
    {
        x * y + z
    }
}

/// [`mul_add`] in `f32`.
#[inline]
pub fn mul_add_f32(x: f32, y: f32, z: f32) -> f32 {
    #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
    {
        use core::arch::x86_64::{_mm_cvtss_f32, _mm_fmadd_ss, _mm_set_ss};
        // SAFETY: as in `mul_add`.
        unsafe { _mm_cvtss_f32(_mm_fmadd_ss(_mm_set_ss(x), _mm_set_ss(y), _mm_set_ss(z))) }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
    {
        x * y + z
    }
}

/// Correctly rounded square root in integer arithmetic (the fallback of [`sqrt`] on targets
/// without a square-root instruction the runtime knows of).
///
/// With x = m·2ᵉ (m an integer, e even after moving one bit into m), √x = √(m·2⁵⁶)·2^(e/2−28);
/// the integer square root of m·2⁵⁶ has 55 bits, two more than the result, and its remainder
/// says whether anything was cut off, which rounds the result to nearest, ties to even.
// Unused where the instruction exists, but tested everywhere.
#[cfg_attr(all(target_arch = "x86_64", target_feature = "sse2"), allow(dead_code))]
pub fn sqrt_software(x: f64) -> f64 {
    if x.is_nan() || x < 0.0 {
        return f64::NAN;
    }
    if x == 0.0 || x == f64::INFINITY {
        return x;
    }
    let bits = x.to_bits();
    let biased = (bits >> FRACTION_BITS) as i32;
    // m · 2^e with m < 2⁵³ and, for normal numbers, m ≥ 2⁵².
    let (mut m, mut e) = if biased == 0 {
        (bits & FRACTION_MASK, 1 - BIAS - FRACTION_BITS as i32)
    } else {
        (
            (bits & FRACTION_MASK) | (1 << FRACTION_BITS),
            biased - BIAS - FRACTION_BITS as i32,
        )
    };
    // Normalise subnormals so that m ≥ 2⁵².
    let shift = m.leading_zeros() - (63 - FRACTION_BITS);
    m <<= shift;
    e -= shift as i32;
    if e % 2 != 0 {
        m <<= 1;
        e -= 1;
    }
    // m ∈ [2⁵², 2⁵⁴): m·2⁵⁶ ∈ [2¹⁰⁸, 2¹¹⁰), its root r ∈ [2⁵⁴, 2⁵⁵).
    let (root, remainder) = integer_sqrt(u128::from(m) << 56);
    let root = root as u64;
    let guard = root & 2 != 0;
    let sticky = root & 1 != 0 || remainder != 0;
    let mut significand = root >> 2;
    if guard && (sticky || significand & 1 != 0) {
        significand += 1;
    }
    // The value is significand · 2^(e/2 − 26) with significand ∈ [2⁵², 2⁵³].
    let mut exponent = e / 2 - 26;
    if significand == 1 << (FRACTION_BITS + 1) {
        significand >>= 1;
        exponent += 1;
    }
    let biased = (exponent + BIAS + FRACTION_BITS as i32) as u64;
    f64::from_bits((biased << FRACTION_BITS) | (significand & FRACTION_MASK))
}

/// `(⌊√n⌋, n − ⌊√n⌋²)`, one result bit per step (the digit-by-digit method).
fn integer_sqrt(n: u128) -> (u128, u128) {
    let mut remainder = n;
    let mut root: u128 = 0;
    // The largest power of four not above n.
    let mut bit: u128 = 1 << ((127 - n.leading_zeros()) & !1);
    while bit != 0 {
        if remainder >= root + bit {
            remainder -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    (root, remainder)
}

/// The largest integer not above `x`, bit for bit `f64::floor` (`-0.0` stays `-0.0`).
pub fn floor(x: f64) -> f64 {
    let t = trunc(x);
    if t > x {
        t - 1.0
    } else {
        t
    }
}

/// The nearest integer, halfway cases away from zero, bit for bit `f64::round`.
pub fn round(x: f64) -> f64 {
    let t = trunc(x);
    if (x - t).abs() >= 0.5 {
        t + 1.0_f64.copysign(x)
    } else {
        t
    }
}

/// `x` with its fractional bits cleared (rounding toward zero), keeping the sign of zero.
pub fn trunc(x: f64) -> f64 {
    let bits = x.to_bits();
    let exponent = ((bits >> FRACTION_BITS) & 0x7ff) as i32 - BIAS;
    if exponent >= FRACTION_BITS as i32 {
        // Already an integer, or infinite or NaN.
        return x;
    }
    if exponent < 0 {
        return 0.0_f64.copysign(x);
    }
    let fraction = FRACTION_MASK >> exponent;
    f64::from_bits(bits & !fraction)
}

/// ⌊log₁₀ x⌋ or one less, for finite x > 0 (from the binary exponent: with
/// x ∈ [2ᵇ, 2ᵇ⁺¹), ⌊b·log₁₀ 2⌋ ≤ log₁₀ x < ⌊b·log₁₀ 2⌋ + 2).
pub fn floor_log10_estimate(x: f64) -> i32 {
    let bits = x.to_bits();
    let biased = (bits >> FRACTION_BITS) as i32;
    let binary_exponent = if biased == 0 {
        (63 - bits.leading_zeros()) as i32 - 1074
    } else {
        biased - BIAS
    };
    floor(f64::from(binary_exponent) * core::f64::consts::LOG10_2) as i32
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// Edge inputs: zeros, subnormals, the normal range's ends, powers of two and their
    /// neighbours, exact squares, infinities and NaN.
    fn edge_values() -> std::vec::Vec<f64> {
        let mut values = std::vec![
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::EPSILON,
            5e-324,
            1e-310,
            f64::from_bits(0x000f_ffff_ffff_ffff),
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -1.0,
            -5e-324,
            0.5,
            1.0,
            2.0,
            3.0,
            4.0,
            9.0,
            1e10,
            0.1,
            0.3,
        ];
        // Every power of two, normal and subnormal, and its neighbours.
        for biased in 1..2047u64 {
            let p = biased << 52;
            values.extend([p - 1, p, p + 1].map(f64::from_bits));
        }
        values.extend((0..52).map(|k| f64::from_bits(1 << k)));
        for k in 1..2000u64 {
            let k = k as f64;
            values.extend([k * k, k * k + 1.0, k * k - 1.0, k + 0.5, -k - 0.5, k - 0.25]);
        }
        values
    }

    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    fn random_values(count: usize) -> impl Iterator<Item = f64> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        (0..count).map(move |i| {
            if i % 2 == 0 {
                // Uniform over bit patterns: every exponent, subnormals, NaN payloads.
                f64::from_bits(rng.gen())
            } else {
                rng.gen_range(-1e6..1e6)
            }
        })
    }

    #[test]
    fn square_roots_equal_the_standard_librarys_bit_for_bit() {
        for x in edge_values().into_iter().chain(random_values(300_000)) {
            assert!(same(sqrt(x), x.sqrt()), "sqrt({x:e})");
            assert!(same(sqrt_software(x), x.sqrt()), "sqrt_software({x:e})");
        }
    }

    /// With the `fma` target feature, one rounding: `f64::mul_add`'s bits; without, the
    /// product and the sum each rounded.
    #[test]
    fn mul_add_is_fused_exactly_where_the_target_has_fma() {
        let fused = cfg!(all(target_arch = "x86_64", target_feature = "fma"));
        let values: std::vec::Vec<f64> = random_values(30_000).collect();
        for w in values.windows(3) {
            let (x, y, z) = (w[0], w[1], w[2]);
            let expected = if fused { x.mul_add(y, z) } else { x * y + z };
            assert!(same(mul_add(x, y, z), expected), "{x:e}·{y:e} + {z:e}");
            let (a, b, c) = (x as f32, y as f32, z as f32);
            let expected = if fused { a.mul_add(b, c) } else { a * b + c };
            let got = mul_add_f32(a, b, c);
            assert!(got.to_bits() == expected.to_bits() || got.is_nan() && expected.is_nan());
        }
    }

    #[test]
    fn floor_round_and_trunc_equal_the_standard_librarys_bit_for_bit() {
        for x in edge_values().into_iter().chain(random_values(300_000)) {
            assert!(same(floor(x), x.floor()), "floor({x:e})");
            assert!(same(round(x), x.round()), "round({x:e})");
            assert!(same(trunc(x), x.trunc()), "trunc({x:e})");
        }
        // Halfway cases go away from zero; the largest double below one half stays at zero.
        assert_eq!(round(2.5), 3.0);
        assert_eq!(round(-2.5), -3.0);
        assert_eq!(round(0.499_999_999_999_999_94), 0.0);
    }

    #[test]
    fn the_decimal_exponent_estimate_is_exact_or_one_low() {
        for x in edge_values().into_iter().chain(random_values(100_000)) {
            let x = x.abs();
            if x.is_finite() && x > 0.0 {
                let exact = x.log10().floor() as i32;
                let estimate = floor_log10_estimate(x);
                assert!(
                    estimate == exact || estimate == exact - 1,
                    "{x:e}: {estimate} vs {exact}"
                );
            }
        }
    }
}
