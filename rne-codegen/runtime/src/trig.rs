//! Sine and cosine together, fast and accurate, for the generated kernels.
//!
//! The kernels need `sin q_k` and `cos q_k` of every joint angle; at a few nanoseconds each
//! they are a large share of a small robot's inverse dynamics. [`sin_cos`] reduces the
//! argument by Cody and Waite's method (π/2 split into two parts of 33 bits, whose products
//! with the quadrant number are exact for |x| < 2²⁰·π/2 ≈ 1.6·10⁶, and a tail) and evaluates
//! the minimax polynomials of Sun Microsystems' fdlibm kernels on [−π/4, π/4]; it has no
//! branch except the one to Payne and Hanek's reduction (module `large`) for larger or
//! non-finite arguments. The polynomials are evaluated by Estrin's scheme rather than
//! fdlibm's Horner rule, which shortens the chain the kernels wait on (see `polynomial`). The
//! error is within 1 ulp for |x| ≤ 100, the range of joint angles, and 2 ulp up to 1.5·10⁶
//! (where the reduced argument may lose one more bit; 2 ulp occur from |x| ≈ 10³ on, as with
//! Horner's rule), checked against double-double values in the tests, and within 1 ulp
//! beyond; `sin(−0)` is `+0`. Built for a target with FMA, the reduction's and the polynomials'
//! multiply–adds are fused (trait `Arithmetic`), so the results differ from a build without
//! it by rounding, within the same bounds (CI runs the tests in both builds); within a build,
//! the scalar, the pairs, the quads and the lane types agree bit for bit. Nothing here needs
//! the standard library.

// The constants below are written with the digits fdlibm publishes; each rounds to the f64
// the algorithm needs.
#![allow(clippy::excessive_precision)]

use core::ops::{Add, Mul, Sub};

/// `+`, `−` and `×` of a register type of module `pair` or `quad` (a newtype of the
/// intrinsics' vector), each one intrinsic, and the type's [`Arithmetic`]: the multiply–adds
/// one fused intrinsic each on targets with FMA (as the scalar's [`crate::float::mul_add`]).
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
macro_rules! register_arithmetic {
    (
        $register:ident,
        $add:ident,
        $sub:ident,
        $mul:ident,
        $splat:ident,
        $fmadd:ident,
        $fnmadd:ident
    ) => {
        // SAFETY (each block): the module is compiled only for a target with the
        // intrinsics' instruction set (the fused ones only with FMA), and they touch no
        // memory.
        impl core::ops::Add for $register {
            type Output = $register;
            #[inline(always)]
            fn add(self, rhs: $register) -> $register {
                $register(unsafe { $add(self.0, rhs.0) })
            }
        }
        impl core::ops::Sub for $register {
            type Output = $register;
            #[inline(always)]
            fn sub(self, rhs: $register) -> $register {
                $register(unsafe { $sub(self.0, rhs.0) })
            }
        }
        impl core::ops::Mul for $register {
            type Output = $register;
            #[inline(always)]
            fn mul(self, rhs: $register) -> $register {
                $register(unsafe { $mul(self.0, rhs.0) })
            }
        }
        impl super::Arithmetic for $register {
            #[inline(always)]
            fn splat(x: f64) -> $register {
                $register(unsafe { $splat(x) })
            }
            #[inline(always)]
            fn mul_add(self, y: $register, z: $register) -> $register {
                #[cfg(target_feature = "fma")]
                return $register(unsafe { core::arch::x86_64::$fmadd(self.0, y.0, z.0) });
                #[cfg(not(target_feature = "fma"))]
                return self * y + z;
            }
            #[inline(always)]
            fn neg_mul_add(self, y: $register, z: $register) -> $register {
                #[cfg(target_feature = "fma")]
                return $register(unsafe { core::arch::x86_64::$fnmadd(self.0, y.0, z.0) });
                #[cfg(not(target_feature = "fma"))]
                return z - self * y;
            }
        }
    };
}

mod large;
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
mod pair;
#[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
mod quad;

/// Whether the fast path's multiply–adds are fused in this build (x86-64 with the `fma`
/// target feature). With the constants below, what a code generator needs
/// to compute [`sin_cos`]'s bits itself (the JIT inlines the fast path).
pub const FUSED: bool = cfg!(all(target_arch = "x86_64", target_feature = "fma"));

