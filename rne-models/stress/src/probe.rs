//! A robot's kernels evaluated twice at the same state: in `f64` exactly as the generated code
//! computes them, and in double-double, the ≥ 30-digit reference.
//!
//! - The `f64` value comes from the kernel's optimised straight-line program
//!   ([`build_kernel`]: the kernel built in a graph of its own, its linear combinations
//!   rewritten, lowered to instructions), evaluated operation by operation in the emitted
//!   order with the same `Real::sin_cos`. The generated Rust performs the same operations in
//!   the same order (no re-association, no fused multiply–add), so this is bit for bit what a
//!   compiled kernel returns — checked on every built-in robot by [`super::cases::compiled`].
//! - The reference is the kernel's expression graph *before* code optimisation (the model as
//!   the spec defines it, with its `f64` constants), evaluated in
//!   [`DoubleDouble`](rne_symbolic::DoubleDouble) at the same `f64` inputs: the exact value of
//!   the `f64` model to about 10⁻³¹ relative.
//!
//! Their difference is the error of the generated kernel alone: the rounding of its
//! operations and of the constants the optimiser folds anew, not an error of the model or of
//! the inputs.

use rne_codegen::{build_kernel, BuiltKernel, Kernel, Real};
use rne_codegen_core::Operand;
use rne_symbolic::expr::Evaluator;
use rne_symbolic::{DoubleDouble, RobotModel, Symbol, SymbolicDynamics};

use super::measure::{
    condition, scaled_condition, Deviation, ErrorsByKernel, KernelErrors, Spread, EPSILON,
};

/// The joint-space state a kernel is evaluated at. Each kernel reads the arrays it takes
/// (DESIGN.md §4) and ignores the others, which may then be empty.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct JointState {
    /// Joint positions q.
    pub q: Vec<f64>,
    /// Joint velocities q̇.
    pub qd: Vec<f64>,
    /// Joint accelerations q̈ (inverse dynamics).
    pub qdd: Vec<f64>,
    /// Joint torques τ (forward dynamics).
    pub tau: Vec<f64>,
}

impl JointState {
    /// The value of a joint symbol; NaN for a symbol the state does not hold.
    fn value(&self, symbol: Symbol) -> f64 {
        let pick = |values: &[f64], k: u16| values.get(usize::from(k)).copied();
        match symbol {
            Symbol::Position(k) => pick(&self.q, k),
            Symbol::Velocity(k) => pick(&self.qd, k),
            Symbol::Acceleration(k) => pick(&self.qdd, k),
            Symbol::Force(k) => pick(&self.tau, k),
            Symbol::Parameter(_) => None,
        }
        .unwrap_or(f64::NAN)
    }
}

/// The errors of several kernels over a set of states, and how well conditioned M was there.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sweep {
    /// The errors of each kernel.
    pub errors: ErrorsByKernel,
    /// cond(M) over the states.
    pub condition: Spread,
    /// The condition number of M scaled to a unit diagonal over the states.
    pub scaled_condition: Spread,
    /// The cancellation κ in forward dynamics' right-hand side over the states (see
    /// [`Probe::cancellation`]).
    pub cancellation: Spread,
    /// Forward dynamics' error over ε·max(κ, 1)·(scaled cond), state by state: the error of
    /// forming τ − b (ε κ relative) amplified by the conditioning of M.
    pub fd_over_estimate: Spread,
}

/// One kernel: its graph, its emitted program and the evaluation of its outputs in the graph.
struct Prepared {
    kernel: Kernel,
    built: BuiltKernel,
    reference: Evaluator,
}

/// Chosen kernels of one robot, prepared for evaluation in `f64` (the emitted programs) and in
/// double-double (the model's graph).
pub struct Probe {
    dynamics: SymbolicDynamics,
    prepared: Vec<Prepared>,
}

