//! The step of the base parameters' refinement that costs most: `r ← r − x·c` down a column
//! of W, in double-double (`Split::refine` forms R = W₂ − W₁ K by one such step per non-zero
//! coefficient of K: 21 204 steps of 1 920 rows each, twice, for a random 48-joint chain).
//!
//! Each step multiplies two double-doubles, whose exact product of the high parts is the
//! costly part: Dekker's, from Veltkamp's splitting, 17 operations and three branches
//! ([`rne_runtime`]'s `two_prod`; `core` has no fused multiply–add). Where the processor has
//! a fused multiply–add (detected at run time), the error of `p = fl(a·b)` is one,
//! `fma(a, b, −p)`, and the loop has no branch left. Both are exact when neither factor's
//! magnitude is outside [2⁻⁴⁵⁰, 2⁴⁵⁰] (zero aside): Veltkamp's halves and their products
//! then neither overflow nor underflow. So a column whose entries and coefficient all are
//! zero or within that range takes the fused path with the bits of the runtime's operators,
//! and any other column (huge, tiny, infinite or NaN entries) goes through the operators.

use crate::DoubleDouble;

/// 2⁻⁴⁵⁰ and 2⁴⁵⁰: the magnitudes between which both exact products agree (module docs).
const EXACT_LOW: f64 = 3.439_552_567_074_349_4e-136;
const EXACT_HIGH: f64 = 2.907_354_897_182_427_6e135;

/// Whether `x` is zero or within [`EXACT_LOW`, `EXACT_HIGH`] in magnitude (not NaN).
fn products_exact(x: DoubleDouble) -> bool {
    x.hi() == 0.0 || (EXACT_LOW..=EXACT_HIGH).contains(&x.hi().abs())
}

/// A column of W, with whether the fused path may take it: the processor has FMA and AVX2
/// and every entry is within the exact range. Checked once per column, as a refinement
/// subtracts each kept column many times.
#[derive(Clone, Copy)]
pub(super) struct Column<'a> {
    entries: &'a [DoubleDouble],
    #[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
    fused: bool,
}

