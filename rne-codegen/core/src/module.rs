//! A whole generated module: constants, the runtime `Params` struct, the kernels and the
//! `Model` type implementing the runtime's `Dynamics` trait.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use proc_macro2::{Literal, TokenStream};
use quote::quote;
use rne_symbolic::dynamics::base_parameters::BaseParameters;
use rne_symbolic::dynamics::derivatives::Sweep;
use rne_symbolic::{Id, OpCount, RobotModel, SymbolicDynamics};

use crate::emit::{emit_kernel, is_valid_parameter_name, parameter_fields, EmitContext};
use crate::error::CodegenError;
use crate::kernel::articulated_applies;
use crate::kernel::{build_outputs, Dims, Kernel, KernelSetup};
use crate::linear::distribute_constants;
use crate::model_type::ModelType;
use crate::params::{base_params, spec_params};
use crate::program::Program;
use crate::scene::{ForwardDynamicsMethod, ParameterMode, ScalarType, Scene};
use crate::split::SPLIT_ABOVE;

/// What was generated for one kernel.
#[derive(Clone, Debug, PartialEq)]
pub struct KernelReport {
    /// The kernel.
    pub kernel: Kernel,
    /// Operations per call of the emitted function.
    pub ops: OpCount,
    /// Its critical path in modelled cycles ([`Program::critical_path`]).
    pub critical_path: u32,
    /// Time spent building and emitting this kernel: for forward dynamics whose method is
    /// chosen, building it both ways to choose included; for ∂ID built on one thread and
    /// lowered on the other, both parts.
    pub generation_time: Duration,
}

/// A generated module and how it was made.
#[derive(Clone, Debug)]
pub struct GeneratedModule {
    /// The module's items (to be wrapped in `mod name { ... }`), as Rust source text: the
    /// kernels are written as text ([`emit_kernel`]), which costs a small fraction of the
    /// memory and time of a token stream on the largest robots.
    pub source: String,
    /// Number of joint variables (after locking).
    pub ndof: usize,
    /// Joint variable names, in order.
    pub joints: Vec<String>,
    /// One report per kernel, in emission order.
    pub kernels: Vec<KernelReport>,
    /// When `forward_dynamics` was generated and both algorithms apply: the operations of
    /// each, articulated-body first and factorised second, and which was emitted.
    pub forward_dynamics_choice: Option<ForwardDynamicsChoice>,
    /// Total generation time.
    pub generation_time: Duration,
}

impl GeneratedModule {
    /// The items as tokens, lexed from [`source`](Self::source), for the macro to expand to.
    /// An error would mean the generator wrote text that is not Rust.
    pub fn items(&self) -> Result<TokenStream, proc_macro2::LexError> {
        self.source.parse()
    }

    /// The items as formatted Rust source (prettyplease), for people to read.
    pub fn to_pretty_string(&self) -> String {
        match syn::parse_file(&self.source) {
            Ok(file) => prettyplease::unparse(&file),
            Err(_) => self.source.clone(),
        }
    }
}