/// π/2 split into parts of 33 significant bits (the last with its tail), as in fdlibm's
/// `__ieee754_rem_pio2`.
pub const PIO2_1: f64 = 1.570_796_326_734_125_614_17;
/// The second part of π/2.
pub const PIO2_2: f64 = 6.077_100_506_303_965_976_60e-11;
/// The tail of π/2 beyond its first two parts.
pub const PIO2_2T: f64 = 2.022_266_248_795_950_631_54e-21;
/// 2/π, by which the argument is multiplied to find its quadrant.
pub const FRAC_2_PI: f64 = core::f64::consts::FRAC_2_PI;
/// 2²⁰: the fast path applies to arguments whose quadrant number k has |k| below it.
pub const QUADRANTS: f64 = 1_048_576.0;
/// 1.5 · 2⁵²: adding and subtracting it rounds to the nearest integer.
pub const ROUND: f64 = 6_755_399_441_055_744.0;

/// Taylor-like minimax coefficients of sin on [−π/4, π/4] (fdlibm `__kernel_sin`).
pub const S: [f64; 6] = [
    -1.666_666_666_666_663_243_48e-01,
    8.333_333_333_322_489_461_24e-03,
    -1.984_126_982_985_794_931_34e-04,
    2.755_731_370_707_006_767_89e-06,
    -2.505_076_025_340_686_341_95e-08,
    1.589_690_995_211_550_102_21e-10,
];

/// Minimax coefficients of cos on [−π/4, π/4] (fdlibm `__kernel_cos`).
pub const C: [f64; 6] = [
    4.166_666_666_666_660_190_37e-02,
    -1.388_888_888_887_410_957_49e-03,
    2.480_158_728_947_672_941_78e-05,
    -2.755_731_435_139_066_330_35e-07,
    2.087_572_321_298_174_827_90e-09,
    -1.135_964_755_778_819_482_65e-11,
];

/// The arithmetic of the fast path, for the scalar, the SSE2 pairs, the AVX2 quads and the
/// `F64x4` lanes: `+ − ×` of IEEE 754 in every lane, a constant in every lane, and the two
/// multiply–adds, each **one fused instruction on targets with FMA** (rounded once) **and
/// otherwise the product and the sum, each rounded** — there exactly the expressions the fast
/// path had before it used them, so that its results there are unchanged.
pub(crate) trait Arithmetic:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self>
{
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// `self · y + z`.
    fn mul_add(self, y: Self, z: Self) -> Self;
    /// `z − self · y`.
    fn neg_mul_add(self, y: Self, z: Self) -> Self;
}

