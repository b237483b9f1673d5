//! [`F64x4`]: four `f64` lanes.

use bytemuck::cast;
use wide::{f64x4, u64x4, CmpLt};

use super::ops::{lane_arithmetic, lane_sign};
use crate::real::Real;
use crate::trig::{fast_path, reduce_each, Arithmetic};

/// Four `f64` evaluated together (feature `simd`): a generic kernel called with `F64x4`
/// computes four states per call.
///
/// Every operation gives in each lane the bits the `f64` operation gives: `+ − × ÷` and
/// `sqrt` are IEEE-754 in every lane, negation flips the sign bit, and [`Real::sin_cos`] is
/// the runtime's scalar [`sin_cos`](crate::sin_cos) lane by lane (the same reduction and
/// polynomials in the same order, checked bit for bit in the tests), so lane `i` of a kernel
/// equals the `f64` kernel at lane `i`'s state.
#[derive(Clone, Copy, Default)]
#[repr(transparent)]
pub struct F64x4(f64x4);

impl F64x4 {
    /// The number of lanes.
    pub const LANES: usize = 4;

    /// The lanes `lanes`.
    #[inline(always)]
    pub const fn new(lanes: [f64; 4]) -> F64x4 {
        F64x4(f64x4::new(lanes))
    }

    /// `x` in every lane.
    #[inline(always)]
    pub fn splat(x: f64) -> F64x4 {
        F64x4(f64x4::splat(x))
    }

    /// The lanes as an array.
    #[inline(always)]
    pub fn to_array(self) -> [f64; 4] {
        self.0.to_array()
    }

    /// The 4 × 4 block `x` transposed: lane `k` of result `i` is lane `i` of `x[k]`. With
    /// AVX, four unpacks and four lane permutations in registers.
    #[inline(always)]
    pub fn transpose(x: [F64x4; 4]) -> [F64x4; 4] {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
        {
            use core::arch::x86_64::{
                __m256d, _mm256_permute2f128_pd, _mm256_unpackhi_pd, _mm256_unpacklo_pd,
            };
            let [a, b, c, d] = x.map(|v| cast::<f64x4, __m256d>(v.0));
            // SAFETY: the target has AVX (the `cfg` above).
            let rows = unsafe {
                // (a0 b0 a2 b2), (a1 b1 a3 b3), (c0 d0 c2 d2), (c1 d1 c3 d3).
                let (ab0, ab1) = (_mm256_unpacklo_pd(a, b), _mm256_unpackhi_pd(a, b));
                let (cd0, cd1) = (_mm256_unpacklo_pd(c, d), _mm256_unpackhi_pd(c, d));
                [
                    _mm256_permute2f128_pd::<0x20>(ab0, cd0),
                    _mm256_permute2f128_pd::<0x20>(ab1, cd1),
                    _mm256_permute2f128_pd::<0x31>(ab0, cd0),
                    _mm256_permute2f128_pd::<0x31>(ab1, cd1),
                ]
            };
            rows.map(|r| F64x4(cast(r)))
        }
        #[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
        {
            let x = x.map(F64x4::to_array);
            core::array::from_fn(|i| F64x4::new(x.map(|row| row[i])))
        }
    }

    /// `(sin, cos)` of every lane by the scalar `trig::reduced`, lane by lane, and whether
    /// every lane's argument is within its range (|x| < 2²⁰·π/2, finite): branch-free, so
    /// that several arguments' evaluations interleave.
    #[inline(always)]
    fn reduced(self) -> (F64x4, F64x4, bool) {
        let splat = f64x4::splat;
        let (shifted, k, sin, cos) = fast_path(self.0);
        let in_range = k.abs().cmp_lt(splat(crate::trig::QUADRANTS)).all();
        let quadrant = cast::<f64x4, u64x4>(shifted) & u64x4::splat(3);
        // Odd quadrants swap sine and cosine; quadrants 2 and 3 negate the sine, 1 and 2 the
        // cosine (the scalar's bit operations).
        let swap = (quadrant & u64x4::splat(1)).cmp_eq(u64x4::splat(1));
        let (sin, cos) = (cast::<f64x4, u64x4>(sin), cast::<f64x4, u64x4>(cos));
        let s = swap.blend(cos, sin) ^ ((quadrant & u64x4::splat(2)) << 62);
        let c = swap.blend(sin, cos) ^ (((quadrant + u64x4::splat(1)) & u64x4::splat(2)) << 62);
        (F64x4(cast(s)), F64x4(cast(c)), in_range)
    }

