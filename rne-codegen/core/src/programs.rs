//! The generated programs themselves, for backends other than the Rust emitter (the JIT, the
//! C emitter): the same stages as [`crate::generate`] — validate, plan, build on two threads —
//! ending in each kernel's optimised [`Program`] instead of its Rust text, so every backend
//! computes the operations the macro's kernels compute, in their order.

use std::time::{Duration, Instant};

use rne_symbolic::dynamics::base_parameters::BaseParameters;
use rne_symbolic::model::Parameter;
use rne_symbolic::{RobotModel, Symbol};

use crate::built::BuiltKernel;
use crate::error::CodegenError;
use crate::generation_options::{GenerationOptions, ParameterMode};
use crate::kernel::{Dims, Kernel};
use crate::module::{ForwardDynamicsChoice, KernelReport};
use crate::plan::Plan;
use crate::program::Program;
use crate::scene::Scene;
use crate::schedule;
use std::sync::Arc;

/// One kernel's program and how it was made.
#[derive(Clone, Debug)]
pub struct KernelProgram {
    /// The kernel.
    pub kernel: Kernel,
    /// Its program, with multiply-adds fused when the options say `fma`
    /// ([`Program::fuse_multiply_add`]); matrices' outputs row-major, tuples concatenated.
    /// Shared: a backend handed each program as it is built ([`generate_programs_each`])
    /// keeps it without a copy.
    pub program: Arc<Program>,
    /// Its operation count, critical path and generation time.
    pub report: KernelReport,
}

/// Every kernel the options ask for, as programs, and what reading them needs.
#[derive(Clone, Debug)]
pub struct GeneratedPrograms {
    /// The robot's name.
    pub robot: String,
    /// The kernels, in the options' order ([`GenerationOptions::kernels`]).
    pub kernels: Vec<KernelProgram>,
    /// Joint variable names, in state order.
    pub joints: Vec<String>,
    /// Number of joint variables (after locking).
    pub ndof: usize,
    /// Size of the configuration q.
    pub nq: usize,
    /// The sizes of the arrays: NV, NF frames, NP standard and NB base parameters.
    pub dims: Dims,
    /// Whether the robot has a free-flyer root.
    pub floating_base: bool,
    /// The frames of the kinematics kernels (link names), in output order.
    pub frames: Vec<String>,
    /// The standard parameters' names (the regressor's columns).
    pub parameter_names: Vec<String>,
    /// The base parameters' names, when a kernel reads them.
    pub base_parameter_names: Vec<String>,
    /// The value of each `Symbol::Parameter(i)` the programs read (runtime or base
    /// parameters), at the robot file's values; empty for constant parameters.
    /// `base_parameters` reads the standard parameters there instead.
    pub parameter_values: Vec<f64>,
    /// The names of those parameters.
    pub parameter_symbols: Vec<String>,
    /// How parameters enter the kernels.
    pub parameter_mode: ParameterMode,
    /// The parameters read at run time (`Runtime`: the robot file's; `Base`: the base
    /// parameters as identifiers), with the robot file's values; empty for `Constant`.
    pub runtime_parameters: Vec<Parameter>,
    /// The base parameters (their map from the standard ones), when a kernel or the parameter
    /// mode reads them.
    pub base_parameters: Option<BaseParameters>,
    /// Both ways forward dynamics could be built, when it was and both apply.
    pub forward_dynamics_choice: Option<ForwardDynamicsChoice>,
    /// The model as the scene sees it (base, mimic, gravity, locks applied).
    pub model: RobotModel,
    /// Time from the robot model to the last program.
    pub generation_time: Duration,
}

/// The programs of every kernel `options` ask for, for `model` in `scene`; `source` names the
/// robot file. The derivative kernels are built in scalars (lanes are the Rust emitter's).
pub fn generate_programs(
    model: &RobotModel,
    scene: &Scene,
    options: &GenerationOptions,
    source: &str,
) -> Result<GeneratedPrograms, CodegenError> {
    generate_programs_each(model, scene, options, source, &|_| {})
}

