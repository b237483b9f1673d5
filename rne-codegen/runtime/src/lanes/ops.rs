//! The arithmetic of a lane type, lane by lane, on its `wide` vector.

/// `Add`, `Sub`, `Mul`, `Div` (IEEE-754 in each lane, as the scalar), their assigning forms,
/// and `Neg` as a flip of each sign bit (`wide`'s own `0 − x` would turn −0 into +0 and
/// break bit-for-bit equality with the scalar).
macro_rules! lane_arithmetic {
    ($lanes:ident, $vector:ty, $scalar:ty, $n:literal) => {
        impl core::ops::Add for $lanes {
            type Output = $lanes;
            #[inline(always)]
            fn add(self, rhs: $lanes) -> $lanes {
                $lanes(self.0 + rhs.0)
            }
        }
        impl core::ops::Sub for $lanes {
            type Output = $lanes;
            #[inline(always)]
            fn sub(self, rhs: $lanes) -> $lanes {
                $lanes(self.0 - rhs.0)
            }
        }
        impl core::ops::Mul for $lanes {
            type Output = $lanes;
            #[inline(always)]
            fn mul(self, rhs: $lanes) -> $lanes {
                $lanes(self.0 * rhs.0)
            }
        }
        impl core::ops::Div for $lanes {
            type Output = $lanes;
            #[inline(always)]
            fn div(self, rhs: $lanes) -> $lanes {
                $lanes(self.0 / rhs.0)
            }
        }
        impl core::ops::Neg for $lanes {
            type Output = $lanes;
            #[inline(always)]
            fn neg(self) -> $lanes {
                $lanes(self.0 ^ <$vector>::splat(-0.0))
            }
        }
        impl core::ops::AddAssign for $lanes {
            #[inline(always)]
            fn add_assign(&mut self, rhs: $lanes) {
                *self = *self + rhs;
            }
        }
        impl core::ops::SubAssign for $lanes {
            #[inline(always)]
            fn sub_assign(&mut self, rhs: $lanes) {
                *self = *self - rhs;
            }
        }
        impl core::ops::MulAssign for $lanes {
            #[inline(always)]
            fn mul_assign(&mut self, rhs: $lanes) {
                *self = *self * rhs;
            }
        }
        impl core::fmt::Debug for $lanes {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.debug_tuple(stringify!($lanes))
                    .field(&self.to_array())
                    .finish()
            }
        }
        impl From<[$scalar; $n]> for $lanes {
            #[inline]
            fn from(lanes: [$scalar; $n]) -> $lanes {
                $lanes::new(lanes)
            }
        }
        impl From<$lanes> for [$scalar; $n] {
            #[inline]
            fn from(x: $lanes) -> [$scalar; $n] {
                x.to_array()
            }
        }
        impl $crate::Lanes for $lanes {
            type Lane = $scalar;
            const LANES: usize = $n;
            #[inline(always)]
            fn from_fn(lane: impl FnMut(usize) -> $scalar) -> $lanes {
                $lanes::new(core::array::from_fn(lane))
            }
            #[inline(always)]
            fn lane(self, i: usize) -> $scalar {
                self.0.as_array_ref()[i.min($n - 1)]
            }
            /// By [`Self::transpose`].
            #[inline(always)]
            fn transposed(block: impl Fn(usize) -> $lanes, mut row: impl FnMut(usize, &[$scalar])) {
                let rows = $lanes::transpose(core::array::from_fn(block));
                for (i, r) in rows.iter().enumerate() {
                    row(i, &r.to_array());
                }
            }
        }
    };
}

/// `abs` (the sign bits cleared) and `sign` (1, −1, or the value itself for ±0 and NaN: the
/// scalar's `sign` in every lane) of a lane type.
macro_rules! lane_sign {
    () => {
        #[inline(always)]
        fn abs(self) -> Self {
            Self(self.0.abs())
        }
        #[inline(always)]
        fn sign(self) -> Self {
            use wide::{CmpGt, CmpLt};
            let (zero, one) = (Self::splat(0.0).0, Self::splat(1.0).0);
            let negative = self.0.cmp_lt(zero).blend(Self::splat(-1.0).0, self.0);
            Self(self.0.cmp_gt(zero).blend(one, negative))
        }
    };
}

pub(crate) use lane_arithmetic;
pub(crate) use lane_sign;
