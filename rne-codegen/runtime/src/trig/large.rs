//! `sin` and `cos` of arguments too large for the Cody–Waite reduction (|x| ≥ 2²⁰·π/2), by
//! Payne and Hanek's reduction: x·2/π is computed in fixed point from the bits of 2/π that
//! matter for x (its integer part modulo 4 and 128 bits of its fraction), so no precision is
//! lost however large x is.
//!
//! M. Payne and R. Hanek, "Radian reduction for trigonometric functions", SIGNUM Newsletter
//! 18 (1983); the closest a double comes to a multiple of π/2 is about 2⁻⁶¹ (K. C.
//! Ng, "Argument reduction for huge arguments: good to the last bit", 1992), which the 128
//! fraction bits cover with more than 60 bits to spare.

// The polynomial coefficients are written with the digits fdlibm publishes.
#![allow(clippy::excessive_precision)]

use super::{C, S};
use crate::eft::two_prod;

/// The bits of 2/π after the binary point, most significant first: 1280 bits, enough for the
/// largest finite `f64` (whose exponent skips the first ~970) plus a 192-bit window.
const TWO_OVER_PI: [u64; 20] = [
    0xA2F9_836E_4E44_1529,
    0xFC27_57D1_F534_DDC0,
    0xDB62_9599_3C43_9041,
    0xFE51_63AB_DEBB_C561,
    0xB724_6E3A_424D_D2E0,
    0x0649_2EEA_09D1_921C,
    0xFE1D_EB1C_B129_A73E,
    0xE882_35F5_2EBB_4484,
    0xE99C_7026_B45F_7E41,
    0x3991_D639_8353_39F4,
    0x9C84_5F8B_BDF9_283B,
    0x1FF8_97FF_DE05_980F,
    0xEF2F_118B_5A0A_6D1F,
    0x6D36_7ECF_27CB_09B7,
    0x4F46_3F66_9E5F_EA2D,
    0x7527_BAC7_EBE5_F17B,
    0x3D07_39F7_8A52_92EA,
    0x6BFB_5FB1_1F8D_5D08,
    0x5603_3046_FC7B_6BAB,
    0xF0CF_BC20_9AF4_361D,
];

/// π/2 as a double-double (hi + lo).
const HALF_PI_HI: f64 = core::f64::consts::FRAC_PI_2;
const HALF_PI_LO: f64 = 6.123_233_995_736_766e-17;

/// 2⁻¹²⁸ (exact).
const TWO_POW_MINUS_128: f64 = 2.938_735_877_055_718_8e-39;

