//! Error-free transformations: a rounded `f64` result together with its exact rounding error.
//!
//! See Shewchuk, "Adaptive precision floating-point arithmetic and fast robust geometric
//! predicates", Discrete Comput. Geom. 18 (1997). `core` has no fused multiply–add, so the
//! exact product is Dekker's, from Veltkamp's splitting.

/// `(s, e)` with `s = fl(a + b)` and `s + e = a + b` exactly, for any doubles (Knuth's
/// TwoSum; six operations, no branch).
#[inline]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let b_virtual = s - a;
    let a_virtual = s - b_virtual;
    (s, (a - a_virtual) + (b - b_virtual))
}

/// `(s, e)` with `s = fl(a + b)` and `s + e = a + b` exactly, provided `|a| ≥ |b|` or
/// `a = 0` (Dekker 1971; three operations).
#[inline]
pub fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// 2²⁷ + 1: Veltkamp's splitting constant for 53-bit significands.
const SPLITTER: f64 = 134_217_729.0;
/// Above this magnitude splitting could overflow; such a factor is scaled down first.
const SPLIT_LIMIT: f64 = 6.696_928_794_914_171e299; // 2⁹⁹⁶
/// 2⁻⁶⁴ and 2⁶⁴: the scaling of a factor beyond [`SPLIT_LIMIT`] (exact).
const SCALE_DOWN: f64 = 5.421_010_862_427_522e-20;
const SCALE_UP: f64 = 18_446_744_073_709_551_616.0;

/// `(h, l)` with `h + l = a` exactly and each half of at most 26 significant bits
/// (Veltkamp's splitting), for |a| ≤ [`SPLIT_LIMIT`].
#[inline]
fn split(a: f64) -> (f64, f64) {
    let c = SPLITTER * a;
    let h = c - (c - a);
    (h, a - h)
}

/// `a · b − p` exactly, for `p = fl(a · b)` and factors within [`SPLIT_LIMIT`] (Dekker 1971).
#[inline]
fn product_error(a: f64, b: f64, p: f64) -> f64 {
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    ((ah * bh - p) + ah * bl + al * bh) + al * bl
}

/// `(p, e)` with `p = fl(a · b)` and `p + e = a · b` exactly, barring underflow of `e` and
/// overflow of `p` (Dekker 1971). Where `p` is not finite, `e` is 0.
#[inline]
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    if !p.is_finite() {
        return (p, 0.0);
    }
    let (large, small) = if a.abs() >= b.abs() { (a, b) } else { (b, a) };
    if large.abs() > SPLIT_LIMIT {
        // The scaled product is exact in the same bits: fl(a·b·2⁻⁶⁴) = p·2⁻⁶⁴.
        let e = product_error(large * SCALE_DOWN, small, p * SCALE_DOWN);
        return (p, e * SCALE_UP);
    }
    (p, product_error(a, b, p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn two_prod_error_is_what_a_fused_multiply_add_gives(a in -1e300f64..1e300, b in -1e6f64..1e6) {
            let (p, e) = two_prod(a, b);
            prop_assert_eq!(p, a * b);
            if p.abs() > 1e-290 {
                prop_assert_eq!(e.to_bits(), a.mul_add(b, -p).to_bits());
            }
        }

        #[test]
        fn two_prod_is_exact_for_any_exponents(m1 in 1.0f64..2.0, m2 in 1.0f64..2.0, e1 in -500i32..500, e2 in -500i32..500) {
            let (a, b) = (m1 * 2f64.powi(e1), m2 * 2f64.powi(e2));
            let (p, e) = two_prod(a, b);
            if p.is_finite() && p.abs() > 1e-290 {
                prop_assert_eq!(e.to_bits(), a.mul_add(b, -p).to_bits());
            }
        }

        #[test]
        fn two_sum_error_is_exact(a in -1e300f64..1e300, b in -1e300f64..1e300) {
            let (s, e) = two_sum(a, b);
            prop_assert_eq!(s, a + b);
            // Dekker's FastTwoSum is exact when the larger operand comes first.
            let (larger, smaller) = if a.abs() >= b.abs() { (a, b) } else { (b, a) };
            prop_assert_eq!((s, e), fast_two_sum(larger, smaller));
        }
    }

    #[test]
    fn two_prod_of_huge_arguments_is_exact() {
        for (a, b) in [(f64::MAX, 0.75), (1e300, 1e-10), (-3.0e307, 5.0)] {
            let (p, e) = two_prod(a, b);
            assert_eq!(e.to_bits(), a.mul_add(b, -p).to_bits(), "{a} * {b}");
        }
    }
}
