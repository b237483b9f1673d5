//! A batch's states computed with the GIL released. A kernel whose result is its whole output
//! writes it in place, on one thread or several (rne-jit's batch functions), and so does one
//! whose result is a tuple of its matrices (∂ID, ∂FD: each matrix into its array); the others
//! (placements) are computed a chunk of states at a time into a buffer that stays in the
//! processor's cache and gathered from it into their arrays, each thread taking the next
//! chunk when it has finished its last (`rne_jit::share`). The values are the same whatever
//! the chunks and threads: every state is one call of the same kernel.

use rne_codegen_core::Kernel;
use rne_jit::share::for_each_shared;
use rne_jit::{Batch, JitError, JitModel};

use crate::layout::{self, Part};

/// States computed per chunk before their values are gathered: a few tens of kilobytes of
/// values for the larger kernels, so that they are gathered from the cache.
const CHUNK: usize = 32;

/// The fewest states a thread is started for. Threads are started per call (scoped), and
/// starting one costs as much as an arm's inverse dynamics at a hundred or so states
/// (docs/python.md), so a batch takes at most one thread per this many states.
const MIN_STATES_PER_THREAD: usize = 256;

/// The output slices of a batch or of a chunk of it, one per part of the result.
type Slices<'o> = Vec<&'o mut [f64]>;

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
    /// Whether the parts are the kernel's matrices, each written in place into its array
    /// (`rne_jit`'s `evaluate_batch_matrices`).
    pub matrices: bool,
}

impl<'a> Job<'a> {
    /// Computes `n` states into `outs` (one slice per part, each `n · part.len()` long) on at
    /// most `threads` threads ([`MIN_STATES_PER_THREAD`]).
    pub fn run(&self, n: usize, outs: Slices<'_>, threads: usize) -> Result<(), JitError> {
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
        if self.matrices {
            let mut outs = outs;
            return match threads {
                1 => model.evaluate_batch_matrices(kernel, self.states, &mut outs),
                t => model.evaluate_batch_matrices_threaded(kernel, self.states, &mut outs, t),
            };
        }
        let chunks = Chunks {
            outs,
            parts: self.parts,
            start: 0,
            n,
        };
        let buffer = || vec![0.0; CHUNK.min(n) * self.per];
        for_each_shared(chunks, threads, buffer, |values, (start, k, outs)| {
            self.chunk(start, k, outs, values)
        })
    }

    /// States `start..start + k` (at most [`CHUNK`]; `outs` are their slices) computed into
    /// `values` and gathered from there.
    fn chunk(
        &self,
        start: usize,
        k: usize,
        mut outs: Slices<'_>,
        values: &mut [f64],
    ) -> Result<(), JitError> {
        let buffer = &mut values[..k * self.per];
        self.model
            .evaluate_batch(self.kernel, self.slice(start, k), buffer)?;
        layout::gather(buffer, self.per, self.parts, &mut outs, 0);
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

/// A batch's output slices cut into chunks of [`CHUNK`] states: (first state, states, the
/// chunk's slice of each part).
struct Chunks<'o, 'p> {
    /// The slices of the states not handed out yet.
    outs: Slices<'o>,
    /// The arrays of the result.
    parts: &'p [Part],
    /// The first state not handed out yet.
    start: usize,
    /// The number of states.
    n: usize,
}

impl<'o> Iterator for Chunks<'o, '_> {
    type Item = (usize, usize, Slices<'o>);

    fn next(&mut self) -> Option<Self::Item> {
        let k = CHUNK.min(self.n - self.start);
        if k == 0 {
            return None;
        }
        let outs = std::mem::take(&mut self.outs);
        let (mut chunk, mut rest) = (Slices::new(), Slices::new());
        for (out, part) in outs.into_iter().zip(self.parts) {
            let (a, b) = out.split_at_mut(k * part.len());
            chunk.push(a);
            rest.push(b);
        }
        self.outs = rest;
        let start = self.start;
        self.start += k;
        Some((start, k, chunk))
    }
}
