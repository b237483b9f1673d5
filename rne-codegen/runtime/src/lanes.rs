//! Lanes: several values of one scalar evaluated by every operation at once, so that a
//! `scalar: generic` kernel called with [`F64x4`] or [`F32x8`] computes 4 or 8 states per
//! call (docs/design.md §4).
//!
//! [`Lanes`] is what the [`batch`](crate::batch) helper needs of a scalar: how many lanes it
//! has and how to fill and read them. The plain scalars are one lane each, so the helper
//! runs the same code with or without vectors. With the feature `simd` the runtime adds
//! [`F64x4`] and [`F32x8`], built on the `wide` crate: one AVX instruction per operation when
//! the target has AVX (e.g. `-C target-cpu=native`), two SSE2 instructions on a baseline
//! x86-64, portable code elsewhere. Their results are bit for bit those of the scalar in
//! every lane, `sin_cos` included (see [`F64x4`]).

use crate::real::{OrderedReal, Real};
use crate::DoubleDouble;

#[cfg(feature = "simd")]
mod f32x8;
#[cfg(feature = "simd")]
mod f64x4;
#[cfg(feature = "simd")]
mod ops;

#[cfg(feature = "simd")]
pub use f32x8::F32x8;
#[cfg(feature = "simd")]
pub use f64x4::F64x4;

/// A [`Real`] holding [`Lanes::LANES`] values of the scalar [`Lanes::Lane`], every operation
/// acting on each lane as the scalar would.
pub trait Lanes: Real {
    /// The scalar of one lane.
    type Lane: OrderedReal;
    /// The number of lanes.
    const LANES: usize;
    /// The value whose lane `i` is `lane(i)`, for `i` in `0..LANES`.
    fn from_fn(lane: impl FnMut(usize) -> Self::Lane) -> Self;
    /// Lane `i` (`i < LANES`; the last lane for a larger `i`).
    fn lane(self, i: usize) -> Self::Lane;
    /// A square block transposed, row by row: `row(i, r)` for `i` in `0..LANES`, where
    /// `r[k]` is lane `i` of `block(k)`. The batch helper scatters a result's consecutive
    /// values to each state this way; the lane types transpose in registers, so that each
    /// row is one vector.
    fn transposed(block: impl Fn(usize) -> Self, row: impl FnMut(usize, &[Self::Lane]));
}

/// The plain scalars: one lane.
macro_rules! single_lane {
    ($($t:ty),*) => {$(
        impl Lanes for $t {
            type Lane = $t;
            const LANES: usize = 1;
            #[inline]
            fn from_fn(mut lane: impl FnMut(usize) -> $t) -> $t {
                lane(0)
            }
            #[inline]
            fn lane(self, _: usize) -> $t {
                self
            }
            #[inline(always)]
            fn transposed(block: impl Fn(usize) -> $t, mut row: impl FnMut(usize, &[$t])) {
                row(0, &[block(0)]);
            }
        }
    )*};
}

single_lane!(f64, f32, DoubleDouble);

#[cfg(test)]
mod tests {
    use super::Lanes;

    #[test]
    fn scalars_are_one_lane_of_themselves() {
        assert_eq!(<f64 as Lanes>::LANES, 1);
        assert_eq!(<f64 as Lanes>::from_fn(|i| i as f64 + 2.5), 2.5);
        assert_eq!(Lanes::lane(-1.5f32, 0), -1.5);
    }

    #[cfg(feature = "simd")]
    mod simd {
        use crate::{F32x8, F64x4, Lanes, Real};
        use rand::{Rng, SeedableRng};
        use rand_chacha::ChaCha8Rng;
        use std::vec::Vec;

        /// Arguments of every kind: joint angles, wide ranges, the edges of the fast path's
        /// range, and values the fast path declines (huge, infinite, NaN).
        fn arguments() -> Vec<f64> {
            let mut rng = ChaCha8Rng::seed_from_u64(41);
            let mut xs: Vec<f64> = (0..20_000).map(|_| rng.gen_range(-7.0..7.0)).collect();
            xs.extend((0..4_000).map(|_| rng.gen_range(-1.6e6..1.6e6)));
            xs.extend((0..2_000).map(|_| 10f64.powf(rng.gen_range(-12.0..9.0))));
            xs.extend([0.0, -0.0, 1.5e-320, 1_647_099.0, 1_647_100.0, -1e300]);
            xs.extend([f64::INFINITY, f64::NEG_INFINITY, f64::NAN, f64::MAX]);
            xs
        }

        fn same(a: f64, b: f64) -> bool {
            a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
        }