impl Probe {
    /// Prepares `kernels` of `model`, each built in a graph of its own exactly as code
    /// generation builds it ([`build_kernel`]), so that the `f64` values are those of the
    /// compiled kernels, bit for bit, whichever other kernels a module holds.
    pub fn new(model: &RobotModel, kernels: &[Kernel]) -> Probe {
        let dynamics = SymbolicDynamics::new(model);
        let prepared = kernels
            .iter()
            .map(|&kernel| {
                let built = build_kernel(&dynamics, kernel);
                let reference = Evaluator::new(&built.dynamics.model.graph, &built.roots);
                Prepared {
                    kernel,
                    built,
                    reference,
                }
            })
            .collect();
        Probe { dynamics, prepared }
    }

    /// Number of joint variables.
    pub fn dof(&self) -> usize {
        self.dynamics.dof()
    }

    /// The kernels this probe evaluates.
    pub fn kernels(&self) -> Vec<Kernel> {
        self.prepared.iter().map(|p| p.kernel).collect()
    }

    fn prepared(&self, kernel: Kernel) -> Option<&Prepared> {
        self.prepared.iter().find(|p| p.kernel == kernel)
    }

    /// The value of `symbol` at `state` in the scalar `T`; parameters kept symbolic take their
    /// spec values.
    fn input<T: Real>(&self, state: &JointState, symbol: Symbol) -> T {
        match symbol {
            Symbol::Parameter(_) => T::from_f64(
                self.dynamics
                    .model
                    .parameter_value(symbol)
                    .unwrap_or(f64::NAN),
            ),
            joint => T::from_f64(state.value(joint)),
        }
    }

    /// What the generated `f64` kernel returns at `state` (matrices row-major): its program
    /// evaluated in emitted order. `None` if the probe was not built with this kernel.
    pub fn eval_f64(&self, kernel: Kernel, state: &JointState) -> Option<Vec<f64>> {
        let prepared = self.prepared(kernel)?;
        Some(prepared.built.program.eval(|s| self.input(state, s)))
    }

    /// The double-double reference at `state`: the model's graph, before optimisation.
    pub fn eval_dd(&self, kernel: Kernel, state: &JointState) -> Option<Vec<DoubleDouble>> {
        let prepared = self.prepared(kernel)?;
        let graph = &prepared.built.dynamics.model.graph;
        Some(prepared.reference.eval(graph, |s| self.input(state, s)))
    }

    /// The rounding error of the `f64` kernel at `state`, against double-double.
    pub fn deviation(&self, kernel: Kernel, state: &JointState) -> Option<Deviation> {
        let computed = self.eval_f64(kernel, state)?;
        let exact = self.eval_dd(kernel, state)?;
        Some(Deviation::between(&computed, &exact))
    }

    /// The errors of each of `kernels` that the probe was built with, over `states`.
    pub fn errors(&self, kernels: &[Kernel], states: &[JointState]) -> ErrorsByKernel {
        ErrorsByKernel(
            kernels
                .iter()
                .filter_map(|&kernel| {
                    let deviations: Option<Vec<Deviation>> = states
                        .iter()
                        .map(|state| self.deviation(kernel, state))
                        .collect();
                    Some((kernel, KernelErrors::of(&deviations?)))
                })
                .collect(),
        )
    }

    /// The torque τ(q, q̇, q̈) of `state` as the `f64` inverse-dynamics kernel computes it:
    /// the input that makes forward dynamics reproduce `state.qdd`. `None` if the probe was
    /// not built with inverse dynamics.
    pub fn torque_for(&self, state: &JointState) -> Option<Vec<f64>> {
        self.eval_f64(Kernel::InverseDynamics, state)
    }

    /// cond(M(q)) and the condition number of M scaled to a unit diagonal (see
    /// [`scaled_condition`]), from M in double-double rounded once to `f64`. `None` if the
    /// probe was not built with the mass matrix.
    pub fn conditions(&self, q: &[f64]) -> Option<(f64, f64)> {
        let state = JointState {
            q: q.to_vec(),
            ..JointState::default()
        };
        let m: Vec<f64> = self
            .eval_dd(Kernel::MassMatrix, &state)?
            .into_iter()
            .map(DoubleDouble::to_f64)
            .collect();
        let n = self.dof();
        Some((condition(&m, n), scaled_condition(&m, n)))
    }