/// `(sin x, cos x)` for any `x` (NaN for infinite or NaN `x`), within 1 ulp.
pub(super) fn sin_cos(x: f64) -> (f64, f64) {
    if !x.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let (quadrant, r_hi, r_lo) = reduce(x);
    let (s, c) = (sin_kernel(r_hi, r_lo), cos_kernel(r_hi, r_lo));
    match quadrant {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `(k mod 4, r_hi, r_lo)` with x = k·π/2 + r, |r| ≤ π/4 and r ≈ r_hi + r_lo to about 120
/// bits, for finite |x| ≥ 1 (smaller arguments need no reduction and are not passed here).
fn reduce(x: f64) -> (u32, f64, f64) {
    let bits = x.abs().to_bits();
    // |x| = m · 2^e with m < 2⁵³ an integer.
    let m = (bits & ((1 << 52) - 1)) | (1 << 52);
    let e = ((bits >> 52) as i32) - 1075;
    // Bits j of 2/π (weight 2^−(j+1)) with j < e − 2 contribute multiples of 4 to x·2/π and
    // drop out; the next 192 bits W give x·2/π ≡ m·W·2^−t (mod 4) with t fraction bits.
    let first = (e - 2).max(0) as u32;
    let t = first as i32 + 192 - e;
    let product = mul_53_by_192(m, window(first));
    // Integer part modulo 4, and the top 128 bits of the fraction.
    let quadrant = (shift_right(&product, t as u32) & 3) as u32;
    let fraction = shift_right_128(&product, t as u32 - 128);
    // Round to the nearest quadrant: a fraction of one half or more counts from the next
    // quadrant down (wrapping the fraction to [−1/2, 1/2) as a signed number).
    let signed = fraction as i128;
    let quadrant = if signed < 0 { quadrant + 1 } else { quadrant } & 3;
    // The fraction as a double-double in units of 2⁻¹²⁸, then times π/2.
    let hi = signed as f64;
    let lo = signed.wrapping_sub(hi as i128) as f64;
    let (hi, lo) = (hi * TWO_POW_MINUS_128, lo * TWO_POW_MINUS_128);
    let (p, p_err) = two_prod(hi, HALF_PI_HI);
    let tail = p_err + (hi * HALF_PI_LO + lo * HALF_PI_HI);
    let r_hi = p + tail;
    let r_lo = tail - (r_hi - p);
    if x < 0.0 {
        ((4 - quadrant) & 3, -r_hi, -r_lo)
    } else {
        (quadrant, r_hi, r_lo)
    }
}

/// Bits `first .. first + 192` of 2/π as three words, most significant first.
fn window(first: u32) -> [u64; 3] {
    let word = (first / 64) as usize;
    let offset = first % 64;
    let at = |i: usize| TWO_OVER_PI[word + i];
    let mut w = [0; 3];
    for (i, slot) in w.iter_mut().enumerate() {
        *slot = if offset == 0 {
            at(i)
        } else {
            (at(i) << offset) | (at(i + 1) >> (64 - offset))
        };
    }
    w
}

/// `m · W` for a 53-bit m and a 192-bit W (three words, most significant first), as four
/// words, least significant first.
fn mul_53_by_192(m: u64, w: [u64; 3]) -> [u64; 4] {
    let mut out = [0u64; 4];
    let mut carry: u128 = 0;
    for (i, &word) in w.iter().rev().enumerate() {
        let p = u128::from(m) * u128::from(word) + carry;
        out[i] = p as u64;
        carry = p >> 64;
    }
    out[3] = carry as u64;
    out
}

/// The low 64 bits of `n >> shift` (n least significant word first, shift < 256).
fn shift_right(n: &[u64; 4], shift: u32) -> u64 {
    let word = (shift / 64) as usize;
    let offset = shift % 64;
    let low = n.get(word).copied().unwrap_or(0);
    let high = n.get(word + 1).copied().unwrap_or(0);
    if offset == 0 {
        low
    } else {
        (low >> offset) | (high << (64 - offset))
    }
}

/// The low 128 bits of `n >> shift`.
fn shift_right_128(n: &[u64; 4], shift: u32) -> u128 {
    u128::from(shift_right(n, shift)) | (u128::from(shift_right(n, shift + 64)) << 64)
}

/// sin(x + y) for |x| ≤ π/4 and a tail |y| ≪ ulp(x) (fdlibm's `__kernel_sin`).
fn sin_kernel(x: f64, y: f64) -> f64 {
    let z = x * x;
    let v = z * x;
    let r = S[1] + z * (S[2] + z * (S[3] + z * (S[4] + z * S[5])));
    x - ((z * (0.5 * y - v * r) - y) - v * S[0])
}

/// cos(x + y) for |x| ≤ π/4 and a tail |y| ≪ ulp(x) (fdlibm's `__kernel_cos` as in musl).
fn cos_kernel(x: f64, y: f64) -> f64 {
    let z = x * x;
    let w = z * z;
    let r = z * (C[0] + z * (C[1] + z * C[2])) + w * w * (C[3] + z * (C[4] + z * C[5]));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + (z * r - x * y))
}

#[cfg(test)]
mod tests {
    use super::sin_cos;
    use rand::{Rng, SeedableRng};

    /// Distance between `a` and `b` in units of the last place of `b`.
    fn ulps(a: f64, b: f64) -> f64 {
        if a == b {
            return 0.0;
        }
        let ulp = f64::from_bits(b.abs().to_bits() + 1) - b.abs();
        (a - b).abs() / ulp
    }

    fn assert_near_std(x: f64) {
        let (s, c) = sin_cos(x);
        let (se, ce) = x.sin_cos();
        assert!(
            ulps(s, se) <= 1.0 && ulps(c, ce) <= 1.0,
            "sin_cos({x:e}) = ({s:e}, {c:e}), std gives ({se:e}, {ce:e})"
        );
    }

    #[test]
    fn within_one_ulp_of_the_standard_library_at_every_magnitude() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        for _ in 0..200_000 {
            let exponent = rng.gen_range(1.0..1024.0f64);
            let x = rng.gen_range(1.0..2.0) * 2f64.powf(exponent.floor());
            let x = if rng.gen() { x } else { -x };
            assert_near_std(x);
        }
    }

    #[test]
    fn within_one_ulp_at_arguments_nearest_multiples_of_half_pi() {
        // The largest double, multiples of π/2 themselves and the edges of the reduction.
        for x in [
            f64::MAX,
            -f64::MAX,
            1e22,
            core::f64::consts::FRAC_PI_2 * 2f64.powi(30),
            2f64.powi(20) * core::f64::consts::FRAC_PI_2,
            1.0,
            2.0,
            4.5e15,
            2f64.powi(53),
        ] {
            assert_near_std(x);
        }
    }

    #[test]
    fn correctly_rounded_at_the_double_nearest_a_multiple_of_half_pi() {
        // K. C. Ng's worst case for reduction, x = 6381956970095103·2⁷⁹⁷ = k·π/2 + r with
        // k ≡ 1 (mod 4) and r = 4.687165924254628…e−19 (exact rational
        // arithmetic with 2000 bits of π): cos x = −sin r rounds to −4.687165924254628e−19,
        // which this machine's glibc misses by 8 ulp.
        let worst = 6_381_956_970_095_103.0 * 2f64.powi(797);
        assert_eq!(sin_cos(worst), (1.0, -4.687_165_924_254_628e-19));
        assert_eq!(sin_cos(-worst), (-1.0, -4.687_165_924_254_628e-19));
    }

    #[test]
    fn infinite_and_nan_arguments_give_nan() {
        for x in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            let (s, c) = sin_cos(x);
            assert!(s.is_nan() && c.is_nan(), "sin_cos({x})");
        }
    }
}
