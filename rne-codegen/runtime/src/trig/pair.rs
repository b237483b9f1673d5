//! The fast path of [`sin_cos`](super::sin_cos) for two arguments in one SSE2 register, for
//! [`sin_cos_array`](super::sin_cos_array) on x86-64: the scalar `reduced`, the same
//! operations in the same order, so each half is bit for bit the scalar result.
//!
//! Written with the intrinsics rather than left to the vectoriser: a loop over the angles was
//! vectorised through memory (with AVX-512, masked stores that the processor does not forward
//! to the kernel's loads of them), and straight-line scalar code was vectorised together with
//! the kernel's own arithmetic into wide shuffles; pairs in registers are neither.

use super::fast_path;
use core::arch::x86_64::{
    __m128d, __m128i, _mm_add_epi64, _mm_add_pd, _mm_and_pd, _mm_and_si128, _mm_andnot_si128,
    _mm_castpd_si128, _mm_castsi128_pd, _mm_cmplt_pd, _mm_cvtsd_f64, _mm_movemask_pd, _mm_mul_pd,
    _mm_or_si128, _mm_set1_epi64x, _mm_set1_pd, _mm_set_pd, _mm_setzero_si128, _mm_slli_epi64,
    _mm_sub_epi64, _mm_sub_pd, _mm_unpackhi_pd, _mm_xor_si128,
};

/// Two `f64` in an SSE2 register.
#[derive(Clone, Copy)]
struct Pair(__m128d);

// SAFETY (every `unsafe` block in this module): the intrinsics need SSE2, part of the
// x86-64 baseline this module is compiled for only; none of them touches memory.

impl Pair {
    #[inline(always)]
    fn bits(self) -> __m128i {
        unsafe { _mm_castpd_si128(self.0) }
    }
    #[inline(always)]
    fn halves(self) -> (f64, f64) {
        unsafe {
            (
                _mm_cvtsd_f64(self.0),
                _mm_cvtsd_f64(_mm_unpackhi_pd(self.0, self.0)),
            )
        }
    }
}

register_arithmetic!(
    Pair,
    _mm_add_pd,
    _mm_sub_pd,
    _mm_mul_pd,
    _mm_set1_pd,
    _mm_fmadd_pd,
    _mm_fnmadd_pd
);

/// `((sin a, sin b), (cos a, cos b), both in the fast path's range)`.
#[inline(always)]
pub(super) fn reduced(a: f64, b: f64) -> ((f64, f64), (f64, f64), bool) {
    let x = Pair(unsafe { _mm_set_pd(b, a) });
    let (shifted, k, sin, cos) = fast_path(x);
    let in_range = unsafe {
        let magnitude = _mm_and_pd(k.0, _mm_castsi128_pd(_mm_set1_epi64x(i64::MAX)));
        _mm_movemask_pd(_mm_cmplt_pd(magnitude, _mm_set1_pd(super::QUADRANTS))) == 3
    };
    let (sin, cos) = unsafe {
        let quadrant = _mm_and_si128(shifted.bits(), _mm_set1_epi64x(3));
        let one = _mm_set1_epi64x(1);
        let two = _mm_set1_epi64x(2);
        // All ones where the quadrant is odd: sine and cosine swap.
        let swap = _mm_sub_epi64(_mm_setzero_si128(), _mm_and_si128(quadrant, one));
        let (sin, cos) = (sin.bits(), cos.bits());
        let s = _mm_or_si128(_mm_andnot_si128(swap, sin), _mm_and_si128(cos, swap));
        let c = _mm_or_si128(_mm_andnot_si128(swap, cos), _mm_and_si128(sin, swap));
        let flip_sin = _mm_slli_epi64(_mm_and_si128(quadrant, two), 62);
        let flip_cos = _mm_slli_epi64(_mm_and_si128(_mm_add_epi64(quadrant, one), two), 62);
        (
            Pair(_mm_castsi128_pd(_mm_xor_si128(s, flip_sin))),
            Pair(_mm_castsi128_pd(_mm_xor_si128(c, flip_cos))),
        )
    };
    (sin.halves(), cos.halves(), in_range)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_multiply_adds_round_as_the_scalar_ones() {
        super::super::tests::check_multiply_adds(|x: super::Pair| {
            let (a, b) = x.halves();
            [a, b]
        });
    }
}