    /// The cancellation κ = ‖b‖∞ / ‖τ − b‖∞ in forward dynamics' right-hand side τ − b, with
    /// b = C(q, q̇) q̇ + g(q) from the `f64` bias kernel: the subtraction leaves an absolute
    /// error of about ε‖b‖, which is ε κ relative to τ − b. `None` if the probe was not built
    /// with the bias or the state has no τ.
    pub fn cancellation(&self, state: &JointState) -> Option<f64> {
        let bias = self.eval_f64(Kernel::BiasTorques, state)?;
        if state.tau.len() != bias.len() {
            return None;
        }
        let norm = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0f64, |m, x| m.max(x.abs()));
        let net = norm(&mut state.tau.iter().zip(&bias).map(|(t, b)| t - b));
        Some(norm(&mut bias.iter().copied()) / net)
    }

    /// The errors of `kernels` over `states`, with the spread of cond(M), of the scaled
    /// condition number and of the cancellation κ over the same states, and forward dynamics'
    /// error against the estimate ε·max(κ, 1)·(scaled cond) where all three are available.
    pub fn sweep(&self, kernels: &[Kernel], states: &[JointState]) -> Sweep {
        let conditions: Vec<Option<(f64, f64)>> =
            states.iter().map(|s| self.conditions(&s.q)).collect();
        let cancellations: Vec<Option<f64>> = states.iter().map(|s| self.cancellation(s)).collect();
        let fd_estimate = states
            .iter()
            .zip(conditions.iter().zip(&cancellations))
            .filter_map(|(s, (c, k))| {
                let error = self.deviation(Kernel::ForwardDynamics, s)?.relative;
                Some(error / (EPSILON * k.as_ref()?.max(1.0) * c.as_ref()?.1))
            });
        Sweep {
            fd_over_estimate: Spread::of(fd_estimate),
            errors: self.errors(kernels, states),
            condition: Spread::of(conditions.iter().flatten().map(|c| c.0)),
            scaled_condition: Spread::of(conditions.iter().flatten().map(|c| c.1)),
            cancellation: Spread::of(cancellations.into_iter().flatten()),
        }
    }

    /// For each output of `kernel` (matrices row-major), the inputs its emitted program
    /// reads: the outputs a non-finite input must reach. `None` if the probe was not built
    /// with this kernel.
    pub fn dependencies(&self, kernel: Kernel) -> Option<Vec<Vec<Symbol>>> {
        let program = &self.prepared(kernel)?.built.program;
        // Every input the program reads, numbered; each instruction's inputs, direct or
        // through earlier instructions, as a bit set over that numbering.
        let mut inputs: Vec<Symbol> = program
            .instrs
            .iter()
            .flat_map(|i| i.operands())
            .chain(program.outputs.iter().copied())
            .filter_map(|o| match o {
                Operand::Input(s) => Some(s),
                _ => None,
            })
            .collect();
        inputs.sort_unstable();
        inputs.dedup();
        let words = inputs.len().div_ceil(64).max(1);
        let mut reads: Vec<u64> = Vec::with_capacity(program.instrs.len() * words);
        let mark = |set: &mut [u64], operand: Operand, reads: &[u64]| match operand {
            Operand::Temp(t) => {
                let from = t as usize * words;
                for (w, r) in set.iter_mut().zip(&reads[from..from + words]) {
                    *w |= r;
                }
            }
            Operand::Input(s) => {
                if let Ok(k) = inputs.binary_search(&s) {
                    set[k / 64] |= 1 << (k % 64);
                }
            }
            Operand::Const(_) => {}
        };
        let mut set = vec![0u64; words];
        for instr in &program.instrs {
            set.iter_mut().for_each(|w| *w = 0);
            for operand in instr.operands() {
                mark(&mut set, operand, &reads);
            }
            reads.extend_from_slice(&set);
        }
        Some(
            program
                .outputs
                .iter()
                .map(|&o| {
                    set.iter_mut().for_each(|w| *w = 0);
                    mark(&mut set, o, &reads);
                    inputs
                        .iter()
                        .enumerate()
                        .filter(|(k, _)| set[k / 64] & (1 << (k % 64)) != 0)
                        .map(|(_, &s)| s)
                        .collect()
                })
                .collect(),
        )
    }
}
