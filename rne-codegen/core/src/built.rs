//! Kernels built: each kernel of a module in an expression graph of its own, optimised into the
//! straight-line [`Program`] every backend emits from.

use rne_symbolic::{Id, SymbolicDynamics};

use crate::generation_options::ForwardDynamicsMethod;
use crate::kernel::{build_outputs, Kernel, KernelSetup};
use crate::linear::distribute_constants;
use crate::module::ForwardDynamicsChoice;
use crate::program::Program;
use crate::split::SPLIT_ABOVE;

/// One kernel built in an expression graph of its own.
#[derive(Clone, Debug)]
pub struct BuiltKernel {
    /// The dynamics whose graph holds this kernel's expressions and nothing of other kernels.
    pub dynamics: SymbolicDynamics,
    /// The kernel's outputs as built (flattened row-major for matrices), before optimisation;
    /// for a kernel built in lanes, the vectors that carry them.
    pub roots: Vec<Id>,
    /// The optimised straight-line program: the outputs with their linear combinations
    /// rewritten ([`distribute_constants`]), lowered ([`Program::lower`]). This is exactly what
    /// `generate` emits.
    pub program: Program,
}

/// Builds `kernel` into a copy of `dynamics` and optimises it, for every frame and with the
/// base parameters found from the dynamics ([`KernelSetup::new`]).
pub fn build_kernel(dynamics: &SymbolicDynamics, kernel: Kernel) -> BuiltKernel {
    build_kernel_with(dynamics, kernel, &KernelSetup::new(dynamics, &[kernel]))
}

/// Builds `kernel` into a copy of `dynamics` and optimises it. Given dynamics in which nothing
/// has been built yet, the result depends on the model, the kernel and `setup` alone: the
/// order of the terms of rewritten sums follows node ids, so kernels sharing one graph would
/// round differently depending on which others were generated before them.
pub fn build_kernel_with(
    dynamics: &SymbolicDynamics,
    kernel: Kernel,
    setup: &KernelSetup,
) -> BuiltKernel {
    if setup.derivative_lanes {
        if let Some(built) = build_in_lanes(dynamics, kernel) {
            return built;
        }
    }
    build_in_scalars(dynamics.clone(), kernel, setup)
}

/// [`build_kernel_with`] without lanes, into `dynamics` itself: a graph in which only this
/// kernel's expressions have been built (and cached) gives the same kernel as a fresh one.
pub(crate) fn build_in_scalars(
    mut dynamics: SymbolicDynamics,
    kernel: Kernel,
    setup: &KernelSetup,
) -> BuiltKernel {
    let roots = build_outputs(kernel, &mut dynamics, setup);
    let nv = dynamics.layout().nv();
    let graph = &mut dynamics.model.graph;
    let outputs = match kernel {
        // M⁻¹, the last NV² outputs, is rewritten on its own first, as the
        // `mass_matrix_inverse` kernel is: which sums are opened depends on the other outputs
        // using them, and the third output must round exactly as that kernel does.
        Kernel::ForwardDynamicsDerivatives => {
            let split = roots.len() - nv * nv;
            let inverse = distribute_constants(graph, &roots[split..]);
            let derivatives = distribute_constants(graph, &roots[..split]);
            [derivatives, inverse].concat()
        }
        _ => distribute_constants(graph, &roots),
    };
    let program = Program::lower(&dynamics.model.graph, &outputs);
    BuiltKernel {
        dynamics,
        roots,
        program,
    }
}

/// A derivative kernel built in lanes ([`rne_symbolic::dynamics::LanePartials`]), its program returning each
/// derivative from the lane that carries it ([`Program::pick_lanes`]); its roots are the
/// vectors. `None` for another kernel or a program long enough to be split (module `split`
/// passes values between parts in scalar slots).
fn build_in_lanes(dynamics: &SymbolicDynamics, kernel: Kernel) -> Option<BuiltKernel> {
    let mut dynamics = dynamics.clone();
    let (partials, inverse) = match kernel {
        Kernel::InverseDynamicsDerivatives => (dynamics.inverse_dynamics_derivative_lanes(), None),
        Kernel::ForwardDynamicsDerivatives => {
            let (partials, inverse) = dynamics.forward_dynamics_derivative_lanes();
            (partials, Some(inverse))
        }
        _ => return None,
    };
    // ∂/∂q then ∂/∂q̇, row-major.
    let mut picks: Vec<(usize, u8)> = [partials.dq, partials.dv].concat().concat();
    let vectors = partials.vectors;
    let graph = &mut dynamics.model.graph;
    let outputs = match &inverse {
        // M⁻¹ rewritten on its own first, as in `build_kernel_with`.
        Some(inverse) => {
            let inverse = distribute_constants(graph, &inverse.concat());
            let derivatives = distribute_constants(graph, &vectors);
            picks.extend((0..inverse.len()).map(|k| (derivatives.len() + k, 0)));
            [derivatives, inverse].concat()
        }
        None => distribute_constants(graph, &vectors),
    };
    let program = Program::lower(graph, &outputs).pick_lanes(&picks);
    if program.instrs.len() > SPLIT_ABOVE {
        return None;
    }
    let roots = [vectors, inverse.map(|m| m.concat()).unwrap_or_default()].concat();
    Some(BuiltKernel {
        dynamics,
        roots,
        program,
    })
}

/// The optimised straight-line program of one kernel ([`build_kernel`]).
pub fn kernel_program(dynamics: &SymbolicDynamics, kernel: Kernel) -> Program {
    build_kernel(dynamics, kernel).program
}

/// Builds `forward_dynamics` both ways and keeps the one `method` asks for, or with `Auto` the
/// one of lower cost ([`OpCount::cost`]): the choice, and the kernel built the chosen way (so
/// that the module does not build it a third time).
pub(crate) fn choose_forward_dynamics(
    dynamics: &SymbolicDynamics,
    setup: &KernelSetup,
    method: ForwardDynamicsMethod,
) -> (ForwardDynamicsChoice, BuiltKernel) {
    let build = |articulated: bool| {
        let setup = KernelSetup {
            articulated,
            ..setup.clone()
        };
        build_kernel_with(dynamics, Kernel::ForwardDynamics, &setup)
    };
    let (aba_kernel, ldlt_kernel) = (build(true), build(false));
    let (aba, ldlt) = (
        aba_kernel.program.op_count(),
        ldlt_kernel.program.op_count(),
    );
    let chosen = match method {
        ForwardDynamicsMethod::Auto if aba.cost() < ldlt.cost() => ForwardDynamicsMethod::Aba,
        ForwardDynamicsMethod::Auto => ForwardDynamicsMethod::Ldlt,
        forced => forced,
    };
    let built = match chosen {
        ForwardDynamicsMethod::Aba => aba_kernel,
        _ => ldlt_kernel,
    };
    (ForwardDynamicsChoice { aba, ldlt, chosen }, built)
}
