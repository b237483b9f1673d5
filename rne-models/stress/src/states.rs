//! Seeded random joint values for the stress states.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The generator of every stress case: ChaCha8, so that a seed gives the same states on
/// every platform.
pub fn generator(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// `n` values uniform in [−bound, bound].
pub fn uniform(rng: &mut ChaCha8Rng, n: usize, bound: f64) -> Vec<f64> {
    (0..n).map(|_| rng.gen_range(-bound..=bound)).collect()
}

/// `n` values of magnitude uniform in [lo, hi] with random signs: states at a given scale,
/// none of them accidentally small.
pub fn magnitudes(rng: &mut ChaCha8Rng, n: usize, lo: f64, hi: f64) -> Vec<f64> {
    (0..n)
        .map(|_| {
            let x = rng.gen_range(lo..=hi);
            if rng.gen_bool(0.5) {
                x
            } else {
                -x
            }
        })
        .collect()
}
