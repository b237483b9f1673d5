//! The fast path of [`sin_cos`](super::sin_cos) for four arguments in one AVX register, for
//! [`sin_cos_array`](super::sin_cos_array) in builds for AVX2: module `pair`'s operations on
//! 256 bits, so each lane is bit for bit the scalar result, and a 6-joint arm's angles take
//! one quad and one pair instead of three pairs.

use super::fast_path;
use core::arch::x86_64::{
    __m256d, __m256i, _mm256_add_epi64, _mm256_add_pd, _mm256_and_pd, _mm256_and_si256,
    _mm256_andnot_si256, _mm256_castpd256_pd128, _mm256_castpd_si256, _mm256_castsi256_pd,
    _mm256_cmp_pd, _mm256_extractf128_pd, _mm256_movemask_pd, _mm256_mul_pd, _mm256_or_si256,
    _mm256_set1_epi64x, _mm256_set1_pd, _mm256_set_pd, _mm256_setzero_si256, _mm256_slli_epi64,
    _mm256_sub_epi64, _mm256_sub_pd, _mm256_xor_si256, _mm_cvtsd_f64, _mm_unpackhi_pd, _CMP_LT_OS,
};

/// Four `f64` in an AVX register.
#[derive(Clone, Copy)]
struct Quad(__m256d);

// SAFETY (every `unsafe` block in this module): the intrinsics need AVX and AVX2, which the
// target this module is compiled for has (its `cfg`); none of them touches memory.

impl Quad {
    #[inline(always)]
    fn bits(self) -> __m256i {
        unsafe { _mm256_castpd_si256(self.0) }
    }
    #[inline(always)]
    fn lanes(self) -> [f64; 4] {
        unsafe {
            let (low, high) = (
                _mm256_castpd256_pd128(self.0),
                _mm256_extractf128_pd::<1>(self.0),
            );
            [
                _mm_cvtsd_f64(low),
                _mm_cvtsd_f64(_mm_unpackhi_pd(low, low)),
                _mm_cvtsd_f64(high),
                _mm_cvtsd_f64(_mm_unpackhi_pd(high, high)),
            ]
        }
    }
}

register_arithmetic!(
    Quad,
    _mm256_add_pd,
    _mm256_sub_pd,
    _mm256_mul_pd,
    _mm256_set1_pd,
    _mm256_fmadd_pd,
    _mm256_fnmadd_pd
);

/// `(sin xᵢ, cos xᵢ)` of the four arguments and whether all four are in the fast path's
/// range.
#[inline(always)]
pub(super) fn reduced(x: [f64; 4]) -> ([f64; 4], [f64; 4], bool) {
    let x = Quad(unsafe { _mm256_set_pd(x[3], x[2], x[1], x[0]) });
    let (shifted, k, sin, cos) = fast_path(x);
    let in_range = unsafe {
        let magnitude = _mm256_and_pd(k.0, _mm256_castsi256_pd(_mm256_set1_epi64x(i64::MAX)));
        _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OS>(
            magnitude,
            _mm256_set1_pd(super::QUADRANTS),
        )) == 15
    };
    let (sin, cos) = unsafe {
        let quadrant = _mm256_and_si256(shifted.bits(), _mm256_set1_epi64x(3));
        let one = _mm256_set1_epi64x(1);
        let two = _mm256_set1_epi64x(2);
        // All ones where the quadrant is odd: sine and cosine swap.
        let swap = _mm256_sub_epi64(_mm256_setzero_si256(), _mm256_and_si256(quadrant, one));
        let (sin, cos) = (sin.bits(), cos.bits());
        let s = _mm256_or_si256(_mm256_andnot_si256(swap, sin), _mm256_and_si256(cos, swap));
        let c = _mm256_or_si256(_mm256_andnot_si256(swap, cos), _mm256_and_si256(sin, swap));
        let flip_sin = _mm256_slli_epi64::<62>(_mm256_and_si256(quadrant, two));
        let flip_cos =
            _mm256_slli_epi64::<62>(_mm256_and_si256(_mm256_add_epi64(quadrant, one), two));
        (
            Quad(_mm256_castsi256_pd(_mm256_xor_si256(s, flip_sin))),
            Quad(_mm256_castsi256_pd(_mm256_xor_si256(c, flip_cos))),
        )
    };
    (sin.lanes(), cos.lanes(), in_range)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_multiply_adds_round_as_the_scalar_ones() {
        super::super::tests::check_multiply_adds(|x: super::Quad| x.lanes());
    }
}