impl Arithmetic for f64 {
    #[inline(always)]
    fn splat(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn mul_add(self, y: f64, z: f64) -> f64 {
        crate::float::mul_add(self, y, z)
    }
    #[inline(always)]
    fn neg_mul_add(self, y: f64, z: f64) -> f64 {
        crate::float::mul_add(-self, y, z)
    }
}

/// `c₀ + c₁ z + … + c₅ z⁵` as `c₀ + ((c₁ z + z² (c₂ + c₃ z)) + z⁴ (c₄ + c₅ z))`, given `z²`:
/// Estrin's scheme (the pairs and `z⁴` are independent) with the leading coefficient added
/// last, so that the result is rounded against it as in Horner's rule. Its chain of dependent
/// operations is 7 long instead of Horner's 10 (5 with FMA, where each pair and each
/// product-and-sum is one multiply–add): the kernels wait for their sines and cosines before
/// their first link, and this shortens the wait.
#[inline(always)]
pub(crate) fn polynomial<T: Arithmetic>(z: T, z2: T, c: [f64; 6]) -> T {
    let pair = |a: f64, b: f64| z.mul_add(T::splat(b), T::splat(a));
    let inner = z2.mul_add(pair(c[2], c[3]), z * T::splat(c[1]));
    T::splat(c[0]) + (z2 * z2).mul_add(pair(c[4], c[5]), inner)
}

/// The arithmetic of the fast path, the same operations in the same order for the scalar,
/// the SSE2 pairs, the AVX2 quads and the `F64x4` lanes, so that all of them round alike:
/// `(shifted, k, sin r, cos r)` — `x·2/π` shifted so that its low mantissa bits are the
/// quadrant, the quadrant number k, and the sine and cosine of the reduced argument
/// `r = x − k·π/2` (Cody and Waite's three parts) before the quadrant's swap and signs.
///
/// With FMA, `x·2/π` is rounded once before the shift (the quadrant may then differ from the
/// unfused one where `x·2/π` is within half an ulp of a half-integer; |r| still exceeds π/4
/// by no more than an ulp of it), `k·π/2`'s first two parts are exact products either way,
/// and its tail and the polynomials' products are rounded with their sums. An evaluation is
/// then 25 operations instead of 39 and its chain 44 cycles long instead of 51 (by the
/// latencies of `rne stats`: 3 for a sum or product, 4 for a multiply–add); every kernel waits
/// for it before its first link (docs/performance.md).
#[inline(always)]
pub(crate) fn fast_path<T: Arithmetic>(x: T) -> (T, T, T, T) {
    let shifted = x.mul_add(T::splat(FRAC_2_PI), T::splat(ROUND));
    let k = shifted - T::splat(ROUND);
    let r = k.neg_mul_add(
        T::splat(PIO2_2T),
        k.neg_mul_add(T::splat(PIO2_2), k.neg_mul_add(T::splat(PIO2_1), x)),
    );
    let z = r * r;
    let z2 = z * z;
    let sin = (r * z).mul_add(polynomial(z, z2, S), r);
    let cos = T::splat(1.0) - z2.neg_mul_add(polynomial(z, z2, C), T::splat(0.5) * z);
    (shifted, k, sin, cos)
}

/// The fast path for one argument (mirrored lane by lane by the `simd` lanes): `(sin x,
/// cos x)` and whether the reduction applies (|x| < 2²⁰·π/2 and finite). Branch-free — every
/// step is arithmetic or a bit operation — so that a loop over several arguments vectorises.
#[inline(always)]
fn reduced(x: f64) -> (f64, f64, bool) {
    let (shifted, k, sin, cos) = fast_path(x);
    let in_range = k.abs() < QUADRANTS;
    // Quadrant k mod 4, from the low bits of the shifted value's mantissa.
    let quadrant = shifted.to_bits() & 3;
    // Odd quadrants swap sine and cosine; quadrants 2 and 3 negate the sine, 1 and 2 the
    // cosine.
    let swap = ((quadrant & 1) as i64).wrapping_neg() as u64;
    let (sin, cos) = (sin.to_bits(), cos.to_bits());
    let s = (sin & !swap) | (cos & swap);
    let c = (cos & !swap) | (sin & swap);
    let flip_sin = (quadrant & 2) << 62;
    let flip_cos = ((quadrant + 1) & 2) << 62;
    (
        f64::from_bits(s ^ flip_sin),
        f64::from_bits(c ^ flip_cos),
        in_range,
    )
}

/// `(sin x, cos x)`.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    match reduced(x) {
        (s, c, true) => (s, c),
        _ => large::sin_cos(x),
    }
}

/// `(sin xᵢ, cos xᵢ)` of every element, bit for bit those of [`sin_cos`] (the kernels take
/// the sines and cosines of all joint angles at once). On x86-64, up to 16 arguments go two
/// by two through SSE2 (module `pair`), or with AVX2 four by four (module `quad`) and the
/// last one or two as a pair, at constant indices, so that they and their results stay in
/// registers; elsewhere, and for more arguments, a branch-free loop the compiler
/// vectorises. An argument out of the fast path's range sends the whole array to a cold
/// scalar path. Always inlined: as a call, which LLVM chose for AVX2 targets, the results go
/// through memory and the kernel's first link waits for the call to return, which slowed the
/// arms' inverse dynamics (docs/performance.md has the figures).
#[inline(always)]
pub fn sin_cos_array<const N: usize>(x: &[f64; N]) -> ([f64; N], [f64; N]) {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    if N <= PAIRED {
        let mut sin = [0.0; N];
        let mut cos = [0.0; N];
        let mut in_range = true;
        // Pairs at constant indices (the conditions fold for each N): angles, sines and
        // cosines stay in registers (module `pair`).
        macro_rules! pairs {
            ($($i:literal)*) => {$(
                if $i < N {
                    let next = if $i + 1 < N { $i + 1 } else { $i };
                    let ((s0, s1), (c0, c1), ok) = pair::reduced(x[$i], x[next]);
                    (sin[$i], cos[$i]) = (s0, c0);
                    (sin[next], cos[next]) = (s1, c1);
                    in_range &= ok;
                }
            )*};
        }
        // With AVX2, four at a time while three or more are left (the last index repeated
        // to fill a quad), then a pair: a 6-joint arm's angles take one quad and one pair.
        #[cfg(target_feature = "avx2")]
        {
            macro_rules! quads {
                ($($i:literal)*) => {$(
                    if $i + 3 <= N {
                        let at = |k: usize| ($i + k).min(N - 1);
                        let (s, c, ok) = quad::reduced([x[at(0)], x[at(1)], x[at(2)], x[at(3)]]);
                        for k in 0..4 {
                            (sin[at(k)], cos[at(k)]) = (s[k], c[k]);
                        }
                        in_range &= ok;
                    } else {
                        pairs!($i);
                    }
                )*};
            }
            quads!(0 4 8 12);
        }
        #[cfg(not(target_feature = "avx2"))]
        pairs!(0 2 4 6 8 10 12 14);
        if !in_range {
            return sin_cos_each(x);
        }
        return (sin, cos);
    }
    reduce_each(x, 0.0, reduced, sin_cos_each)
}

