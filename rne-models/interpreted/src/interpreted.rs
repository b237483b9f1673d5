//! A robot's kernels as the optimised straight-line programs `derive_dynamics!` emits,
//! evaluated at run time without compiling them: what `rne eval` uses for robots that are not
//! built in, what user scenarios simulate for them, the baseline that shows what compiling the
//! code buys, and the subject of the stress measurements.
//!
//! - [`Interpreted::eval`] evaluates a kernel's program operation by operation in the emitted
//!   order with the same `Real::sin_cos`, in any scalar. The generated Rust performs the same
//!   operations in the same order (no re-association, no fused multiply–add), so in `f64` the
//!   result is bit for bit what the compiled kernel returns.
//! - [`Interpreted::exact`] evaluates the kernel's expression graph *before* code
//!   optimisation (the model as the spec defines it, with its `f64` constants) in
//!   [`DoubleDouble`]: the value of the `f64` model to about 10⁻³¹ relative.
//! - [`Interpreted::dependencies`] lists the inputs each output of a program reads.
//!
//! Each kernel is built in a graph of its own ([`build_kernel`]), exactly as code generation
//! builds it, so the values do not depend on which other kernels are built.

use std::sync::OnceLock;

use rne_codegen::{DoubleDouble, Input, Kernel, Real};
use rne_codegen_core::Operand;
use rne_codegen_core::{build_kernel, BuiltKernel, Program};
use rne_symbolic::expr::Evaluator;
use rne_symbolic::{RobotModel, Symbol, SymbolicDynamics};

use crate::error::Error;
use crate::state::StateRef;

/// One kernel: its graph, its emitted program and, once asked for, the evaluation order of
/// its outputs in the graph.
struct Prepared {
    kernel: Kernel,
    built: BuiltKernel,
    exact: OnceLock<Evaluator>,
}

/// Chosen kernels of one robot as straight-line programs (see the module documentation).
pub struct Interpreted {
    dynamics: SymbolicDynamics,
    prepared: Vec<Prepared>,
}

impl Interpreted {
    /// Builds the dynamics kernels of `model` ([`Kernel::DYNAMICS`], what a module generates
    /// without `outputs`), with numeric or symbolic parameters (symbolic ones take their spec
    /// values when evaluated).
    pub fn new(model: &RobotModel) -> Interpreted {
        Interpreted::with_kernels(model, &Kernel::DYNAMICS)
    }

    /// Builds `kernels` of `model` only.
    pub fn with_kernels(model: &RobotModel, kernels: &[Kernel]) -> Interpreted {
        let dynamics = SymbolicDynamics::new(model);
        let prepared = kernels
            .iter()
            .map(|&kernel| Prepared {
                kernel,
                built: build_kernel(&dynamics, kernel),
                exact: OnceLock::new(),
            })
            .collect();
        Interpreted { dynamics, prepared }
    }

    /// Number of joint variables.
    pub fn dof(&self) -> usize {
        self.dynamics.dof()
    }

    /// Size of the configuration q (NQ; NV + 1 on a floating base).
    pub fn nq(&self) -> usize {
        self.dynamics.layout().nq()
    }

    /// Size of the velocity q̇ and of q̈ and τ (NV).
    pub fn nv(&self) -> usize {
        self.dynamics.layout().nv()
    }

    /// Joint variable names, in state order.
    pub fn joints(&self) -> Vec<String> {
        self.dynamics.model.joint_names()
    }

    /// The kernels built, in the order asked for.
    pub fn kernels(&self) -> Vec<Kernel> {
        self.prepared.iter().map(|p| p.kernel).collect()
    }

    /// Whether `kernel` was built.
    pub fn has(&self, kernel: Kernel) -> bool {
        self.prepared(kernel).is_some()
    }

    fn prepared(&self, kernel: Kernel) -> Option<&Prepared> {
        self.prepared.iter().find(|p| p.kernel == kernel)
    }

    /// The program of `kernel`, if built.
    pub fn program(&self, kernel: Kernel) -> Option<&Program> {
        self.prepared(kernel).map(|p| &p.built.program)
    }

