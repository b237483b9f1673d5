//! Two states a call: a kernel lowered in two lanes (`f64x2`, `lower.rs`) for batches.
//!
//! A batch of two or more states compiles its kernel in two lanes at its first call (once per
//! model and kernel, kept until the model is dropped) and then computes the states two at a
//! time: their inputs interleaved into one array each, one call that stores each state's
//! results in its own half of the output (`lower.rs`). Each lane performs the scalar kernel's
//! operations on its own state, so the results are the single calls' bits; an odd last state
//! takes the scalar kernel.

use rne_codegen_core::KernelProgram;

use crate::code::{Code, Out};
use crate::error::JitError;
use crate::model::{compile_programs, Compiled, JitModel, State, Tier};

/// States per call of a lane kernel (`f64x2`).
pub(crate) const LANES: usize = 2;

/// States a batch computes per call: `RNE_JIT_LANES=1` for one (to measure what the lanes
/// gain, or a kernel's own time per state), else two; read when a model is compiled.
pub(crate) fn from_env() -> usize {
    match std::env::var("RNE_JIT_LANES").as_deref() {
        Ok("1") => 1,
        _ => LANES,
    }
}

/// One kernel compiled in two lanes, with the code it runs.
pub(crate) struct LaneKernel {
    compiled: Compiled,
    /// The memory `compiled` points into, freed with it.
    _code: Code,
}

impl LaneKernel {
    /// `program` in two lanes with `blocks` output blocks (0: none; `lower.rs`), with the
    /// model's `fma` and tier; Cranelift's message if it fails (a bug: the scalar kernel
    /// compiled).
    pub(crate) fn compile(
        program: &KernelProgram,
        fma: bool,
        tier: Tier,
        blocks: usize,
    ) -> Result<Self, String> {
        let (module, _, mut kernels) =
            compile_programs(&[program], fma, tier, (LANES, blocks)).map_err(|e| e.to_string())?;
        let compiled = kernels.pop().ok_or("no kernel was compiled")?;
        Ok(LaneKernel {
            compiled,
            _code: Code::new(module),
        })
    }

    pub(crate) fn compiled(&self) -> &Compiled {
        &self.compiled
    }
}

/// The interleaved inputs of two states and their scratch array, reused from pair to pair.
#[derive(Default)]
pub(crate) struct Pair {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    tau: Vec<f64>,
    scratch: Vec<f64>,
}

impl Pair {
    /// The arrays for `lane`'s calls.
    pub(crate) fn new(lane: &Compiled) -> Pair {
        Pair {
            scratch: lane.scratch(),
            ..Pair::default()
        }
    }
}

impl JitModel {
    /// The two-lane kernel `lane` at two states, checked, each one's results into `out`: its
    /// slice of the outputs' array (the kernel's outputs twice, state 0's first) or, for a
    /// kernel in output blocks, the blocks' arrays (each block's values twice, from the pair's
    /// place on). The values are checked for finiteness as they are interleaved; only when
    /// one is not are the two states checked one by one, for the error a single call would
    /// give, as the error of the batch's state `first` or `first + 1`.
    pub(crate) fn run_pair(
        &self,
        lane: &Compiled,
        (states, first): ([State<'_>; LANES], usize),
        out: Out<'_, '_>,
        pair: &mut Pair,
    ) -> Result<(), JitError> {
        let kernel = lane.kernel();
        for state in &states {
            self.check_lengths(kernel, state)?;
        }
        let [a, b] = states;
        let finite = interleave(a.q, b.q, &mut pair.q)
            & interleave(a.qd, b.qd, &mut pair.qd)
            & interleave(a.qdd, b.qdd, &mut pair.qdd)
            & interleave(a.tau, b.tau, &mut pair.tau);
        if !finite {
            for (k, state) in states.iter().enumerate() {
                self.check_state(kernel, state)
                    .map_err(|e| e.in_batch(first + k))?;
            }
        }
        let Pair {
            q,
            qd,
            qdd,
            tau,
            scratch,
        } = pair;
        let state = State { q, qd, qdd, tau };
        // The kernel stores each state's outputs in its own half of `out` (`lower.rs`).
        self.run_in(lane, state, self.parameters(), out, scratch);
        Ok(())
    }
}

/// `a` and `b` side by side into `into`: `a[0], b[0], a[1], b[1], …` (arrays of equal length,
/// both empty for an input the kernel does not take); whether every value is finite.
fn interleave(a: &[f64], b: &[f64], into: &mut Vec<f64>) -> bool {
    into.resize(2 * a.len().min(b.len()), 0.0);
    let mut finite = true;
    for ((into, &x), &y) in into.chunks_exact_mut(LANES).zip(a).zip(b) {
        into[0] = x;
        into[1] = y;
        finite &= x.is_finite() & y.is_finite();
    }
    finite
}

#[cfg(test)]
mod tests {
    use super::interleave;

    #[test]
    fn interleave_puts_the_two_states_side_by_side_and_tells_whether_they_are_finite() {
        let mut into = vec![9.0];
        assert!(interleave(&[1.0, 2.0, 3.0], &[4.0, 5.0, 6.0], &mut into));
        assert_eq!(into, [1.0, 4.0, 2.0, 5.0, 3.0, 6.0]);
        assert!(!interleave(&[1.0, 2.0], &[f64::INFINITY, 5.0], &mut into));
        assert!(!interleave(&[1.0, f64::NAN], &[4.0, 5.0], &mut into));
        assert!(interleave(&[], &[], &mut into));
        assert!(into.is_empty());
    }
}
