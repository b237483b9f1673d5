//! A progress bar for long runs, on a terminal only.

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressStyle};

use rne_runtime::Dynamics;
use rne_sim::{Controller, Integrator, SimError, State, Stats};

/// Wraps an integrator and advances a progress bar (on standard error, only when it is a
/// terminal and progress was asked for) at every output time. The integration itself is the
/// wrapped integrator's, step for step: only the sink is observed.
pub struct WithProgress<'a, I> {
    inner: &'a I,
    bar: ProgressBar,
}

/// Progress steps of the bar per run.
const TICKS: u64 = 1000;

impl<'a, I> WithProgress<'a, I> {
    /// `inner` with a bar labelled `label` when `show` is set and standard error is a terminal.
    pub fn new(inner: &'a I, label: &str, show: bool) -> Self {
        let bar = if show && std::io::stderr().is_terminal() {
            let bar = ProgressBar::new(TICKS);
            let style =
                ProgressStyle::with_template("{msg:>28} [{bar:40}] {percent:>3}% {elapsed}")
                    .map(|s| s.progress_chars("=> "));
            if let Ok(style) = style {
                bar.set_style(style);
            }
            bar.set_message(label.to_owned());
            bar
        } else {
            ProgressBar::hidden()
        };
        Self { inner, bar }
    }
}

impl<const N: usize, I: Integrator<N>> Integrator<N> for WithProgress<'_, I> {
    fn integrate<D, C, F>(
        &self,
        model: &D,
        controller: &C,
        x0: &State<N>,
        times: &[f64],
        mut sink: F,
    ) -> Result<Stats, SimError>
    where
        D: Dynamics<N, N, Scalar = f64> + ?Sized,
        C: Controller<N> + ?Sized,
        F: FnMut(f64, &State<N>),
    {
        let (t0, t_end) = match times {
            [first, .., last] => (*first, *last),
            _ => (0.0, 1.0),
        };
        let span = (t_end - t0).max(f64::MIN_POSITIVE);
        let bar = &self.bar;
        let result = self.inner.integrate(model, controller, x0, times, |t, x| {
            sink(t, x);
            // Truncation is intended: a whole number of ticks in 0..=TICKS.
            bar.set_position(((t - t0) / span * TICKS as f64) as u64);
        });
        bar.finish_and_clear();
        result
    }
}
