//! [`F32x8`]: eight `f32` lanes.

use wide::f32x8;

use super::ops::{lane_arithmetic, lane_sign};
use super::F64x4;
use crate::real::Real;

/// Eight `f32` evaluated together (feature `simd`): a generic kernel called with `F32x8`
/// computes eight states per call.
///
/// Every operation gives in each lane the bits the `f32` [`Real`] operation gives:
/// `+ − × ÷` and `sqrt` are IEEE-754 in every lane (the scalar's `sqrt` through `f64` is
/// correctly rounded too), and [`Real::sin_cos`] is, like the scalar's, the `f64`
/// [`sin_cos`](crate::sin_cos) of each lane (two [`F64x4`]) rounded once to `f32`.
#[derive(Clone, Copy, Default)]
#[repr(transparent)]
pub struct F32x8(f32x8);

impl F32x8 {
    /// The number of lanes.
    pub const LANES: usize = 8;

    /// The lanes `lanes`.
    #[inline(always)]
    pub const fn new(lanes: [f32; 8]) -> F32x8 {
        F32x8(f32x8::new(lanes))
    }

    /// `x` in every lane.
    #[inline(always)]
    pub fn splat(x: f32) -> F32x8 {
        F32x8(f32x8::splat(x))
    }

    /// The 8 × 8 block `x` transposed: lane `k` of result `i` is lane `i` of `x[k]`
    /// (`wide`'s transposition: shuffles in registers with AVX).
    #[inline(always)]
    pub fn transpose(x: [F32x8; 8]) -> [F32x8; 8] {
        f32x8::transpose(x.map(|v| v.0)).map(F32x8)
    }

    /// The lanes as an array.
    #[inline(always)]
    pub fn to_array(self) -> [f32; 8] {
        self.0.to_array()
    }

    /// Lanes `4 half .. 4 half + 4` widened to `f64`.
    #[inline(always)]
    fn widen(self, half: usize) -> F64x4 {
        let a = self.to_array();
        F64x4::new(core::array::from_fn(|i| f64::from(a[4 * half + i])))
    }

    /// Two [`F64x4`] rounded to eight `f32`.
    #[inline(always)]
    fn narrow(low: F64x4, high: F64x4) -> F32x8 {
        let (low, high) = (low.to_array(), high.to_array());
        F32x8::new(core::array::from_fn(|i| {
            if i < 4 {
                low[i] as f32
            } else {
                high[i - 4] as f32
            }
        }))
    }
}

lane_arithmetic!(F32x8, f32x8, f32, 8);

impl Real for F32x8 {
    /// `x` rounded to `f32`, in every lane.
    #[inline(always)]
    fn from_f64(x: f64) -> F32x8 {
        F32x8::splat(x as f32)
    }
    #[inline]
    fn sin_cos(self) -> (F32x8, F32x8) {
        let (sin_low, cos_low) = self.widen(0).sin_cos();
        let (sin_high, cos_high) = self.widen(1).sin_cos();
        (
            F32x8::narrow(sin_low, sin_high),
            F32x8::narrow(cos_low, cos_high),
        )
    }
    /// Every element's [`Real::sin_cos`] through [`F64x4`]'s `sin_cos_array` on the low and
    /// the high halves, always inlined for the same reason as it.
    #[inline(always)]
    fn sin_cos_array<const N: usize>(x: &[F32x8; N]) -> ([F32x8; N], [F32x8; N]) {
        let (sin_low, cos_low) = F64x4::sin_cos_array(&x.map(|v| v.widen(0)));
        let (sin_high, cos_high) = F64x4::sin_cos_array(&x.map(|v| v.widen(1)));
        (
            core::array::from_fn(|i| F32x8::narrow(sin_low[i], sin_high[i])),
            core::array::from_fn(|i| F32x8::narrow(cos_low[i], cos_high[i])),
        )
    }
    #[inline(always)]
    fn sqrt(self) -> F32x8 {
        F32x8(self.0.sqrt())
    }
    /// `wide`'s `mul_add`: fused where the target has FMA, as the scalar's.
    #[inline(always)]
    fn mul_add(self, a: F32x8, b: F32x8) -> F32x8 {
        F32x8(self.0.mul_add(a.0, b.0))
    }
    lane_sign!();
}

#[cfg(test)]
mod tests {
    use super::F32x8;

    /// Lane `k` of row `i` of the transposition is lane `i` of value `k`.
    #[test]
    fn transpose_swaps_values_and_lanes() {
        use crate::Lanes;
        let block: [F32x8; 8] = core::array::from_fn(|k| F32x8::from_fn(|i| (10 * k + i) as _));
        let rows = F32x8::transpose(block);
        for i in 0..8 {
            for k in 0..8 {
                assert_eq!(rows[i].lane(k), block[k].lane(i), "row {i}, lane {k}");
            }
        }
    }
}
