//! A batch's states computed with the GIL released. A kernel whose result is its whole output
//! writes it in place, on one thread or several (rne-jit's batch functions); the others
//! (tuples of matrices, placements) are computed a chunk of states at a time into a buffer
//! that stays in the processor's cache and gathered from it into their arrays, each thread
//! taking a contiguous share of the states. The values are the same whatever the chunks and
//! threads: every state is one call of the same kernel.

use rne_codegen_core::Kernel;
use rne_jit::{Batch, JitError, JitModel};

use crate::layout::{self, Part};

/// States computed per chunk before their values are gathered: a few tens of kilobytes of
/// values for the larger kernels, so that they are gathered from the cache.
const CHUNK: usize = 32;

/// The fewest states a thread is started for. Threads are started per call (scoped), and
/// starting one costs as much as an arm's inverse dynamics at a hundred or so states
/// (docs/python.md), so a batch takes at most one thread per this many states.
const MIN_STATES_PER_THREAD: usize = 256;

/// One kernel over a batch of states.
pub(crate) struct Job<'a> {
    /// The compiled kernels.
    pub model: &'a JitModel,
    /// The kernel.
    pub kernel: Kernel,
    /// The states' inputs, end to end.
    pub states: Batch<'a>,
    /// Values per state of the kernel's output.
    pub per: usize,
    /// The arrays of the result.
    pub parts: &'a [Part],
    /// Whether the one part is the whole output in order (written in place).
    pub whole: bool,
}

impl<'a> Job<'a> {
    /// Computes `n` states into `outs` (one slice per part, each `n · part.len()` long) on at
    /// most `threads` threads ([`MIN_STATES_PER_THREAD`]).
    pub fn run(&self, n: usize, outs: Vec<&mut [f64]>, threads: usize) -> Result<(), JitError> {
        let (model, kernel) = (self.model, self.kernel);
        if n == 0 {
            return Ok(());
        }
        let threads = threads.min(n.div_ceil(MIN_STATES_PER_THREAD)).max(1);
        if self.whole {
            let Some(out) = outs.into_iter().next() else {
                return Ok(());
            };
            return match threads {
                1 => model.evaluate_batch(kernel, self.states, out),
                t => model.evaluate_batch_threaded(kernel, self.states, out, t),
            };
        }
        if threads <= 1 {
            return self.chunks(0, n, outs);
        }
        let share = n.div_ceil(threads);
        let shares = self.split(n, share, outs);
        std::thread::scope(|scope| {
            let handles: Vec<_> = shares
                .into_iter()
                .map(|(start, count, outs)| scope.spawn(move || self.chunks(start, count, outs)))
                .collect();
            handles
                .into_iter()
                .try_for_each(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
        })
    }

    /// The output slices split into shares of `share` states: (first state, states, slices).
    fn split<'o>(
        &self,
        n: usize,
        share: usize,
        mut outs: Vec<&'o mut [f64]>,
    ) -> Vec<(usize, usize, Vec<&'o mut [f64]>)> {
        let mut shares = Vec::new();
        let mut start = 0;
        while start < n {
            let count = share.min(n - start);
            let (mut mine, mut rest) = (Vec::new(), Vec::new());
            for (out, part) in outs.into_iter().zip(self.parts) {
                let (a, b) = out.split_at_mut(count * part.len());
                mine.push(a);
                rest.push(b);
            }
            shares.push((start, count, mine));
            outs = rest;
            start += count;
        }
        shares
    }

    /// States `start..start + count` a chunk at a time, gathered into `outs` (the slices of
    /// those states).
    fn chunks(
        &self,
        start: usize,
        count: usize,
        mut outs: Vec<&mut [f64]>,
    ) -> Result<(), JitError> {
        let mut values = vec![0.0; CHUNK.min(count) * self.per];
        let mut done = 0;
        while done < count {
            let k = CHUNK.min(count - done);
            let buffer = &mut values[..k * self.per];
            let states = self.slice(start + done, k);
            self.model.evaluate_batch(self.kernel, states, buffer)?;
            layout::gather(buffer, self.per, self.parts, &mut outs, done);
            done += k;
        }
        Ok(())
    }

    /// The inputs of states `start..start + k` (the arrays the kernel does not take stay empty).
    fn slice(&self, start: usize, k: usize) -> Batch<'a> {
        let (nq, nv) = (self.model.nq(), self.model.nv());
        let cut = |values: &'a [f64], width: usize| match values.is_empty() {
            true => values,
            false => &values[start * width..(start + k) * width],
        };
        Batch {
            q: cut(self.states.q, nq),
            qd: cut(self.states.qd, nv),
            qdd: cut(self.states.qdd, nv),
            tau: cut(self.states.tau, nv),
        }
    }
}
