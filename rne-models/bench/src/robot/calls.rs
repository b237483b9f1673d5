//! The calls `rne bench MODEL` times: a kernel of the JIT or of the interpreter through its
//! slice API, cycling through the seeded states, and a kernel of a built-in robot's compiled
//! module through the `Dynamics` trait (timed inside a [`Visitor`], which owns the module).

use std::hint::black_box;

use rne_codegen::{Dynamics, Kernel};
use rne_interpreted::agreement::Engine as Agreement;
use rne_interpreted::{Error, Interpreted, JointState, StateRef};
use rne_jit::{JitModel, State};
use rne_models::Visitor;

use crate::calls::{Calls, Input, Pool};
use crate::timing::{time_interleaved, Plan, Timed, Timing};

/// A kernel of the JIT at the states in turn, into one output buffer.
struct JitCalls<'a> {
    jit: &'a JitModel,
    kernel: Kernel,
    states: Pool<&'a JointState>,
    out: Vec<f64>,
}

impl Timed for JitCalls<'_> {
    fn run(&mut self, calls: u64) {
        let (jit, kernel, out) = (self.jit, self.kernel, &mut self.out);
        self.states.cycle(calls, |s| {
            let state = State {
                q: &s.q,
                qd: &s.qd,
                qdd: &s.qdd,
                tau: &s.tau,
            };
            // The states are finite and of the robot's lengths: the call cannot fail.
            let _ = jit.evaluate(kernel, state, out);
            black_box(&*out);
        });
    }
}

/// `kernel` of `jit` at `states` (at least one), timed through [`JitModel::evaluate`].
pub fn jit<'a>(jit: &'a JitModel, kernel: Kernel, states: &'a [JointState]) -> Box<dyn Timed + 'a> {
    Box::new(JitCalls {
        jit,
        kernel,
        states: cycled(states),
        out: vec![0.0; jit.output_len(kernel).unwrap_or(0)],
    })
}

/// A kernel of the interpreter at the states in turn.
struct InterpretedCalls<'a> {
    programs: &'a Interpreted,
    kernel: Kernel,
    states: Pool<&'a JointState>,
}

impl Timed for InterpretedCalls<'_> {
    fn run(&mut self, calls: u64) {
        let (programs, kernel) = (self.programs, self.kernel);
        self.states
            .cycle(calls, |s| programs.eval::<f64>(kernel, s.as_ref()));
    }
}

/// `kernel` of `programs` at `states` (at least one), timed through [`Interpreted::eval`].
pub fn interpreted<'a>(
    programs: &'a Interpreted,
    kernel: Kernel,
    states: &'a [JointState],
) -> Box<dyn Timed + 'a> {
    Box::new(InterpretedCalls {
        programs,
        kernel,
        states: cycled(states),
    })
}

/// `states` cycled through in order, as the compiled module's calls cycle through theirs
/// ([`Calls`]): every engine pays the same for its next state.
fn cycled(states: &[JointState]) -> Pool<&JointState> {
    Pool::new(states.iter().collect(), states.len())
}

/// Times `kernel` of a built-in robot's compiled module together with `others`, and measures
/// its error by `error`: run by [`rne_models::BuiltinRobot::visit`].
pub struct WithCompiled<'a, 'b> {
    /// The kernel.
    pub kernel: Kernel,
    /// The other engines' calls of it, timed in the same rounds.
    pub others: &'a mut [Box<dyn Timed + 'b>],
    /// The seeded states.
    pub states: &'a [JointState],
    /// The timing plan.
    pub plan: &'a Plan,
    /// The compiled kernel's largest error against the reference, given it as an engine.
    pub error: &'a dyn Fn(&dyn Agreement) -> Result<f64, Error>,
}

/// The timings of a [`WithCompiled`] run: the other engines' (in order), then the compiled
/// module's with its error, when the module has the kernel.
pub struct CompiledRun {
    /// The other engines' timings, in order.
    pub others: Vec<Timing>,
    /// The compiled kernel's timing and error.
    pub compiled: Option<(Timing, Result<f64, Error>)>,
}

impl Visitor for WithCompiled<'_, '_> {
    type Output = CompiledRun;

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) -> CompiledRun {
        let mut subjects: Vec<&mut dyn Timed> = self
            .others
            .iter_mut()
            .map(|c| &mut **c as &mut dyn Timed)
            .collect();
        let n_others = subjects.len();
        if !D::KERNELS.contains(&self.kernel) || D::FLOATING_BASE {
            return CompiledRun {
                others: time_interleaved(&mut subjects, self.plan),
                compiled: None,
            };
        }
        let error = (self.error)(&CompiledEngine::<D, N> { model: &model });
        let inputs: Vec<Input<f64, N>> = self.states.iter().map(input).collect();
        let mut calls = Calls::new(model, self.kernel, inputs, self.states.len());
        subjects.push(&mut calls);
        let mut times = time_interleaved(&mut subjects, self.plan);
        let compiled = times.split_off(n_others).pop().map(|t| (t, error));
        CompiledRun {
            others: times,
            compiled,
        }
    }
}

/// A state as the compiled module's arrays (the module's N entries of each).
fn input<const N: usize>(s: &JointState) -> Input<f64, N> {
    let array = |v: &[f64]| -> [f64; N] { std::array::from_fn(|i| v[i]) };
    Input {
        q: array(&s.q),
        qd: array(&s.qd),
        qdd: array(&s.qdd),
        tau: array(&s.tau),
    }
}

/// A compiled module as an engine of the agreement check (its dynamics kernels).
struct CompiledEngine<'a, D, const N: usize> {
    model: &'a D,
}

impl<const N: usize, D: Dynamics<N, N, Scalar = f64>> Agreement for CompiledEngine<'_, D, N> {
    fn has(&self, kernel: Kernel) -> bool {
        D::KERNELS.contains(&kernel)
    }

    fn evaluate(&self, kernel: Kernel, state: StateRef<'_>) -> Result<Vec<f64>, Error> {
        rne_interpreted::evaluate(self.model, kernel, state)
    }

    fn base_parameters(&self, _: &[f64]) -> Result<Vec<f64>, Error> {
        Ok(Vec::new())
    }

    fn frames(&self) -> Vec<String> {
        Vec::new()
    }
}
