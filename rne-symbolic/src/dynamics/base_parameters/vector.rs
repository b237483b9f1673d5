//! The two vector operations of the base parameters' Gram–Schmidt (`Split::of`): a dot
//! product and `r ← r − p·q`, with the bits of nalgebra's `dot` and `axpy`, so that the base
//! parameters found are those nalgebra would find.
//!
//! They are most of the work of finding a large robot's base parameters (docs/performance.md,
//! "What a load is made of"). Where the processor has AVX2 (detected at run time) the same loops are compiled for it, four entries
//! per instruction instead of two: each entry's product and sum are the same IEEE operations
//! in the same order (no multiply–add is fused: AVX2 alone does not enable FMA), so the bits
//! are the same on either path.

/// `a · b` with the bits of nalgebra's `dot` (eight partial sums over the entries' indices
/// modulo eight, added in its order, then the remainder), on slices: the compiler keeps the
/// partial sums in vector registers, where nalgebra's strided loop reads one entry at a time.
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2 (detected just above).
        return unsafe { dot_avx2(a, b) };
    }
    dot_portable(a, b)
}

/// `r ← r − p·q` entry by entry: the bits of nalgebra's `r.axpy(−p, q, 1.0)`, which computes
/// `(−p·q)·1 + 1·r`, without its two products by one.
pub(super) fn subtract_scaled(r: &mut [f64], p: f64, q: &[f64]) {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2 (detected just above).
        unsafe { subtract_scaled_avx2(r, p, q) };
        return;
    }
    subtract_scaled_portable(r, p, q);
}

/// [`dot`] for any x86-64 or other processor.
#[inline(always)]
fn dot_portable(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let whole = n - n % 8;
    let mut acc = [0.0f64; 8];
    for (x, y) in a[..whole].chunks_exact(8).zip(b[..whole].chunks_exact(8)) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    let mut sum = 0.0;
    for k in 0..4 {
        sum += acc[k] + acc[k + 4];
    }
    for k in whole..n {
        sum += a[k] * b[k];
    }
    sum
}

/// [`subtract_scaled`] for any x86-64 or other processor.
#[inline(always)]
fn subtract_scaled_portable(r: &mut [f64], p: f64, q: &[f64]) {
    for (r, &q) in r.iter_mut().zip(q) {
        *r += -p * q;
    }
}

/// [`dot_portable`] compiled for AVX2.
///
/// # Safety
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn dot_avx2(a: &[f64], b: &[f64]) -> f64 {
    dot_portable(a, b)
}

/// [`subtract_scaled_portable`] compiled for AVX2.
///
/// # Safety
/// The processor must have AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn subtract_scaled_avx2(r: &mut [f64], p: f64, q: &[f64]) {
    subtract_scaled_portable(r, p, q);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::base_parameters::SplitMix;
    use nalgebra::DVector;

    type Dot = fn(&[f64], &[f64]) -> f64;
    type SubtractScaled = fn(&mut [f64], f64, &[f64]);

    /// Each path this processor can take: the portable one, and the AVX2 one where it has
    /// AVX2.
    fn paths() -> Vec<(&'static str, Dot, SubtractScaled)> {
        let mut paths: Vec<(&'static str, Dot, SubtractScaled)> =
            vec![("portable", dot_portable, subtract_scaled_portable)];
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY (both): the processor has AVX2 (detected just above).
            let dot: Dot = |a, b| unsafe { dot_avx2(a, b) };
            let subtract: SubtractScaled = |r, p, q| unsafe { subtract_scaled_avx2(r, p, q) };
            paths.push(("avx2", dot, subtract));
        }
        paths
    }

    /// Every path gives nalgebra's bits on vectors of every length around the eight-entry
    /// blocks and a long one: the base parameters do not depend on which computes.
    #[test]
    fn dot_and_subtract_scaled_are_nalgebras_bits_on_every_path() {
        for (path, dot, subtract_scaled) in paths() {
            let mut random = SplitMix(0x0d07);
            for n in (0..=25).chain([1960]) {
                let a = DVector::from_fn(n, |_, _| {
                    random.uniform(-3.0, 3.0) * 1e3f64.powf(random.uniform(-1.0, 1.0))
                });
                let b = DVector::from_fn(n, |_, _| random.uniform(-3.0, 3.0));
                assert_eq!(
                    dot(a.as_slice(), b.as_slice()).to_bits(),
                    a.dot(&b).to_bits(),
                    "{path}, n = {n}"
                );
                let p = random.uniform(-2.0, 2.0);
                let mut ours = b.clone();
                subtract_scaled(ours.as_mut_slice(), p, a.as_slice());
                let mut theirs = b.clone();
                theirs.axpy(-p, &a, 1.0);
                assert!(
                    ours.iter()
                        .zip(&theirs)
                        .all(|(x, y)| x.to_bits() == y.to_bits()),
                    "{path}, n = {n}"
                );
            }
        }
    }
}