/// `(sin xᵢ, cos xᵢ)` of every element by `reduced` (the fast path of one value: sine,
/// cosine and whether it applies), or by `each` (the cold path, for the whole array) when it
/// declines one: branch-free, so that the evaluations interleave. Up to [`UNROLLED`]
/// elements are evaluated at constant indices, so that the arguments, sines and cosines stay
/// in registers and the coefficients are loaded once: as a loop, which LLVM kept for UR5's
/// mass matrix in `F64x4` on an AVX2 target (six iterations of 60 instructions), the
/// coefficients were loaded again in every iteration and the results went through the
/// stack. [`sin_cos_array`]'s and the lane types' `sin_cos_array`.
#[inline(always)]
pub(crate) fn reduce_each<T: Copy, const N: usize>(
    x: &[T; N],
    zero: T,
    reduced: impl Fn(T) -> (T, T, bool),
    each: impl FnOnce(&[T; N]) -> ([T; N], [T; N]),
) -> ([T; N], [T; N]) {
    let mut sin = [zero; N];
    let mut cos = [zero; N];
    let mut in_range = true;
    let mut reduce = |i: usize| {
        let (s, c, ok) = reduced(x[i]);
        sin[i] = s;
        cos[i] = c;
        in_range &= ok;
    };
    if N <= UNROLLED {
        // The conditions fold for each N.
        macro_rules! unrolled {
            ($($i:literal)*) => {$(
                if $i < N {
                    reduce($i);
                }
            )*};
        }
        unrolled!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15);
    } else {
        for i in 0..N {
            reduce(i);
        }
    }
    if !in_range {
        return each(x);
    }
    (sin, cos)
}

/// The most arguments [`reduce_each`] evaluates at constant indices.
const UNROLLED: usize = 16;

/// The most arguments [`sin_cos_array`] evaluates in pairs without a loop.
#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
const PAIRED: usize = 16;

