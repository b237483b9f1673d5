/* sin and cos: the rne runtime's `sin_cos` (rne-codegen/runtime/src/trig.rs and
 * trig/large.rs, with two_prod of eft.rs), ported operation for operation -- the same
 * constants, the same operations in the same order -- so that its results equal the Rust
 * kernels' bit for bit. Cody and Waite's reduction and fdlibm's polynomials by Estrin's
 * scheme for |x| < 2^20 pi/2; Payne and Hanek's reduction beyond, and NaN for infinities and
 * NaN. The multiply-adds are fused exactly where the Rust runtime's are (rne_mul_add). */

/* pi/2 in three parts of 33 bits (fdlibm's __ieee754_rem_pio2), 2/pi, and 1.5 * 2^52. */
#define RNE_PIO2_1 1.57079632673412561417e+00
#define RNE_PIO2_2 6.07710050630396597660e-11
#define RNE_PIO2_2T 2.02226624879595063154e-21
#define RNE_FRAC_2_PI 0.6366197723675814
#define RNE_ROUND 6755399441055744.0

/* Minimax coefficients of sin and cos on [-pi/4, pi/4] (fdlibm's __kernel_sin, __kernel_cos). */
static const double rne_sin_coefficients[6] = {
    -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04,
    2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10};
static const double rne_cos_coefficients[6] = {
    4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05,
    -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11};

/* x * y + z - rne_neg_mul_add: z - x * y -- fused (rounded once) where the Rust runtime's
 * multiply-adds are: x86-64 with FMA (-mfma, -march=haswell or later, -march=native there). */
static double rne_neg_mul_add(double x, double y, double z) { return rne_mul_add(-x, y, z); }