    /// The scalar [`sin_cos`](crate::sin_cos) of each lane: the path of [`Real::sin_cos`]
    /// when a lane is out of the fast path's range, apart and cold.
    #[cold]
    #[inline(never)]
    fn sin_cos_lanes(self) -> (F64x4, F64x4) {
        let pairs = self.to_array().map(crate::trig::sin_cos);
        (
            F64x4::new(pairs.map(|p| p.0)),
            F64x4::new(pairs.map(|p| p.1)),
        )
    }
}

/// [`Real::sin_cos`] of every element: [`F64x4`]'s `sin_cos_array` when an argument is out of
/// the fast path's range, apart and cold as the scalar `trig::sin_cos_each`.
#[cold]
#[inline(never)]
fn sin_cos_each<const N: usize>(x: &[F64x4; N]) -> ([F64x4; N], [F64x4; N]) {
    let pairs = x.map(F64x4::sin_cos);
    (pairs.map(|p| p.0), pairs.map(|p| p.1))
}

/// The sine and cosine's arithmetic in `wide`'s vector: its multiply–adds are fused exactly
/// where the scalar's [`crate::float::mul_add`] is (x86-64 with FMA), so that every lane
/// rounds as the scalar does.
impl Arithmetic for f64x4 {
    #[inline(always)]
    fn splat(x: f64) -> f64x4 {
        f64x4::splat(x)
    }
    #[inline(always)]
    fn mul_add(self, y: f64x4, z: f64x4) -> f64x4 {
        #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
        return f64x4::mul_add(self, y, z);
        #[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
        return self * y + z;
    }
    #[inline(always)]
    fn neg_mul_add(self, y: f64x4, z: f64x4) -> f64x4 {
        #[cfg(all(target_arch = "x86_64", target_feature = "fma"))]
        return f64x4::mul_neg_add(self, y, z);
        #[cfg(not(all(target_arch = "x86_64", target_feature = "fma")))]
        return z - self * y;
    }
}

lane_arithmetic!(F64x4, f64x4, f64, 4);

impl Real for F64x4 {
    #[inline(always)]
    fn from_f64(x: f64) -> F64x4 {
        F64x4::splat(x)
    }
    /// The scalar [`sin_cos`](crate::sin_cos) in every lane, bit for bit: four at once when
    /// every argument is in its fast path's range, else lane by lane.
    #[inline]
    fn sin_cos(self) -> (F64x4, F64x4) {
        match self.reduced() {
            (s, c, true) => (s, c),
            _ => self.sin_cos_lanes(),
        }
    }
    /// Every element's [`Real::sin_cos`], always inlined and with one cold call for the case
    /// of an argument out of range, as the scalar [`sin_cos_array`](crate::trig::sin_cos_array)
    /// and for its reason: as a call (the trait's default, which LLVM did not inline), the
    /// sines and cosines went through memory and the kernel waited for the call to return.
    #[inline(always)]
    fn sin_cos_array<const N: usize>(x: &[F64x4; N]) -> ([F64x4; N], [F64x4; N]) {
        reduce_each(x, F64x4::splat(0.0), F64x4::reduced, sin_cos_each)
    }
    #[inline(always)]
    fn sqrt(self) -> F64x4 {
        F64x4(self.0.sqrt())
    }
    /// Fused exactly where the scalar's is (the sines' and cosines' `Arithmetic` of
    /// `wide`'s vector, one decision for both).
    #[inline(always)]
    fn mul_add(self, a: F64x4, b: F64x4) -> F64x4 {
        F64x4(Arithmetic::mul_add(self.0, a.0, b.0))
    }
    lane_sign!();
}

#[cfg(test)]
mod tests {
    use super::F64x4;

    /// Lane `k` of row `i` of the transposition is lane `i` of value `k`.
    #[test]
    fn transpose_swaps_values_and_lanes() {
        use crate::Lanes;
        let block: [F64x4; 4] = core::array::from_fn(|k| F64x4::from_fn(|i| (10 * k + i) as _));
        let rows = F64x4::transpose(block);
        for i in 0..4 {
            for k in 0..4 {
                assert_eq!(rows[i].lane(k), block[k].lane(i), "row {i}, lane {k}");
            }
        }
    }

    #[test]
    fn the_sine_and_cosine_multiply_adds_round_as_the_scalar_ones() {
        crate::trig::tests::check_multiply_adds(|x: wide::f64x4| x.to_array());
    }

    #[test]
    fn four_joint_angles_take_the_vector_path_and_huge_ones_do_not() {
        assert!(F64x4::new([0.3, -2.0, 7.5, 1e3]).reduced().2);
        assert!(!F64x4::new([0.3, -2.0, 7.5, 2e6]).reduced().2);
        assert!(!F64x4::new([0.3, f64::NAN, 7.5, 1.0]).reduced().2);
    }
}