/// [`generate_programs`], handing each kernel's program to `on_program` as soon as it is
/// built, on the thread that built it, in the order the kernels are finished (not the
/// options' order): a backend can start on the first kernels while the costliest are still
/// being built.
pub fn generate_programs_each(
    model: &RobotModel,
    scene: &Scene,
    options: &GenerationOptions,
    source: &str,
    on_program: &(dyn Fn(&KernelProgram) + Sync),
) -> Result<GeneratedPrograms, CodegenError> {
    let start = Instant::now();
    let scalar_options = GenerationOptions {
        derivative_lanes: false,
        ..options.clone()
    };
    let plan = Plan::new(model, scene, &scalar_options, source)?;
    let finish = |built: BuiltKernel, kernel: Kernel, _: Dims, start: Instant| {
        let finished = kernel_program(built, kernel, options.fma, start);
        on_program(&finished);
        Ok(finished)
    };
    let built = schedule::build(&plan, &finish)?;
    let symbols = plan.dynamics.model.graph.symbols();
    let parameter_symbols: Vec<String> = symbols.parameters().to_vec();
    let parameter_values = (0..parameter_symbols.len())
        .map(|i| {
            let symbol = Symbol::Parameter(i as u16);
            plan.dynamics
                .model
                .parameter_value(symbol)
                .unwrap_or(f64::NAN)
        })
        .collect();
    let runtime_parameters = match options.parameters {
        ParameterMode::Constant => Vec::new(),
        ParameterMode::Runtime => plan.model.parameters.clone(),
        ParameterMode::Base => plan.dynamics.model.parameters.clone(),
    };
    let base_parameters = built.base_parameters.as_ref();
    Ok(GeneratedPrograms {
        robot: plan.model.name.clone(),
        kernels: built.kernels,
        joints: plan.dynamics.model.joint_names(),
        ndof: plan.dynamics.dof(),
        nq: plan.dynamics.layout().nq(),
        dims: Dims {
            nb: base_parameters.map_or(0, |b| b.len()),
            ..plan.dims
        },
        floating_base: plan.dynamics.layout().floating,
        frames: plan
            .setup
            .frames
            .iter()
            .map(|&f| plan.dynamics.frames()[f].name.clone())
            .collect(),
        base_parameter_names: base_parameters
            .map(|b| b.names(&plan.parameter_names))
            .unwrap_or_default(),
        parameter_names: plan.parameter_names.clone(),
        parameter_values,
        parameter_symbols,
        parameter_mode: options.parameters,
        runtime_parameters,
        base_parameters: built.base_parameters.clone(),
        forward_dynamics_choice: built.forward_dynamics_choice,
        model: plan.model.clone(),
        generation_time: start.elapsed(),
    })
}

/// The program every backend is given for a built kernel: its multiply-adds fused when `fma`
/// ([`Program::fuse_multiply_add`]), then its instructions put in an order that keeps few
/// values alive at once ([`Program::in_register_order`], after the fusion, which chooses by
/// the program's order on ties). Neither step changes a value of the unfused or fused program.
pub(crate) fn final_program(program: Program, fma: bool) -> Program {
    let program = match fma {
        true => program.fuse_multiply_add(),
        false => program,
    };
    program.in_register_order()
}

/// A built kernel's program ([`final_program`]) with its report; `start` is when its building
/// started.
fn kernel_program(built: BuiltKernel, kernel: Kernel, fma: bool, start: Instant) -> KernelProgram {
    let program = final_program(built.program, fma);
    let report = KernelReport {
        kernel,
        ops: program.op_count(),
        critical_path: program.critical_path(),
        generation_time: start.elapsed(),
    };
    KernelProgram {
        kernel,
        program: Arc::new(program),
        report,
    }
}
