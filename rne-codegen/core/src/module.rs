//! A whole generated module, and [`generate`], which makes it in named stages: validate and
//! plan ([`Plan`]), build every kernel on two threads ([`crate::schedule`]), emit each as Rust
//! ([`emit_kernel`]), assemble the module ([`crate::assemble`]).

use std::time::{Duration, Instant};

use proc_macro2::TokenStream;
use rne_symbolic::{OpCount, RobotModel};

use crate::assemble::module_source;
use crate::built::BuiltKernel;
use crate::emit::{emit_kernel, EmitContext};
use crate::error::CodegenError;
use crate::generation_options::{ForwardDynamicsMethod, GenerationOptions};
use crate::kernel::{Dims, Kernel};
use crate::plan::Plan;
use crate::programs::final_program;
use crate::scene::Scene;
use crate::schedule;

/// What was generated for one kernel.
#[derive(Clone, Debug, PartialEq)]
pub struct KernelReport {
    /// The kernel.
    pub kernel: Kernel,
    /// Operations per call of the emitted function.
    pub ops: OpCount,
    /// Its critical path in modelled cycles ([`Program::critical_path`](crate::Program::critical_path)).
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
    /// kernels are written as text (`emit_kernel`), which costs a small fraction of the
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

/// Generates the kernels `options` ask for, for `model` in `scene` (`model` loaded with
/// symbolic parameters when the options want runtime parameters). `source` names the robot
/// file in the docs.
pub fn generate(
    model: &RobotModel,
    scene: &Scene,
    options: &GenerationOptions,
    source: &str,
) -> Result<GeneratedModule, CodegenError> {
    let start = Instant::now();
    let plan = Plan::new(model, scene, options, source)?;
    let runtime = options.runtime_path()?;
    let runtime_text = runtime.to_string();
    let emit = |built: BuiltKernel, kernel: Kernel, dims: Dims, start: Instant| {
        Ok(emit_built(built, kernel, &plan, &runtime_text, dims, start))
    };
    let built = schedule::build(&plan, &emit)?;
    let base_parameter_names = built
        .base_parameters
        .as_ref()
        .map(|base| base.names(&plan.parameter_names))
        .unwrap_or_default();
    let (functions, kernels): (Vec<String>, Vec<KernelReport>) = built.kernels.into_iter().unzip();
    Ok(GeneratedModule {
        source: module_source(&plan, functions, &base_parameter_names, &runtime),
        ndof: plan.dynamics.dof(),
        joints: plan.dynamics.model.joint_names(),
        kernels,
        forward_dynamics_choice: built.forward_dynamics_choice,
        generation_time: start.elapsed(),
    })
}

/// Emits a built kernel (its graph freed first: the largest kernels' graphs and text are not
/// held at the same time) and reports it, timed from `start`.
fn emit_built(
    built: BuiltKernel,
    kernel: Kernel,
    plan: &Plan,
    runtime: &str,
    dims: Dims,
    start: Instant,
) -> (String, KernelReport) {
    let options = plan.options;
    drop(built.dynamics);
    let program = final_program(built.program, options.fma);
    let ctx = EmitContext {
        fields: &plan.fields,
        scalar: options.scalar,
        parameters: options.parameters,
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
