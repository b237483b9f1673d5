//! The timing harness: several implementations timed in short interleaved batches, summarised
//! by robust statistics.
//!
//! # Method
//!
//! 1. **Calibration and warm-up.** For each subject, the number of calls per batch starts at 1
//!    and doubles until one batch takes at least [`Plan::batch`]; the batches run while
//!    calibrating warm the caches and the branch predictors.
//! 2. **Interleaved rounds.** Each of [`Plan::rounds`] rounds times one batch of every subject,
//!    starting with subject `r mod n` in round `r` so that no subject always runs first. A
//!    change of machine load lasting longer than a round (a few milliseconds) hits every
//!    subject alike.
//! 3. **Statistics.** A batch gives one sample: its wall-clock time ([`Instant`]) divided by its
//!    number of calls. Each subject's samples give the median and the interquartile range; the
//!    ratio of two subjects is the median over rounds of the ratio of their samples in the same
//!    round, which cancels load changes slower than a round.
//!
//! The subjects do their own calls ([`Timed::run`]): inputs and results pass through
//! [`std::hint::black_box`], and nothing in the harness allocates between the clock readings.

use std::time::{Duration, Instant};

/// Something to time: a batch of `calls` calls.
pub trait Timed {
    /// Makes `calls` calls.
    fn run(&mut self, calls: u64);
}

/// How long to time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plan {
    /// The shortest batch.
    pub batch: Duration,
    /// Number of interleaved rounds (samples per subject).
    pub rounds: usize,
}

/// One subject's timing: a sample of ns per call per round.
#[derive(Clone, Debug, PartialEq)]
pub struct Timing {
    /// ns per call in each round, in round order.
    pub samples: Vec<f64>,
    /// Calls per batch.
    pub calls: u64,
}

impl Timing {
    /// Median ns per call.
    pub fn median(&self) -> f64 {
        quantile(&self.samples, 0.5)
    }

    /// Interquartile range of ns per call: (first quartile, third quartile).
    pub fn quartiles(&self) -> (f64, f64) {
        (quantile(&self.samples, 0.25), quantile(&self.samples, 0.75))
    }

    /// The median over rounds of `self / other`, ns per call in the same round.
    pub fn ratio_to(&self, other: &Timing) -> f64 {
        let ratios: Vec<f64> = self
            .samples
            .iter()
            .zip(&other.samples)
            .map(|(a, b)| a / b)
            .collect();
        quantile(&ratios, 0.5)
    }
}

/// The `p`-quantile of `values` (linear interpolation between order statistics; NaN when
/// empty).
pub fn quantile(values: &[f64], p: f64) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    match sorted.len() {
        0 => f64::NAN,
        n => {
            let position = p.clamp(0.0, 1.0) * (n - 1) as f64;
            let below = position.floor() as usize;
            let above = (below + 1).min(n - 1);
            let weight = position - below as f64;
            sorted[below] * (1.0 - weight) + sorted[above] * weight
        }
    }
}

/// Times `subjects` by the method of the module documentation.
pub fn time_interleaved(subjects: &mut [&mut dyn Timed], plan: &Plan) -> Vec<Timing> {
    let calls: Vec<u64> = subjects
        .iter_mut()
        .map(|subject| calibrate(&mut **subject, plan.batch))
        .collect();
    let n = subjects.len();
    let mut samples = vec![Vec::with_capacity(plan.rounds); n];
    for round in 0..plan.rounds {
        for offset in 0..n {
            let j = (round + offset) % n;
            let start = Instant::now();
            subjects[j].run(calls[j]);
            let elapsed = start.elapsed();
            samples[j].push(elapsed.as_secs_f64() * 1e9 / calls[j] as f64);
        }
    }
    samples
        .into_iter()
        .zip(calls)
        .map(|(samples, calls)| Timing { samples, calls })
        .collect()
}

/// The number of calls (a power of two) for which one batch of `subject` takes at least
/// `batch`.
fn calibrate(subject: &mut dyn Timed, batch: Duration) -> u64 {
    let mut calls = 1u64;
    loop {
        let start = Instant::now();
        subject.run(calls);
        if start.elapsed() >= batch || calls >= 1 << 40 {
            return calls;
        }
        calls *= 2;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Quantiles interpolate between order statistics; ratios pair samples of the same round.
    #[test]
    fn statistics() {
        assert_eq!(quantile(&[3.0, 1.0, 2.0], 0.5), 2.0);
        assert_eq!(quantile(&[1.0, 2.0, 3.0, 4.0], 0.5), 2.5);
        assert_eq!(quantile(&[1.0, 2.0, 3.0, 4.0, 5.0], 0.25), 2.0);
        assert!(quantile(&[], 0.5).is_nan());
        let a = Timing {
            samples: vec![10.0, 40.0, 12.0],
            calls: 1,
        };
        let b = Timing {
            samples: vec![5.0, 20.0, 4.0],
            calls: 1,
        };
        assert_eq!(a.ratio_to(&b), 2.0);
        assert_eq!(a.median(), 12.0);
        assert_eq!(a.quartiles(), (11.0, 26.0));
    }
}