impl<'a> Column<'a> {
    /// The column `entries`, checked.
    pub(super) fn new(entries: &'a [DoubleDouble]) -> Column<'a> {
        #[cfg(target_arch = "x86_64")]
        let fused = std::is_x86_feature_detected!("fma")
            && std::is_x86_feature_detected!("avx2")
            && entries.iter().all(|&x| products_exact(x));
        #[cfg(not(target_arch = "x86_64"))]
        let fused = false;
        Column { entries, fused }
    }
}

/// `r[i] ← r[i] − x[i]·c` for every row `i`: bit for bit `r[i] - x[i] * c` by the runtime's
/// operators, through a fused multiply–add when the processor has one and the column and
/// coefficient allow it (module docs).
pub(super) fn subtract_scaled(r: &mut [DoubleDouble], x: Column<'_>, c: DoubleDouble) {
    #[cfg(target_arch = "x86_64")]
    if x.fused && products_exact(c) {
        // SAFETY: the processor has FMA and AVX2 (`Column::new` detected them).
        unsafe { subtract_scaled_fused(r, x.entries, c) };
        return;
    }
    subtract_scaled_by_operators(r, x.entries, c);
}

/// [`subtract_scaled`] by the runtime's operators.
fn subtract_scaled_by_operators(r: &mut [DoubleDouble], x: &[DoubleDouble], c: DoubleDouble) {
    for (r, &x) in r.iter_mut().zip(x) {
        *r -= x * c;
    }
}

/// [`subtract_scaled`] with the high parts' product error from a fused multiply–add, for a
/// column whose products are exact both ways ([`products_exact`]). Compiled for AVX2 too, so
/// that the branch-free loop may take four rows per instruction.
///
/// # Safety
/// The processor must have FMA and AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma,avx2")]
unsafe fn subtract_scaled_fused(r: &mut [DoubleDouble], x: &[DoubleDouble], c: DoubleDouble) {
    for (r, &x) in r.iter_mut().zip(x) {
        let p = x.hi() * c.hi();
        let e = x.hi().mul_add(c.hi(), -p);
        *r -= x.mul_given_product(c, (p, e));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn same(a: DoubleDouble, b: DoubleDouble) -> bool {
        let bits = |x: f64| if x.is_nan() { u64::MAX } else { x.to_bits() };
        bits(a.hi()) == bits(b.hi()) && bits(a.lo()) == bits(b.lo())
    }

    /// A double-double the fused path takes: zero, ordinary (a regressor's entries), or of
    /// any exponent up to the exact range's edges, which it includes.
    fn exact_entry() -> BoxedStrategy<DoubleDouble> {
        prop_oneof![
            Just(DoubleDouble::ZERO),
            Just(-DoubleDouble::ZERO),
            (-1e3f64..1e3, -1e-14f64..1e-14).prop_map(|(h, l)| DoubleDouble::from_parts(h, h * l)),
            (1.0f64..2.0, -450i32..450, any::<bool>()).prop_map(|(m, e, negative)| {
                let x = m * 2f64.powi(e);
                DoubleDouble::from_parts(if negative { -x } else { x }, x * 1e-17)
            }),
            Just(DoubleDouble::from_f64(EXACT_LOW)),
            Just(DoubleDouble::from_f64(-EXACT_HIGH)),
        ]
        .boxed()
    }

    /// A double-double of any kind: those of [`exact_entry`], and beyond the exact range
    /// (subnormal or huge), infinite or NaN.
    fn entry() -> BoxedStrategy<DoubleDouble> {
        prop_oneof![
            3 => exact_entry(),
            1 => (1.0f64..2.0, -1074i32..1023)
                .prop_map(|(m, e)| DoubleDouble::from_f64(m * 2f64.powi(e))),
            1 => prop_oneof![
                Just(DoubleDouble::from_f64(f64::INFINITY)),
                Just(DoubleDouble::NAN),
                Just(DoubleDouble::from_f64(1e-300)),
            ],
        ]
        .boxed()
    }

    /// A residual column, a column of W and a coefficient, of entries drawn by `entry`
    /// (the residual's of any kind).
    fn column(
        entry: fn() -> BoxedStrategy<DoubleDouble>,
    ) -> impl Strategy<Value = (Vec<DoubleDouble>, Vec<DoubleDouble>, DoubleDouble)> {
        (1usize..40).prop_flat_map(move |n| {
            (
                proptest::collection::vec(self::entry(), n),
                proptest::collection::vec(entry(), n),
                entry(),
            )
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// Every column, whichever path it takes, gets the operators' bits.
        #[test]
        fn the_update_gives_the_bits_of_the_operators((r, x, c) in column(entry)) {
            let mut fast = r.clone();
            subtract_scaled(&mut fast, Column::new(&x), c);
            for ((f, &r), &x) in fast.iter().zip(&r).zip(&x) {
                prop_assert!(same(*f, r - x * c), "{r:?} - {x:?} * {c:?}");
            }
        }

        /// The fused path, on columns it is given (where the processor has it), gets the
        /// operators' bits: exact product errors both ways within the range.
        #[test]
        fn the_fused_path_gives_the_bits_of_the_operators((r, x, c) in column(exact_entry)) {
            let column = Column::new(&x);
            prop_assert!(products_exact(c));
            #[cfg(target_arch = "x86_64")]
            if std::is_x86_feature_detected!("fma") && std::is_x86_feature_detected!("avx2") {
                prop_assert!(column.fused);
                let (mut fused, mut plain) = (r.clone(), r.clone());
                // SAFETY: FMA and AVX2 detected just above.
                unsafe { subtract_scaled_fused(&mut fused, &x, c) };
                subtract_scaled_by_operators(&mut plain, &x, c);
                for (f, p) in fused.iter().zip(&plain) {
                    prop_assert!(same(*f, *p));
                }
            }
        }
    }

    /// The range's bounds are 2⁻⁴⁵⁰ and 2⁴⁵⁰ exactly.
    #[test]
    fn the_exact_range_is_two_to_the_minus_and_plus_450() {
        assert_eq!(EXACT_LOW, 2f64.powi(-450));
        assert_eq!(EXACT_HIGH, 2f64.powi(450));
    }
}
