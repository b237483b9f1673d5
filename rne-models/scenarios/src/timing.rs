//! Timing of the thesis's 70 s double-pendulum run (figure 6.4) at its solver setting.

use std::time::{Duration, Instant};

use super::experiments::released;
use super::parameters::{thesis_solver, RELEASE_END, SAMPLE};
use rne_sim::{output_times, SimError, Stats};

/// Wall-clock times of repeated runs.
#[derive(Clone, Copy, Debug)]
pub struct Timing {
    /// Runs timed.
    pub runs: usize,
    /// The fastest run.
    pub best: Duration,
    /// The median run.
    pub median: Duration,
    /// The integrator's work in one run (identical in every run).
    pub stats: Stats,
    /// Samples recorded per run.
    pub samples: usize,
}

/// Times `runs` (at least 1) repetitions of the released double pendulum from q = 0 over 70 s
/// with Dormand–Prince at rtol 1e-10, atol 1e-12 ([`thesis_solver`]) on the generated kernels,
/// recording every 10 ms (7001 samples of state, input and energies), as the `double-pendulum`
/// scenario does. Meaningful in release builds only.
pub fn time_thesis_release(runs: usize) -> Result<Timing, SimError> {
    let times = output_times(0.0, RELEASE_END, SAMPLE);
    let solver = thesis_solver();
    let mut elapsed = Vec::with_capacity(runs.max(1));
    let mut last = None;
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        let record = released([0.0, 0.0], &solver, &times)?;
        elapsed.push(start.elapsed());
        last = Some((record.stats, record.len()));
    }
    elapsed.sort();
    let (stats, samples) = last.unwrap_or_default();
    Ok(Timing {
        runs: elapsed.len(),
        best: elapsed[0],
        median: elapsed[elapsed.len() / 2],
        stats,
        samples,
    })
}
