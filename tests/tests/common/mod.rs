//! Shared test helpers: seeded random states and error measures.

#![allow(dead_code)]

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A deterministic random generator for one test.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// `n` values uniform in `[-bound, bound]`.
pub fn uniform(rng: &mut ChaCha8Rng, n: usize, bound: f64) -> Vec<f64> {
    (0..n).map(|_| rng.gen_range(-bound..=bound)).collect()
}

/// A random state: |q| ≤ π, |q̇| ≤ 10, |q̈| ≤ 10.
pub fn state(rng: &mut ChaCha8Rng, n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    (
        uniform(rng, n, std::f64::consts::PI),
        uniform(rng, n, 10.0),
        uniform(rng, n, 10.0),
    )
}

/// Normwise relative error ‖a − b‖∞ / ‖b‖∞ (absolute error when ‖b‖∞ < 1e-300).
pub fn rel_err(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "compared vectors differ in length");
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    let scale = b.iter().map(|y| y.abs()).fold(0.0, f64::max);
    if scale < 1e-300 {
        diff
    } else {
        diff / scale
    }
}

/// ‖a − b‖∞ / max(‖b‖∞, floor): relative error, absolute below `floor` (for quantities that
/// can vanish, where the reference holds only rounding noise).
pub fn rel_err_floor(a: &[f64], b: &[f64], floor: f64) -> f64 {
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    let scale = b.iter().map(|y| y.abs()).fold(floor, f64::max);
    diff / scale
}

/// Flattens a row-major matrix.
pub fn flat(m: &[Vec<f64>]) -> Vec<f64> {
    m.concat()
}

/// `m v`.
pub fn mat_vec(m: &[Vec<f64>], v: &[f64]) -> Vec<f64> {
    m.iter()
        .map(|row| row.iter().zip(v).map(|(a, b)| a * b).sum())
        .collect()
}

/// The worst error seen, and where.
#[derive(Default, Debug)]
pub struct Worst {
    pub error: f64,
    pub sample: usize,
}

impl Worst {
    pub fn record(&mut self, error: f64, sample: usize) {
        if error > self.error || error.is_nan() {
            self.error = error;
            self.sample = sample;
        }
    }
}