/// [`sin_cos`] of every element: [`sin_cos_array`]'s path when an argument is out of the
/// fast path's range. Apart, cold and never inlined, so that the fast path's arrays are not
/// written by a variable index: the loop that did so kept them in memory, where the kernels'
/// loads of pairs of them straddled two stores, which the processor cannot forward
/// (docs/performance.md).
#[cold]
#[inline(never)]
fn sin_cos_each<const N: usize>(x: &[f64; N]) -> ([f64; N], [f64; N]) {
    let mut sin = [0.0; N];
    let mut cos = [0.0; N];
    for i in 0..N {
        (sin[i], cos[i]) = sin_cos(x[i]);
    }
    (sin, cos)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::{sin_cos, Arithmetic};

    /// `T`'s multiply–adds are fused exactly where the scalar's are (x86-64 with FMA) and are
    /// otherwise the product and the sum, each rounded, in every lane (`lanes`): the factors
    /// 1 ± 2⁻³⁰ have the product 1 − 2⁻⁶⁰, which rounds to 1 before a separate sum.
    pub(crate) fn check_multiply_adds<T: Arithmetic, const L: usize>(
        lanes: impl Fn(T) -> [f64; L],
    ) {
        let fused = super::FUSED;
        let tiny = 1.0 / (1u64 << 30) as f64;
        let (a, b) = (T::splat(1.0 + tiny), T::splat(1.0 - tiny));
        let (sum, difference) = if fused {
            (-tiny * tiny, tiny * tiny)
        } else {
            (0.0, 0.0)
        };
        for lane in lanes(a.mul_add(b, T::splat(-1.0))) {
            assert_eq!(lane.to_bits(), sum.to_bits(), "mul_add, fused: {fused}");
        }
        for lane in lanes(a.neg_mul_add(b, T::splat(1.0))) {
            assert_eq!(
                lane.to_bits(),
                difference.to_bits(),
                "neg_mul_add, fused: {fused}"
            );
        }
    }

    #[test]
    fn the_scalar_multiply_adds_are_fused_where_the_target_has_fma() {
        check_multiply_adds(|x: f64| [x]);
    }

    /// Distance between `a` and `b` in units of the last place of `b`.
    fn ulps(a: f64, b: f64) -> f64 {
        if a == b {
            return 0.0;
        }
        let ulp = f64::from_bits(b.abs().to_bits() + 1) - b.abs();
        (a - b).abs() / ulp
    }

    /// Reference values in double-double (≈ 32 digits), rounded once.
    fn exact(x: f64) -> (f64, f64) {
        let (s, c) = crate::Real::sin_cos(crate::DoubleDouble::from_f64(x));
        (s.to_f64(), c.to_f64())
    }

    #[test]
    fn within_one_ulp_up_to_100_and_two_up_to_1_5e6() {
        let mut worst: f64 = 0.0;
        let mut x: f64 = 1e-8;
        while x < 1.5e6 {
            for v in [x, -x, x * 1.000_000_1] {
                let (s, c) = sin_cos(v);
                let (se, ce) = exact(v);
                let error = ulps(s, se).max(ulps(c, ce));
                let bound = if v.abs() <= 100.0 { 1.0 } else { 2.0 };
                assert!(error <= bound, "sin_cos({v:e}) is {error} ulp off");
                worst = worst.max(error);
            }
            x *= 1.003;
        }
        assert!(worst > 0.0, "the comparison saw no rounding at all");
    }

    #[test]
    fn within_one_ulp_at_random_joint_angles() {
        use rand::{Rng, SeedableRng};
        let mut random = rand_chacha::ChaCha8Rng::seed_from_u64(0x5eed_7219);
        let mut worst: f64 = 0.0;
        for _ in 0..100_000 {
            let x = random.gen_range(-100.0..=100.0);
            let ((s, c), (se, ce)) = (sin_cos(x), exact(x));
            let error = ulps(s, se).max(ulps(c, ce));
            assert!(error <= 1.0, "sin_cos({x:e}) is {error} ulp off");
            worst = worst.max(error);
        }
        assert!(worst > 0.0, "the comparison saw no rounding at all");
    }

    #[test]
    fn exact_where_the_results_are_exact() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert_eq!(sin_cos(-0.0), (0.0, 1.0));
    }

    #[test]
    fn arrays_give_the_scalar_results_bit_for_bit() {
        let xs = [0.3, -2.0, 7.5, 1e3, -0.0, 3.0e5, 1.2];
        let (s, c) = super::sin_cos_array(&xs);
        for (i, &x) in xs.iter().enumerate() {
            assert_eq!(
                (s[i].to_bits(), c[i].to_bits()),
                (sin_cos(x).0.to_bits(), sin_cos(x).1.to_bits())
            );
        }
        let with_huge = [0.3, 1e300, f64::NAN];
        let (s, c) = super::sin_cos_array(&with_huge);
        for (i, &x) in with_huge.iter().enumerate() {
            let (es, ec) = sin_cos(x);
            assert!(s[i].to_bits() == es.to_bits() || (s[i].is_nan() && es.is_nan()));
            assert!(c[i].to_bits() == ec.to_bits() || (c[i].is_nan() && ec.is_nan()));
        }
    }

    /// Every length up to beyond the unrolled paths (pairs, and with AVX2 quads then a pair,
    /// the last index repeated), over arguments in every quadrant: each element is the
    /// scalar result bit for bit, and one argument out of range anywhere still gives it.
    #[test]
    fn arrays_of_every_length_give_the_scalar_results_bit_for_bit() {
        fn check<const N: usize>(seed: u64) {
            use rand::{Rng, SeedableRng};
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            for round in 0..200 {
                let mut xs: [f64; N] = core::array::from_fn(|_| rng.gen_range(-10.0..10.0));
                if round % 10 == 9 {
                    xs[round % N] = 1e300;
                }
                let (s, c) = super::sin_cos_array(&xs);
                for (i, &x) in xs.iter().enumerate() {
                    let (es, ec) = sin_cos(x);
                    assert_eq!(
                        (s[i].to_bits(), c[i].to_bits()),
                        (es.to_bits(), ec.to_bits())
                    );
                }
            }
        }
        macro_rules! lengths {
            ($($n:literal)*) => {$( check::<$n>($n); )*};
        }
        lengths!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18);
    }

    #[test]
    fn large_and_non_finite_arguments_are_within_one_ulp_of_the_standard_library() {
        for x in [2e6, -3e9, 1e300, f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            let (s, c) = sin_cos(x);
            let (se, ce) = x.sin_cos();
            assert!(
                ulps(s, se) <= 1.0 || (s.is_nan() && se.is_nan()),
                "sin({x})"
            );
            assert!(
                ulps(c, ce) <= 1.0 || (c.is_nan() && ce.is_nan()),
                "cos({x})"
            );
        }
    }
}
