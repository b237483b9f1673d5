//! Batches of a kernel that returns several matrices (∂ID: ∂τ/∂q and ∂τ/∂q̇; ∂FD: ∂q̈/∂q,
//! ∂q̈/∂q̇ and M⁻¹), each matrix of every state written straight into its own array.
//!
//! [`JitModel::evaluate_batch`] lays a state's matrices side by side, so a caller wanting one
//! array per matrix (the Python package's tuples) copied every value once more. Here the
//! two-lane kernel is lowered with one output block per matrix (`lower.rs`): its `out` is a
//! table of the matrices' addresses for the pair of states, and each lane stores each value
//! into its own matrix's array. An odd last state takes the scalar kernel, its matrices then
//! copied into their arrays. The values are the single calls', bit for bit.

use rne_codegen_core::{Kernel, Shape};

use crate::batch::Batch;
#[cfg(feature = "threads")]
use crate::batch::SHARED_CHUNK;
use crate::code::Out;
use crate::error::JitError;
use crate::lanes::{Pair, LANES};
use crate::model::JitModel;
#[cfg(feature = "threads")]
use crate::share::for_each_shared;

impl JitModel {
    /// `kernel`, which returns several NV × NV matrices, at every state of `batch`: matrix b
    /// of state i into `outs[b][i·NV²..(i+1)·NV²]`, row-major. `outs` holds one array per
    /// matrix, each of N·NV² values for the N states; every array the kernel takes must hold N
    /// states. The values are [`JitModel::evaluate_batch`]'s, each state checked as
    /// [`JitModel::evaluate`] checks one.
    pub fn evaluate_batch_matrices(
        &self,
        kernel: Kernel,
        batch: Batch<'_>,
        outs: &mut [&mut [f64]],
    ) -> Result<(), JitError> {
        self.matrix_states(kernel, &batch, outs)?;
        self.matrices_share(kernel, &batch, 0, outs)
    }

    /// [`JitModel::evaluate_batch_matrices`] on `threads` threads, each taking the next 64
    /// states when it has finished its last, as [`JitModel::evaluate_batch_threaded`] does.
    #[cfg(feature = "threads")]
    pub fn evaluate_batch_matrices_threaded(
        &self,
        kernel: Kernel,
        batch: Batch<'_>,
        outs: &mut [&mut [f64]],
        threads: usize,
    ) -> Result<(), JitError> {
        let (states, len) = self.matrix_states(kernel, &batch, outs)?;
        let threads = threads.clamp(1, states.div_ceil(SHARED_CHUNK).max(1));
        // The lanes compiled before the threads start.
        if states >= LANES {
            self.matrix_lane_kernel(kernel, outs.len())?;
        }
        let mut cuts: Vec<_> = outs
            .iter_mut()
            .map(|out| out.chunks_mut(SHARED_CHUNK * len))
            .collect();
        let chunks = (0..states.div_ceil(SHARED_CHUNK)).map(move |c| {
            let chunk: Vec<&mut [f64]> = cuts
                .iter_mut()
                .map(|cut| cut.next().unwrap_or_default())
                .collect();
            (c, chunk)
        });
        for_each_shared(
            chunks,
            threads,
            || (),
            |(), (c, mut chunk)| self.matrices_share(kernel, &batch, c * SHARED_CHUNK, &mut chunk),
        )
    }

    /// The number of states and the values per matrix, once `outs` is one array per matrix
    /// of `kernel`, all of the same number of states, and every array of `batch` the kernel
    /// takes holds that many.
    fn matrix_states(
        &self,
        kernel: Kernel,
        batch: &Batch<'_>,
        outs: &[&mut [f64]],
    ) -> Result<(usize, usize), JitError> {
        let matrices = match kernel.shape() {
            Shape::Matrices(count) => count,
            _ => 0,
        };
        if matrices != outs.len() || matrices == 0 {
            return Err(JitError::MatrixArrays {
                kernel,
                got: outs.len(),
                expected: matrices,
            });
        }
        let len = self.nv() * self.nv();
        let states = outs[0].len() / len.max(1);
        if let Some(out) = outs.iter().find(|out| out.len() != states * len) {
            return Err(JitError::OutputLength {
                kernel,
                got: out.len(),
                expected: states * len,
            });
        }
        self.batch_states(kernel, batch, states * len * matrices)?;
        Ok((states, len))
    }

    /// `kernel` at states `first`, `first + 1`, … of `batch`, each matrix into its array of
    /// `outs` (as many states as they hold), each state checked: two states a call in two
    /// lanes, an odd last one alone.
    fn matrices_share(
        &self,
        kernel: Kernel,
        batch: &Batch<'_>,
        first: usize,
        outs: &mut [&mut [f64]],
    ) -> Result<(), JitError> {
        let len = self.nv() * self.nv();
        let states = outs.first().map_or(0, |out| out.len() / len.max(1));
        let lane = match states >= LANES {
            true => self.matrix_lane_kernel(kernel, outs.len())?,
            false => None,
        };
        let mut done = 0;
        if let Some(lane) = lane {
            let mut pair = Pair::new(lane);
            while done + LANES <= states {
                let at = first + done;
                let pair_states = [self.state(batch, at), self.state(batch, at + 1)];
                let out = Out::Blocks {
                    blocks: &mut *outs,
                    at: done * len,
                };
                self.run_pair(lane, (pair_states, at), out, &mut pair)?;
                done += LANES;
            }
        }
        let mut values = vec![0.0; if done < states { outs.len() * len } else { 0 }];
        for k in done..states {
            let state = self.state(batch, first + k);
            self.evaluate(kernel, state, &mut values)
                .map_err(|e| e.in_batch(first + k))?;
            for (out, matrix) in outs.iter_mut().zip(values.chunks_exact(len)) {
                out[k * len..(k + 1) * len].copy_from_slice(matrix);
            }
        }
        Ok(())
    }
}