/// The two ways `forward_dynamics` could be generated, and the one that was.
#[derive(Clone, Debug, PartialEq)]
pub struct ForwardDynamicsChoice {
    /// Operations of the articulated-body algorithm.
    pub aba: OpCount,
    /// Operations of M + LᵀDL.
    pub ldlt: OpCount,
    /// The one emitted.
    pub chosen: ForwardDynamicsMethod,
}

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
    /// [`generate`] emits.
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
fn build_in_scalars(
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

/// Generates the kernels `scene` asks for, for `model` (loaded with symbolic parameters when
/// the scene wants runtime parameters). `source` names the robot file in the docs.
pub fn generate(
    model: &RobotModel,
    scene: &Scene,
    source: &str,
) -> Result<GeneratedModule, CodegenError> {
    let start = Instant::now();
    let runtime = scene.runtime_path()?;
    let model = scene.apply(model)?;
    let needs_inverse = [
        Kernel::ForwardDynamics,
        Kernel::ForwardDynamicsDerivatives,
        Kernel::MassMatrixInverse,
    ];
    if scene.outputs.iter().any(|k| needs_inverse.contains(k)) {
        model
            .check_mass_matrix_invertible()
            .map_err(|joint| CodegenError::Massless {
                robot: source.to_owned(),
                joint,
            })?;
    }
    if scene.parameters == ParameterMode::Runtime {
        if let Some(bad) = model
            .parameters
            .iter()
            .find(|p| !is_valid_parameter_name(&p.name))
        {
            return Err(CodegenError::ParameterName(bad.name.clone()));
        }
    }
    if scene.parameters == ParameterMode::Base && !model.graph.symbols().parameters().is_empty() {
        return Err(CodegenError::SymbolicBaseParameters {
            robot: source.to_owned(),
        });
    }
    let mut dynamics = SymbolicDynamics::new(&model);
    if scene.zero_velocities {
        dynamics = dynamics.at_rest();
    }
    if scene.friction {
        dynamics = dynamics.with_friction();
    }
    // `parameters: base`: every kernel a function of the base parameters alone, found once.
    let base_mode = (scene.parameters == ParameterMode::Base).then(|| {
        let (in_base, base) = dynamics.in_base_parameters();
        dynamics = in_base;
        base
    });
    let ndof = dynamics.dof();
    let layout = dynamics.layout();
    let joints = dynamics.model.joint_names();
    let outputs = scene.kernels();
    let mut setup = KernelSetup {
        frames: scene.frame_indices(dynamics.frames())?,
        base_parameters: base_mode.clone(),
        articulated: false,
        derivative_lanes: scene.derivative_lanes && scene.scalar == ScalarType::F64,
    };
    // Found from the regressor at many states when a kernel reads them (and `parameters: base`
    // has not found them already).
    let finds_base_parameters = base_mode.is_none() && outputs.iter().any(|k| reads_base(*k));
    let parameter_names = dynamics.parameter_names();
    let dims = Dims {
        nv: layout.nv(),
        nf: setup.frames.len(),
        np: parameter_names.len(),
        nb: setup
            .base_parameters
            .as_ref()
            .map_or(0, BaseParameters::len),
    };
    let mut emitted: Vec<Option<(String, KernelReport)>> = vec![None; outputs.len()];
    let runtime_text = runtime.to_string();
    let fields = parameter_fields(dynamics.model.graph.symbols());
    let emit = |built: BuiltKernel, kernel: Kernel, dims: Dims, start: Instant| {
        emit_built(built, kernel, scene, &runtime_text, &fields, dims, start)
    };
    // Two threads. This one builds the derivative kernels, the costliest. The other builds
    // forward dynamics (both ways, to choose) and finds the base parameters when a kernel reads
    // them, then builds those kernels. When both derivative kernels are built, forward
    // dynamics' takes the sweep inverse dynamics' chose in scalars (the same torques). Built
    // in scalars, the graph of ∂ID is built both ways at once, by forward sweeps on this
    // thread and by reverse sweeps on the other, which sends its cost; this thread chooses
    // (`Sweep::cheaper`, as one thread trying both would), hands over its graph if the forward
    // sweeps won, and builds ∂FD by the chosen sweep while the other lowers and emits ∂ID from
    // the graph it was handed or its own. Built in lanes
    // (`derivatives: lanes`), this thread builds ∂ID and then ∂FD: only a ∂ID too long for
    // lanes falls back to scalars and chooses a sweep, known once it is built. Every other
    // kernel is shared: each thread, once done with its own, takes the next, costliest first,
    // until none is left. Each kernel is built from the same dynamics and setup on either thread,
    // so the module does not depend on which.
    let both_derivatives = outputs.contains(&Kernel::InverseDynamicsDerivatives)
        && outputs.contains(&Kernel::ForwardDynamicsDerivatives);
    let id_sweeps_on_both_threads = both_derivatives && !setup.derivative_lanes;
    let on_this_thread = |kernel: Kernel| match kernel {
        Kernel::ForwardDynamicsDerivatives => true,
        Kernel::InverseDynamicsDerivatives => !id_sweeps_on_both_threads,
        _ => false,
    };
    let on_the_other_thread = |kernel: Kernel| match kernel {
        Kernel::ForwardDynamics => true,
        Kernel::InverseDynamicsDerivatives => id_sweeps_on_both_threads,
        kernel => finds_base_parameters && reads_base(kernel),
    };
    let numbered = |keep: &dyn Fn(Kernel) -> bool| -> Vec<(usize, Kernel)> {
        outputs
            .iter()
            .copied()
            .enumerate()
            .filter(|&(_, kernel)| keep(kernel))
            .collect()
    };
    let mut shared = numbered(&|kernel| !on_this_thread(kernel) && !on_the_other_thread(kernel));
    shared.sort_by_key(|&(_, kernel)| costliest_first(kernel));
    let next_shared = AtomicUsize::new(0);
    let take_shared = || {
        shared
            .get(next_shared.fetch_add(1, Ordering::Relaxed))
            .copied()
    };
    let (forward_dynamics_choice, dynamics) = std::thread::scope(|scope| {
        // Made inside the scope: a panic here drops the sender before the scope joins the
        // other thread, which then stops waiting.
        let (handover, handed) = std::sync::mpsc::channel::<Option<(SymbolicDynamics, Duration)>>();
        let (reverse_cost_sender, reverse_cost) = std::sync::mpsc::channel::<usize>();
        let other = {
            let (dynamics, mut setup, mut dims) = (dynamics.clone(), setup.clone(), dims);
            let mut kernels = numbered(&on_the_other_thread);
            // The handed-over graph after the others, when it is most likely ready.
            kernels.sort_by_key(|&(_, kernel)| kernel == Kernel::InverseDynamicsDerivatives);
            let (emit, take_shared) = (&emit, &take_shared);
            let builds_forward_dynamics = kernels
                .iter()
                .any(|&(_, kernel)| kernel == Kernel::ForwardDynamics);
            scope.spawn(move || {
                let mut by_reverse_sweeps = id_sweeps_on_both_threads.then(|| {
                    let start = Instant::now();
                    let mut reverse = dynamics.clone().with_derivative_sweep(Sweep::Reverse);
                    let _ = reverse_cost_sender.send(reverse.inverse_dynamics_derivatives_cost());
                    (reverse, start.elapsed())
                });
                let choosing = Instant::now();
                let (forward_dynamics_choice, mut chosen_forward_dynamics) =
                    if builds_forward_dynamics && articulated_applies(&dynamics) {
                        let (choice, built) =
                            choose_forward_dynamics(&dynamics, &setup, scene.forward_dynamics);
                        (Some(choice), Some((built, choosing.elapsed())))
                    } else {
                        (None, None)
                    };
                setup.articulated = forward_dynamics_choice
                    .as_ref()
                    .is_some_and(|c| c.chosen == ForwardDynamicsMethod::Aba);
                if finds_base_parameters {
                    let base = dynamics.base_parameters();
                    dims.nb = base.len();
                    setup.base_parameters = Some(base);
                }
                let emitted: Vec<(usize, (String, KernelReport))> = kernels
                    .into_iter()
                    .chain(std::iter::from_fn(take_shared))
                    .map(|(k, kernel)| {
                        let (built, start) = match kernel {
                            Kernel::ForwardDynamics if chosen_forward_dynamics.is_some() => {
                                let (built, time) = chosen_forward_dynamics
                                    .take()
                                    .expect("forward dynamics is built once");
                                (built, started(time))
                            }
                            Kernel::InverseDynamicsDerivatives if id_sweeps_on_both_threads => {
                                let (graph, time) = handed
                                    .recv()
                                    .expect("the other thread says which sweep won")
                                    .or_else(|| by_reverse_sweeps.take())
                                    .expect("∂ID is built once");
                                // Not in lanes: both sweeps are built only then.
                                let start = started(time);
                                (build_in_scalars(graph, kernel, &setup), start)
                            }
                            _ => {
                                let start = Instant::now();
                                (build_kernel_with(&dynamics, kernel, &setup), start)
                            }
                        };
                        (k, emit(built, kernel, dims, start))
                    })
                    .collect();
                (forward_dynamics_choice, setup.base_parameters, emitted)
            })
        };
        if id_sweeps_on_both_threads {
            let start = Instant::now();
            let mut forward = dynamics.clone().with_derivative_sweep(Sweep::Forward);
            let forward_cost = forward.inverse_dynamics_derivatives_cost();
            // Fails only when the other thread has ended by a panic, which the join resumes;
            // until then this thread goes on as if the reverse sweeps had lost.
            let sweep = Sweep::cheaper(forward_cost, reverse_cost.recv().unwrap_or(usize::MAX));
            dynamics = dynamics.with_derivative_sweep(sweep);
            let _ = handover.send((sweep == Sweep::Forward).then(|| (forward, start.elapsed())));
        }
        let mut own = numbered(&on_this_thread);
        // ∂ID before ∂FD, which takes the sweep ∂ID chose if it fell back to scalars.
        own.sort_by_key(|&(_, kernel)| kernel == Kernel::ForwardDynamicsDerivatives);
        for (k, kernel) in own.into_iter().chain(std::iter::from_fn(&take_shared)) {
            let start = Instant::now();
            let built = build_kernel_with(&dynamics, kernel, &setup);
            if kernel == Kernel::InverseDynamicsDerivatives {
                if let Some(sweep) = built.dynamics.derivative_sweep() {
                    dynamics = dynamics.with_derivative_sweep(sweep);
                }
            }
            emitted[k] = Some(emit(built, kernel, dims, start));
        }
        let (forward_dynamics_choice, base_parameters, others) = other
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        for (k, function) in others {
            emitted[k] = Some(function);
        }
        if finds_base_parameters {
            setup.base_parameters = base_parameters;
        }
        (forward_dynamics_choice, dynamics)
    });
    let (functions, kernels): (Vec<String>, Vec<KernelReport>) = emitted
        .into_iter()
        .map(|e| e.expect("every kernel is emitted"))
        .unzip();
    let base_parameter_names = setup
        .base_parameters
        .as_ref()
        .map(|base| base.names(&parameter_names))
        .unwrap_or_default();

    let ndof_lit = Literal::usize_unsuffixed(ndof);
    let nq_lit = Literal::usize_unsuffixed(layout.nq());
    let nv_lit = Literal::usize_unsuffixed(layout.nv());
    let joint_names = joints.iter().map(|j| Literal::string(j));
    let module_doc = format!(
        "Dynamics of `{}`, generated by rne from `{source}`.",
        model.name
    );
    let params = match (&base_mode, scene.parameters) {
        (Some(base), _) => base_params(
            &dynamics.model,
            base,
            &parameter_names,
            &base_parameter_names,
        ),
        (None, ParameterMode::Runtime) => spec_params(&model),
        (None, _) => quote!(),
    };
    let model_type = ModelType {
        robot: &model.name,
        kernels: &outputs,
        scalar: scene.scalar,
        parameters: scene.parameters,
        runtime: &runtime,
        floating_base: layout.floating,
    }
    .emit();
    let frame_names: Vec<&str> = setup
        .frames
        .iter()
        .map(|&f| dynamics.frames()[f].name.as_str())
        .collect();
    let frames = outputs.iter().any(|k| k.is_kinematics()).then(|| {
        names_const(
            "NF",
            "FRAMES",
            "The frames of the kinematics functions (link names), in output order.",
            &frame_names,
        )
    });
    let names_parameters = base_mode.is_some() || outputs.iter().any(|k| k.is_identification());
    let parameters = names_parameters.then(|| {
        let standard: Vec<&str> = parameter_names.iter().map(String::as_str).collect();
        let base: Vec<&str> = base_parameter_names.iter().map(String::as_str).collect();
        let standard = names_const("NP", "PARAMETERS", "The standard parameters π of `regressor` (per body m, m·cx, m·cy, m·cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz about the body origin; then per joint fv, fc, f0, Ia as present), in column order.", &standard);
        let base = names_const("NB", "BASE_PARAMETERS", "The base parameters π_b of `base_regressor`: each named after the standard parameter it keeps, with `R` when others are regrouped into it (`base_parameters`).", &base);
        quote!(#standard #base)
    });
    let header = quote! {
        #[doc = #module_doc]
        #[doc = "Number of joint variables."]
        pub const NDOF: usize = #ndof_lit;
        #[doc = "Size of the configuration `q`: `NDOF`, after `[x, y, z, qx, qy, qz, qw]` of a floating base."]
        pub const NQ: usize = #nq_lit;
        #[doc = "Size of the velocity `qd` and of `qdd`, `tau` and the outputs: `NDOF`, after the six base velocities of a floating base."]
        pub const NV: usize = #nv_lit;
        #[doc = "Joint variable names, in state order."]
        pub const JOINTS: [&str; NDOF] = [#(#joint_names),*];
        #frames
        #parameters
        #params
    };
    let mut source = header.to_string();
    for function in functions {
        source.push('\n');
        source.push_str(&function);
    }
    source.push('\n');
    source.push_str(&model_type.to_string());
    Ok(GeneratedModule {
        source,
        ndof,
        joints,
        kernels,
        forward_dynamics_choice,
        generation_time: start.elapsed(),
    })
}

/// Whether `kernel` is built from the base parameters.
pub(crate) fn reads_base(kernel: Kernel) -> bool {
    matches!(kernel, Kernel::BaseRegressor | Kernel::BaseParameters)
}

/// Where `kernel` comes in the order the two threads take the shared kernels in: costliest
/// first, so that the last kernel taken is a cheap one and the threads end close together
/// (Graham's "longest processing time first", SIAM J. Appl. Math. 17(2), 1969). The order is
/// that of the kernels' generation times on a 48-joint chain (`rne stats`, docs/performance.md),
/// where the regressor (0.55 s), taken last in the module's order, had kept one thread busy
/// for 0.4 s after the other had run out of work.
fn costliest_first(kernel: Kernel) -> usize {
    const ORDER: [Kernel; 18] = [
        Kernel::ForwardDynamicsDerivatives,
        Kernel::InverseDynamicsDerivatives,
        Kernel::Regressor,
        Kernel::BaseRegressor,
        Kernel::MassMatrixInverse,
        Kernel::CoriolisMatrix,
        Kernel::FrameJacobians,
        Kernel::ForwardDynamics,
        Kernel::MassMatrix,
        Kernel::BaseParameters,
        Kernel::InverseDynamics,
        Kernel::BiasTorques,
        Kernel::FrameJacobianDotQd,
        Kernel::GravityTorques,
        Kernel::KineticEnergy,
        Kernel::FramePlacements,
        Kernel::PotentialEnergy,
        Kernel::FrictionTorques,
    ];
    ORDER
        .iter()
        .position(|&k| k == kernel)
        .unwrap_or(ORDER.len())
}

/// Emits a built kernel (its graph freed first: the largest kernels' graphs and text are not
/// held at the same time) and reports it, timed from `start`.
fn emit_built(
    built: BuiltKernel,
    kernel: Kernel,
    scene: &Scene,
    runtime: &str,
    fields: &[String],
    dims: Dims,
    start: Instant,
) -> (String, KernelReport) {
    drop(built.dynamics);
    let program = match scene.fma {
        true => built.program.fuse_multiply_add(),
        false => built.program,
    };
    let ctx = EmitContext {
        fields,
        scalar: scene.scalar,
        parameters: scene.parameters,
        runtime,
    };
    let function = emit_kernel(kernel, &program, dims, ctx);
    let report = KernelReport {
        kernel,
        ops: program.op_count(),
        critical_path: program.critical_path(),
        generation_time: start.elapsed(),
    };
    (function, report)
}

/// The instant `time` ago: when a kernel whose building took `time` so far started.
fn started(time: Duration) -> Instant {
    let now = Instant::now();
    now.checked_sub(time).unwrap_or(now)
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

/// `pub const SIZE: usize = n; pub const NAMES: [&str; SIZE] = [..];`.
fn names_const(size: &str, names: &str, doc: &str, values: &[&str]) -> TokenStream {
    let size = proc_macro2::Ident::new(size, proc_macro2::Span::call_site());
    let names = proc_macro2::Ident::new(names, proc_macro2::Span::call_site());
    let count = Literal::usize_unsuffixed(values.len());
    let size_doc = format!("The length of `{names}`.");
    quote! {
        #[doc = #size_doc]
        pub const #size: usize = #count;
        #[doc = #doc]
        pub const #names: [&str; #size] = [#(#values),*];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kernel has a place of its own in the threads' order: none falls to the end as
    /// unknown, and no two tie (a tie would leave their order to the sort).
    #[test]
    fn the_shared_order_places_every_kernel() {
        let mut places: Vec<usize> = Kernel::ALL.iter().map(|&k| costliest_first(k)).collect();
        places.sort_unstable();
        assert_eq!(places, (0..Kernel::ALL.len()).collect::<Vec<_>>());
    }
}