        #[test]
        fn f64x4_sin_cos_is_the_scalar_sin_cos_bit_for_bit_in_every_lane() {
            let xs = arguments();
            // Shifted by one so that declined arguments share groups with ordinary ones.
            for offset in [0, 1] {
                for group in xs[offset..].chunks_exact(4) {
                    let (s, c) = F64x4::new([group[0], group[1], group[2], group[3]]).sin_cos();
                    for (i, &x) in group.iter().enumerate() {
                        let (es, ec) = crate::sin_cos(x);
                        assert!(same(s.lane(i), es) && same(c.lane(i), ec), "sin_cos({x:e})");
                    }
                }
            }
        }

        /// Arrays of six lane values (a 6-joint kernel's angles) along the arguments, so that
        /// some hold only arguments in the fast path's range and some one or more it declines,
        /// which sends the whole array to the cold path.
        #[test]
        fn lane_sin_cos_arrays_are_sin_cos_of_each_element_bit_for_bit() {
            let xs = arguments();
            for window in xs.windows(32).step_by(7) {
                let wide: [F64x4; 6] = core::array::from_fn(|k| {
                    F64x4::from_fn(|i| window[(5 * k + i) % window.len()])
                });
                let (s, c) = F64x4::sin_cos_array(&wide);
                let single: [F32x8; 6] = core::array::from_fn(|k| {
                    F32x8::from_fn(|i| window[(5 * k + i) % window.len()] as f32)
                });
                let (s32, c32) = F32x8::sin_cos_array(&single);
                for k in 0..6 {
                    let (es, ec) = wide[k].sin_cos();
                    let (es32, ec32) = single[k].sin_cos();
                    for i in 0..8 {
                        if i < 4 {
                            assert!(
                                same(s[k].lane(i), es.lane(i)) && same(c[k].lane(i), ec.lane(i))
                            );
                        }
                        let same32 = |a: f32, b: f32| {
                            a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
                        };
                        assert!(
                            same32(s32[k].lane(i), es32.lane(i))
                                && same32(c32[k].lane(i), ec32.lane(i))
                        );
                    }
                }
            }
        }

        #[test]
        fn f32x8_sin_cos_is_the_f32_sin_cos_bit_for_bit_in_every_lane() {
            let xs: Vec<f32> = arguments().iter().map(|&x| x as f32).collect();
            for group in xs.chunks_exact(8) {
                let (s, c) = F32x8::from_fn(|i| group[i]).sin_cos();
                for (i, &x) in group.iter().enumerate() {
                    let (es, ec) = Real::sin_cos(x);
                    let same =
                        |a: f32, b: f32| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
                    assert!(same(s.lane(i), es) && same(c.lane(i), ec), "sin_cos({x:e})");
                }
            }
        }

        #[test]
        fn arithmetic_square_roots_and_signs_act_lane_by_lane_bit_for_bit() {
            let xs = arguments();
            for group in xs.chunks_exact(8) {
                let a = F64x4::from_fn(|i| group[i]);
                let b = F64x4::from_fn(|i| group[7 - i]);
                let results = [a + b, a - b, a * b, a / b, -a, a.sqrt(), a.abs(), a.sign()];
                let mut assigned = a;
                assigned += b;
                assigned *= a;
                assigned -= b;
                for i in 0..4 {
                    let (x, y) = (group[i], group[7 - i]);
                    let expected = [
                        x + y,
                        x - y,
                        x * y,
                        x / y,
                        -x,
                        Real::sqrt(x),
                        Real::abs(x),
                        x.sign(),
                    ];
                    for (r, e) in results.iter().zip(expected) {
                        assert!(same(r.lane(i), e), "lane {i} of {results:?}: {e}");
                    }
                    assert!(same(assigned.lane(i), (x + y) * x - y));
                }
                let single = F32x8::from_fn(|i| group[i] as f32);
                let other = F32x8::from_fn(|i| group[7 - i] as f32);
                let results = [
                    single * other,
                    single / other,
                    -single,
                    single.sqrt(),
                    single.sign(),
                ];
                for i in 0..8 {
                    let (x, y) = (group[i] as f32, group[7 - i] as f32);
                    let expected = [x * y, x / y, -x, Real::sqrt(x), x.sign()];
                    for (r, e) in results.iter().zip(expected) {
                        assert!(same(f64::from(r.lane(i)), f64::from(e)), "lane {i}: {e}");
                    }
                }
            }
            assert_eq!((-F64x4::splat(0.0)).lane(2).to_bits(), (-0.0f64).to_bits());
        }

        #[test]
        fn lanes_convert_to_and_from_arrays() {
            let x = F64x4::from([1.0, 2.0, 3.0, 4.0]);
            assert_eq!(<[f64; 4]>::from(x), [1.0, 2.0, 3.0, 4.0]);
            assert_eq!(F64x4::from_f64(0.1).to_array(), [0.1; 4]);
            assert_eq!(F32x8::from_f64(0.1).to_array(), [0.1f32; 8]);
            assert_eq!(
                std::format!("{:?}", F32x8::splat(1.0)),
                "F32x8([1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0])"
            );
        }
    }
}