static uint64_t rne_bits(double x) {
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

static double rne_from_bits(uint64_t bits) {
    double x;
    memcpy(&x, &bits, sizeof x);
    return x;
}

/* c0 + ((c1 z + z^2 (c2 + c3 z)) + z^4 (c4 + c5 z)) given z^2: Estrin's scheme. */
static double rne_polynomial(double z, double z2, const double c[6]) {
    const double inner = rne_mul_add(z2, rne_mul_add(z, c[3], c[2]), z * c[1]);
    return c[0] + rne_mul_add(z2 * z2, rne_mul_add(z, c[5], c[4]), inner);
}

/* --- Payne and Hanek's reduction (trig/large.rs) ------------------------------------------ */

/* The bits of 2/pi after the binary point, most significant first. */
static const uint64_t rne_two_over_pi[20] = {
    UINT64_C(0xA2F9836E4E441529), UINT64_C(0xFC2757D1F534DDC0), UINT64_C(0xDB6295993C439041),
    UINT64_C(0xFE5163ABDEBBC561), UINT64_C(0xB7246E3A424DD2E0), UINT64_C(0x06492EEA09D1921C),
    UINT64_C(0xFE1DEB1CB129A73E), UINT64_C(0xE88235F52EBB4484), UINT64_C(0xE99C7026B45F7E41),
    UINT64_C(0x3991D639835339F4), UINT64_C(0x9C845F8BBDF9283B), UINT64_C(0x1FF897FFDE05980F),
    UINT64_C(0xEF2F118B5A0A6D1F), UINT64_C(0x6D367ECF27CB09B7), UINT64_C(0x4F463F669E5FEA2D),
    UINT64_C(0x7527BAC7EBE5F17B), UINT64_C(0x3D0739F78A5292EA), UINT64_C(0x6BFB5FB11F8D5D08),
    UINT64_C(0x56033046FC7B6BAB), UINT64_C(0xF0CFBC209AF4361D)};

/* A 128-bit integer as two words (two's complement where it is signed). */
struct rne_u128 {
    uint64_t hi, lo;
};

/* a * b + c, exactly. */
static struct rne_u128 rne_mul_64(uint64_t a, uint64_t b, uint64_t c) {
    const uint64_t mask = UINT64_C(0xFFFFFFFF);
    const uint64_t a0 = a & mask, a1 = a >> 32, b0 = b & mask, b1 = b >> 32;
    const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    const uint64_t middle = (p00 >> 32) + (p01 & mask) + (p10 & mask);
    struct rne_u128 r;
    r.lo = (middle << 32) | (p00 & mask);
    r.hi = p11 + (p01 >> 32) + (p10 >> 32) + (middle >> 32);
    r.lo += c;
    r.hi += r.lo < c;
    return r;
}

/* The low 64 bits of n >> shift (n four words, least significant first; shift < 256). */
static uint64_t rne_shift_right(const uint64_t n[4], unsigned shift) {
    const unsigned word = shift / 64, offset = shift % 64;
    const uint64_t low = word < 4 ? n[word] : 0, high = word + 1 < 4 ? n[word + 1] : 0;
    return offset == 0 ? low : (low >> offset) | (high << (64 - offset));
}

/* 2^e for an integer -1022 <= e <= 1023, exactly. */
static double rne_power_of_two(int e) { return rne_from_bits((uint64_t)(e + 1023) << 52); }

/* A signed 128-bit integer to the nearest double, ties to even (Rust's `i128 as f64`). */
static double rne_i128_to_f64(struct rne_u128 n) {
    const int negative = (int)(n.hi >> 63);
    uint64_t hi = n.hi, lo = n.lo, top, sticky, mantissa, rest;
    int shift = 0;
    double magnitude;
    if (negative) {
        hi = ~hi + (lo == 0);
        lo = ~lo + 1;
    }
    if (hi == 0 && lo >> 53 == 0) {
        magnitude = (double)lo;
    } else {
        /* The leading 64 bits, the bits below them folded into `sticky`. */
        if (hi == 0) {
            top = lo;
            sticky = 0;
            shift = 0;
        } else {
            while (hi >> (63 - shift) == 0) {
                shift += 1;
            }
            top = shift == 0 ? hi : (hi << shift) | (lo >> (64 - shift));
            sticky = shift == 0 ? lo : lo << shift;
            shift = 64 - shift;
        }
        while (top >> 63 == 0) {
            top <<= 1;
            shift -= 1;
        }
        mantissa = top >> 11;
        rest = top & 0x7FF;
        if (rest > 0x400 || (rest == 0x400 && (sticky != 0 || (mantissa & 1) != 0))) {
            mantissa += 1;
        }
        magnitude = (double)mantissa * rne_power_of_two(shift + 11);
    }
    return negative ? -magnitude : magnitude;
}

/* An integer-valued double of magnitude at most 2^127 to a signed 128-bit integer, the
 * largest one for 2^127 (Rust's saturating `f64 as i128`). */
static struct rne_u128 rne_f64_to_i128(double x) {
    const uint64_t bits = rne_bits(x);
    const int e = (int)((bits >> 52) & 0x7FF) - 1075;
    const uint64_t m = (bits & ((UINT64_C(1) << 52) - 1)) | (UINT64_C(1) << 52);
    struct rne_u128 r;
    if ((bits & ~(UINT64_C(1) << 63)) == 0) {
        r.hi = 0;
        r.lo = 0;
        return r;
    }
    if (e >= 75 && (bits >> 63) == 0) {
        r.hi = ~(UINT64_C(1) << 63);
        r.lo = ~UINT64_C(0);
        return r;
    }
    if (e <= 0) {
        r.hi = 0;
        r.lo = m >> -e;
    } else if (e < 64) {
        r.hi = m >> (64 - e);
        r.lo = m << e;
    } else {
        r.hi = m << (e - 64);
        r.lo = 0;
    }
    if (bits >> 63) {
        r.hi = ~r.hi + (r.lo == 0);
        r.lo = ~r.lo + 1;
    }
    return r;
}

/* a * b - p exactly for p = fl(a * b) (Dekker, by Veltkamp's splitting). */
static double rne_product_error(double a, double b, double p) {
    const double ca = 134217729.0 * a, cb = 134217729.0 * b;
    const double ah = ca - (ca - a), bh = cb - (cb - b);
    const double al = a - ah, bl = b - bh;
    return ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

/* fl(a * b) and its exact error (eft.rs two_prod). */
static double rne_two_prod(double a, double b, double *error) {
    const double p = a * b;
    const double magnitude_a = a < 0.0 ? -a : a, magnitude_b = b < 0.0 ? -b : b;
    const double large = magnitude_a >= magnitude_b ? a : b, small = magnitude_a >= magnitude_b ? b : a;
    if (!(p - p == 0.0)) {
        *error = 0.0;
        return p;
    }
    if ((large < 0.0 ? -large : large) > 6.696928794914171e299) {
        *error = rne_product_error(large * 5.421010862427522e-20, small, p * 5.421010862427522e-20) *
                 18446744073709551616.0;
        return p;
    }
    *error = rne_product_error(a, b, p);
    return p;
}

/* sin(x + y) for |x| <= pi/4 and a tail |y| << ulp(x) (fdlibm's __kernel_sin). */
static double rne_sin_kernel(double x, double y) {
    const double *s = rne_sin_coefficients;
    const double z = x * x;
    const double v = z * x;
    const double r = s[1] + z * (s[2] + z * (s[3] + z * (s[4] + z * s[5])));
    return x - ((z * (0.5 * y - v * r) - y) - v * s[0]);
}

/* cos(x + y) for |x| <= pi/4 and a tail |y| << ulp(x) (fdlibm's __kernel_cos as in musl). */
static double rne_cos_kernel(double x, double y) {
    const double *c = rne_cos_coefficients;
    const double z = x * x;
    const double w = z * z;
    const double r = z * (c[0] + z * (c[1] + z * c[2])) + w * w * (c[3] + z * (c[4] + z * c[5]));
    const double hz = 0.5 * z;
    const double one_minus_hz = 1.0 - hz;
    return one_minus_hz + (((1.0 - one_minus_hz) - hz) + (z * r - x * y));
}

/* sin and cos of any x, NaN for infinite or NaN x: x = k pi/2 + r with x 2/pi in fixed point
 * from the 192 bits of 2/pi that matter for x (trig/large.rs). Cold and never inlined, so that
 * the fast path is small enough to be inlined into the kernels, where the sines and cosines
 * of several joints then interleave (about a tenth off UR5's inverse dynamics at -O2). */
#if defined(__GNUC__)
__attribute__((cold, noinline))
#endif
static void rne_sin_cos_large(double x, double *sin_x, double *cos_x) {
    static const double half_pi_hi = 1.5707963267948966, half_pi_lo = 6.123233995736766e-17;
    static const double two_pow_minus_128 = 2.9387358770557188e-39;
    const uint64_t bits = rne_bits(x) & ~(UINT64_C(1) << 63);
    const uint64_t m = (bits & ((UINT64_C(1) << 52) - 1)) | (UINT64_C(1) << 52);
    const int e = (int)(bits >> 52) - 1075;
    const unsigned first = e - 2 > 0 ? (unsigned)(e - 2) : 0, word = first / 64, offset = first % 64;
    const unsigned t = (unsigned)((int)first + 192 - e);
    uint64_t window[3], product[4] = {0, 0, 0, 0}, carry = 0;
    unsigned quadrant;
    struct rne_u128 fraction, whole;
    double hi, lo, p, p_error, tail, r_hi, r_lo, s, c;
    int i;
    if (!(x - x == 0.0)) {
        /* Rust's f64::NAN. */
        *sin_x = rne_from_bits(UINT64_C(0x7FF8000000000000));
        *cos_x = *sin_x;
        return;
    }
    for (i = 0; i < 3; i++) {
        window[i] = offset == 0 ? rne_two_over_pi[word + i]
                                : (rne_two_over_pi[word + i] << offset) |
                                      (rne_two_over_pi[word + i + 1] >> (64 - offset));
    }
    for (i = 0; i < 3; i++) {
        const struct rne_u128 digit = rne_mul_64(m, window[2 - i], carry);
        product[i] = digit.lo;
        carry = digit.hi;
    }
    product[3] = carry;
    quadrant = (unsigned)(rne_shift_right(product, t) & 3);
    fraction.lo = rne_shift_right(product, t - 128);
    fraction.hi = rne_shift_right(product, t - 64);
    if (fraction.hi >> 63) {
        quadrant += 1;
    }
    quadrant &= 3;
    hi = rne_i128_to_f64(fraction);
    whole = rne_f64_to_i128(hi);
    whole.hi = fraction.hi - whole.hi - (fraction.lo < whole.lo);
    whole.lo = fraction.lo - whole.lo;
    lo = rne_i128_to_f64(whole);
    hi = hi * two_pow_minus_128;
    lo = lo * two_pow_minus_128;
    p = rne_two_prod(hi, half_pi_hi, &p_error);
    tail = p_error + (hi * half_pi_lo + lo * half_pi_hi);
    r_hi = p + tail;
    r_lo = tail - (r_hi - p);
    if (x < 0.0) {
        quadrant = (4 - quadrant) & 3;
        r_hi = -r_hi;
        r_lo = -r_lo;
    }
    s = rne_sin_kernel(r_hi, r_lo);
    c = rne_cos_kernel(r_hi, r_lo);
    switch (quadrant) {
    case 0: *sin_x = s; *cos_x = c; break;
    case 1: *sin_x = c; *cos_x = -s; break;
    case 2: *sin_x = -s; *cos_x = -c; break;
    default: *sin_x = -c; *cos_x = s; break;
    }
}

/* --- The fast path (trig.rs fast_path and reduced) ---------------------------------------- */

/* sin x and cos x, within 1 ulp for |x| <= 100. */
static inline void rne_sin_cos(double x, double *sin_x, double *cos_x) {
    const double shifted = rne_mul_add(x, RNE_FRAC_2_PI, RNE_ROUND);
    const double k = shifted - RNE_ROUND;
    const double r = rne_neg_mul_add(
        k, RNE_PIO2_2T, rne_neg_mul_add(k, RNE_PIO2_2, rne_neg_mul_add(k, RNE_PIO2_1, x)));
    const double z = r * r;
    const double z2 = z * z;
    const double sin_r = rne_mul_add(r * z, rne_polynomial(z, z2, rne_sin_coefficients), r);
    const double cos_r =
        1.0 - rne_neg_mul_add(z2, rne_polynomial(z, z2, rne_cos_coefficients), 0.5 * z);
    /* Quadrant k mod 4 from the low bits of the shifted value: odd quadrants swap sine and
     * cosine; 2 and 3 negate the sine, 1 and 2 the cosine. */
    const uint64_t quadrant = rne_bits(shifted) & 3;
    const uint64_t swap = (uint64_t)0 - (quadrant & 1);
    const uint64_t s = rne_bits(sin_r), c = rne_bits(cos_r);
    if (!(k < 1048576.0 && k > -1048576.0)) {
        rne_sin_cos_large(x, sin_x, cos_x);
        return;
    }
    *sin_x = rne_from_bits(((s & ~swap) | (c & swap)) ^ ((quadrant & 2) << 62));
    *cos_x = rne_from_bits(((c & ~swap) | (s & swap)) ^ (((quadrant + 1) & 2) << 62));
}
