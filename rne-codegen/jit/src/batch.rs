//! Batches: one kernel at many states, the states' arrays laid end to end, on one thread or
//! shared between several.

use rne_codegen_core::{Input, Kernel};

use crate::code::Out;
use crate::error::JitError;
use crate::lanes::{Pair, LANES};
use crate::model::{JitModel, State};
#[cfg(feature = "threads")]
use crate::share::for_each_shared;

/// The arrays of N states, each laid end to end (state i's q is `q[i·NQ..(i+1)·NQ]`); the
/// arrays a kernel does not take may be empty.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct Batch<'a> {
    /// N configurations.
    pub q: &'a [f64],
    /// N velocities.
    pub qd: &'a [f64],
    /// N accelerations.
    pub qdd: &'a [f64],
    /// N generalised forces.
    pub tau: &'a [f64],
}

impl<'a> Batch<'a> {
    /// The array of `input`, every state's end to end (as [`State::input`] for one state).
    fn input(&self, input: Input) -> &'a [f64] {
        let Batch { q, qd, qdd, tau } = *self;
        State { q, qd, qdd, tau }.input(input)
    }
}

/// States a thread of a shared batch takes at a time: a whole number of pairs of lanes, and
/// enough work (tens of microseconds for an arm's ID) that taking them costs nothing.
#[cfg(feature = "threads")]
pub(crate) const SHARED_CHUNK: usize = 64;

impl JitModel {
    /// `kernel` at every state of `batch`, results laid end to end in `out`: the number of
    /// states is `out.len()` over the kernel's [`JitModel::output_len`], and every array the
    /// kernel takes must hold that many states. Each state is checked as
    /// [`JitModel::evaluate`] checks one.
    pub fn evaluate_batch(
        &self,
        kernel: Kernel,
        batch: Batch<'_>,
        out: &mut [f64],
    ) -> Result<(), JitError> {
        let states = self.batch_states(kernel, &batch, out.len())?;
        let per = self.compiled_kernel(kernel)?.outputs().max(1);
        self.evaluate_share(kernel, &batch, 0, &mut out[..states * per])
    }

    /// `kernel` at states `first`, `first + 1`, … of `batch` into `out`, one kernel's outputs
    /// per state, each state checked: two states a call in two lanes (`lanes.rs`), an odd
    /// last one alone.
    fn evaluate_share(
        &self,
        kernel: Kernel,
        batch: &Batch<'_>,
        first: usize,
        out: &mut [f64],
    ) -> Result<(), JitError> {
        let compiled = self.compiled_kernel(kernel)?;
        let per = compiled.outputs().max(1);
        if out.len() < LANES * per {
            return self.evaluate_singles(kernel, batch, first, out);
        }
        let Some(lane) = self.lane_kernel(kernel)? else {
            return self.evaluate_singles(kernel, batch, first, out);
        };
        let mut pair = Pair::new(lane);
        let done = out.len() / (LANES * per) * LANES;
        let (paired, rest) = out.split_at_mut(done * per);
        for (k, out) in paired.chunks_exact_mut(LANES * per).enumerate() {
            let at = first + LANES * k;
            let states = [self.state(batch, at), self.state(batch, at + 1)];
            self.run_pair(lane, (states, at), Out::Whole(out), &mut pair)?;
        }
        self.evaluate_singles(kernel, batch, first + done, rest)
    }

    /// [`JitModel::evaluate_share`] one state a call, one scratch array for all.
    fn evaluate_singles(
        &self,
        kernel: Kernel,
        batch: &Batch<'_>,
        first: usize,
        out: &mut [f64],
    ) -> Result<(), JitError> {
        let compiled = self.compiled_kernel(kernel)?;
        let mut scratch = compiled.scratch();
        let parameters = self.parameters();
        for (k, out) in out.chunks_mut(compiled.outputs().max(1)).enumerate() {
            let state = self.state(batch, first + k);
            if !self.admits(compiled, &state) {
                self.check_state(kernel, &state)
                    .map_err(|e| e.in_batch(first + k))?;
            }
            self.run_in(compiled, state, parameters, Out::Whole(out), &mut scratch);
        }
        Ok(())
    }

    /// [`JitModel::evaluate_batch`] on `threads` threads (scoped: they end before it returns),
    /// each taking the next 64 states (`SHARED_CHUNK`) when it has finished its last
    /// ([`for_each_shared`]). The results are those of one thread, bit for bit, and so is the
    /// error of a bad state (the first one's).
    #[cfg(feature = "threads")]
    pub fn evaluate_batch_threaded(
        &self,
        kernel: Kernel,
        batch: Batch<'_>,
        out: &mut [f64],
        threads: usize,
    ) -> Result<(), JitError> {
        let states = self.batch_states(kernel, &batch, out.len())?;
        let per = self.compiled_kernel(kernel)?.outputs().max(1);
        let threads = threads.clamp(1, states.div_ceil(SHARED_CHUNK).max(1));
        // The lanes compiled before the threads start.
        if states >= LANES {
            self.lane_kernel(kernel)?;
        }
        let chunks = out[..states * per]
            .chunks_mut(SHARED_CHUNK * per)
            .enumerate();
        for_each_shared(
            chunks,
            threads,
            || (),
            |(), (k, out)| self.evaluate_share(kernel, &batch, k * SHARED_CHUNK, out),
        )
    }

    /// State `i` of `batch`.
    pub(crate) fn state<'a>(&self, batch: &Batch<'a>, i: usize) -> State<'a> {
        let slice = |values: &'a [f64], n: usize| values.get(i * n..(i + 1) * n).unwrap_or(&[]);
        State {
            q: slice(batch.q, self.nq()),
            qd: slice(batch.qd, self.nv()),
            qdd: slice(batch.qdd, self.nv()),
            tau: slice(batch.tau, self.nv()),
        }
    }

    /// The number of states of a batch whose results fill `out_len` values, once every array
    /// the kernel takes is known to hold that many.
    pub(crate) fn batch_states(
        &self,
        kernel: Kernel,
        batch: &Batch<'_>,
        out_len: usize,
    ) -> Result<usize, JitError> {
        let per = self.compiled_kernel(kernel)?.outputs();
        if per == 0 || !out_len.is_multiple_of(per) {
            return Err(JitError::OutputLength {
                kernel,
                got: out_len,
                expected: per,
            });
        }
        let states = out_len / per;
        for &input in kernel.inputs() {
            let (values, n) = (batch.input(input), self.width(kernel, input)?);
            if values.len() != states * n {
                return Err(JitError::BatchLength {
                    kernel,
                    input,
                    got: values.len(),
                    per_state: n,
                    states,
                });
            }
        }
        Ok(states)
    }
}