    /// The value of `symbol` at `state` in the scalar `T`: NaN for an entry the state does not
    /// hold; parameters kept symbolic take their spec values.
    fn input<T: Real>(&self, state: StateRef<'_, T>, symbol: Symbol) -> T {
        let pick = |values: &[T], k: u16| values.get(usize::from(k)).copied();
        match symbol {
            Symbol::Position(k) => pick(state.q, k),
            Symbol::Velocity(k) => pick(state.qd, k),
            Symbol::Acceleration(k) => pick(state.qdd, k),
            Symbol::Force(k) => pick(state.tau, k),
            Symbol::Parameter(_) => self.dynamics.model.parameter_value(symbol).map(T::from_f64),
            // A lane seed is no input of the state: `Program::eval` gives it its value.
            Symbol::Lane(_) => None,
        }
        .unwrap_or_else(|| T::from_f64(f64::NAN))
    }

    /// `kernel` at `state` (matrices row-major) in the scalar `T`: its program evaluated in
    /// emitted order, e.g. in `f64` what the generated kernel returns, or in [`DoubleDouble`]
    /// the same program to ≈ 32 digits. `None` if the kernel was not built.
    pub fn eval<T: Real>(&self, kernel: Kernel, state: StateRef<'_, T>) -> Option<Vec<T>> {
        let program = self.program(kernel)?;
        Some(program.eval(|s| self.input(state, s)))
    }

    /// `kernel` at `state` in `f64`, like [`evaluate`](crate::evaluate) for a `Dynamics`: the
    /// arrays the kernel takes must have the robot's sizes (NQ for q, NV for the others).
    /// Kernels of the standard parameters (`base_parameters`) are not evaluated here.
    pub fn evaluate(&self, kernel: Kernel, state: StateRef<'_>) -> Result<Vec<f64>, Error> {
        for &input in kernel.inputs() {
            let (got, expected) = match input {
                Input::Q => (state.q.len(), self.nq()),
                Input::Qd => (state.qd.len(), self.nv()),
                Input::Qdd => (state.qdd.len(), self.nv()),
                Input::Tau => (state.tau.len(), self.nv()),
                Input::Standard => return Err(Error::StandardParameters { kernel }),
            };
            if got != expected {
                return Err(Error::Dimension {
                    input,
                    got,
                    expected,
                });
            }
        }
        self.eval(kernel, state)
            .ok_or(Error::MissingKernel { kernel })
    }

    /// The double-double value of `kernel` at the `f64` `state`: the model's graph, before
    /// optimisation. `None` if the kernel was not built.
    pub fn exact(&self, kernel: Kernel, state: StateRef<'_>) -> Option<Vec<DoubleDouble>> {
        let prepared = self.prepared(kernel)?;
        let graph = &prepared.built.dynamics.model.graph;
        let evaluator = prepared
            .exact
            .get_or_init(|| Evaluator::new(graph, &prepared.built.roots));
        Some(evaluator.eval(graph, |s| DoubleDouble::from_f64(self.input(state, s))))
    }

    /// For each output of `kernel` (matrices row-major), the inputs its emitted program reads:
    /// the outputs a non-finite input must reach. `None` if the kernel was not built.
    pub fn dependencies(&self, kernel: Kernel) -> Option<Vec<Vec<Symbol>>> {
        let program = self.program(kernel)?;
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
            Operand::Temp(t) | Operand::Lane { temp: t, .. } => {
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

impl crate::agreement::Engine for Interpreted {
    fn has(&self, kernel: Kernel) -> bool {
        Interpreted::has(self, kernel)
    }

    fn evaluate(&self, kernel: Kernel, state: StateRef<'_>) -> Result<Vec<f64>, Error> {
        Interpreted::evaluate(self, kernel, state)
    }

    fn base_parameters(&self, standard: &[f64]) -> Result<Vec<f64>, Error> {
        let kernel = Kernel::BaseParameters;
        let program = self
            .program(kernel)
            .ok_or(Error::MissingKernel { kernel })?;
        Ok(program.eval(|s| match s {
            Symbol::Parameter(i) => standard.get(usize::from(i)).copied().unwrap_or(f64::NAN),
            _ => f64::NAN,
        }))
    }

    fn frames(&self) -> Vec<String> {
        self.dynamics
            .frames()
            .iter()
            .map(|f| f.name.clone())
            .collect()
    }
}
