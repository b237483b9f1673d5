//! rne's side of the comparison with Pinocchio, timed beside each run of its scripts.
//!
//! The scripts are separate processes, timed one after the other; on a shared machine whose
//! speed changes over minutes, a ratio of two times taken minutes apart measures the machine
//! as much as the code (docs/performance.md, "Method", gives an example). So right after each
//! run of the scripts on a robot, rne's generated `f64` kernels of [`COMPARISONS`] are timed
//! together ([`time_compared`]), and each ratio is the median over runs of Pinocchio's time in
//! the run over rne's time right after it ([`PairedTimes::ratio`]), as the harness pairs the
//! rounds of implementations timed together ([`crate::timing::Timing::ratio_to`]).

use std::collections::BTreeMap;

use rne_codegen::Kernel;

use crate::control;
use crate::error::BenchError;
use crate::kernels::time;
use crate::pinocchio::COMPARISONS;
use crate::robots::{generated_subject, Cases, BENCHED};
use crate::timing::{quantile, Plan};

/// ns per call of rne's generated `f64` kernel of each quantity of [`COMPARISONS`] that the
/// robot has, timed together by [`crate::timing::time_interleaved`] on the first `pool`
/// states: the median over rounds.
pub fn time_compared(
    cases: &Cases,
    plan: &Plan,
    pool: usize,
) -> Result<BTreeMap<Kernel, f64>, BenchError> {
    let mut kernels = Vec::new();
    let mut candidates = Vec::new();
    let mut control = if control::has_control(cases.robot.name) {
        control::generated(cases, pool)?
    } else {
        Vec::new()
    };
    for comparison in COMPARISONS {
        let kernel = comparison.kernel;
        let candidate = if BENCHED.contains(&kernel) {
            generated_subject(kernel, cases, pool)?
        } else {
            control
                .iter()
                .position(|(k, _)| *k == kernel)
                .map(|i| control.swap_remove(i).1)
        };
        if let Some(candidate) = candidate {
            kernels.push(kernel);
            candidates.push(candidate);
        }
    }
    let timings = time(&mut candidates, plan);
    Ok(kernels
        .into_iter()
        .zip(timings)
        .map(|(kernel, timing)| (kernel, timing.median()))
        .collect())
}

/// Pinocchio's figures and rne's times of one robot, run by run: `rne[r]` was timed right
/// after the scripts printed `peer[r]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PairedTimes {
    /// Each run's figures of the scripts, keyed `prefix.name` (`run.rnea_ns`, `cg.cg_aba_ns`).
    pub peer: Vec<BTreeMap<String, f64>>,
    /// rne's ns per call right after each run ([`time_compared`]).
    pub rne: Vec<BTreeMap<Kernel, f64>>,
}

impl PairedTimes {
    /// Adds one run: the scripts' figures and rne's times right after them.
    pub fn push(&mut self, peer: BTreeMap<String, f64>, rne: BTreeMap<Kernel, f64>) {
        self.peer.push(peer);
        self.rne.push(rne);
    }

    /// Number of runs.
    pub fn runs(&self) -> usize {
        self.peer.len()
    }

    /// rne's ns per call of `kernel`: the median over runs; NaN if it was never timed.
    pub fn rne(&self, kernel: Kernel) -> f64 {
        let times: Vec<f64> = self
            .rne
            .iter()
            .filter_map(|run| run.get(&kernel).copied())
            .collect();
        quantile(&times, 0.5)
    }

    /// How many times faster rne's `kernel` is than Pinocchio's figure `key`: the median over
    /// the runs that printed `key` of that run's figure over rne's time right after it; NaN
    /// if no run has both.
    pub fn ratio(&self, key: &str, kernel: Kernel) -> f64 {
        let ratios: Vec<f64> = self
            .peer
            .iter()
            .zip(&self.rne)
            .filter_map(|(peer, rne)| Some(peer.get(key)? / rne.get(&kernel)?))
            .collect();
        quantile(&ratios, 0.5)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(
        peer: &[(&str, f64)],
        rne: &[(Kernel, f64)],
    ) -> (BTreeMap<String, f64>, BTreeMap<Kernel, f64>) {
        (
            peer.iter().map(|&(k, v)| (k.to_owned(), v)).collect(),
            rne.iter().copied().collect(),
        )
    }

    /// A ratio pairs each run's figure with rne's time right after it, not the medians of
    /// the two sides: a run in which both sides were twice as slow leaves it alone, and runs
    /// without the figure (`run_cg.sh` takes part in the first runs only) are left out.
    #[test]
    fn a_ratio_pairs_each_run_with_the_time_right_after_it() {
        let id = Kernel::InverseDynamics;
        let mut paired = PairedTimes::default();
        let (p, r) = run(
            &[("run.rnea_ns", 400.0), ("cg.cg_rnea_ns", 200.0)],
            &[(id, 50.0)],
        );
        paired.push(p, r);
        let (p, r) = run(&[("run.rnea_ns", 800.0)], &[(id, 100.0)]);
        paired.push(p, r);
        let (p, r) = run(&[("run.rnea_ns", 400.0)], &[(id, 100.0)]);
        paired.push(p, r);
        assert_eq!(paired.runs(), 3);
        assert_eq!(paired.rne(id), 100.0);
        // Per run 8, 8 and 4: median 8, where the medians of the sides would give 4.
        assert_eq!(paired.ratio("run.rnea_ns", id), 8.0);
        // Only the first run timed the generated code: 200 / 50.
        assert_eq!(paired.ratio("cg.cg_rnea_ns", id), 4.0);
        assert!(paired.ratio("cg.cg_crba_ns", id).is_nan());
        assert!(paired.ratio("run.rnea_ns", Kernel::MassMatrix).is_nan());
        assert!(paired.rne(Kernel::MassMatrix).is_nan());
    }
}
