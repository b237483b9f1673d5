//! A robot's kernels compiled in memory: [`JitModel`].

use std::cell::RefCell;
use std::path::Path;
use std::sync::{Arc, OnceLock};
use std::time::Duration;

use cranelift_codegen::isa::OwnedTargetIsa;
use cranelift_codegen::settings::{self, Configurable};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::default_libcall_names;
use rne_codegen_core::{
    read_robot, GeneratedPrograms, GenerationOptions, Input, Kernel, KernelProgram, Scene,
};
use rne_symbolic::RobotModel;

use crate::admit;
use crate::code::{self, Arrays, Code, Entry, Out};
use crate::compile;
use crate::error::JitError;
use crate::lanes::{self, LaneKernel};
use crate::lower::{Lowered, Lowering, SIN_COS};
use crate::pipeline::{generate_and_compile, Pipelined};

/// The arrays of one state, borrowed. A kernel reads the ones it takes
/// ([`Kernel::inputs`]): q has NQ entries, the others NV; the arrays it does not take may be
/// empty.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct State<'a> {
    /// Configuration q.
    pub q: &'a [f64],
    /// Velocity q̇.
    pub qd: &'a [f64],
    /// Acceleration q̈.
    pub qdd: &'a [f64],
    /// Generalised forces τ.
    pub tau: &'a [f64],
}

impl<'a> State<'a> {
    /// The array of `input` (empty for the standard parameters, which are not a state's).
    pub(crate) fn input(&self, input: Input) -> &'a [f64] {
        match input {
            Input::Q => self.q,
            Input::Qd => self.qd,
            Input::Qdd => self.qdd,
            Input::Tau => self.tau,
            Input::Standard => &[],
        }
    }
}

thread_local! {
    /// The scratch array of this thread's single calls of split kernels, as long as the
    /// longest it has needed: a call allocates nothing. Every part stores a value to its slot
    /// before a later part loads it (`lower.rs`), so what earlier calls left there is never
    /// read.
    static SCRATCH: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

/// One kernel's compiled parts, called in turn.
pub(crate) struct Compiled {
    kernel: Kernel,
    /// The arrays the kernel takes, as bits (`admit.rs`).
    taken: u8,
    parts: Vec<Entry>,
    outputs: usize,
    scratch: usize,
}

/// How much work Cranelift spends on the code: the register allocator is most of the time to
/// compile, and most of the difference in speed (docs/performance.md, "Robots chosen at run
/// time"). Both tiers compute the same bits.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Tier {
    /// Cranelift's backtracking register allocator: the faster code.
    ///
    /// Both tiers run without Cranelift's optimiser (its e-graph pass): the programs arrive
    /// optimised and in an order that keeps few values alive (`rne_codegen_core`'s
    /// `register_order.rs`), which the optimiser would undo by placing each value at its first
    /// use.
    #[default]
    Optimized,
    /// Cranelift's single-pass register allocator: compiles several times faster, code about
    /// half as fast.
    Fast,
}

/// How long the kernels took to obtain.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Timings {
    /// From the robot model to the optimised programs (every kernel's).
    pub generation: Duration,
    /// Cranelift: the programs to machine code in memory.
    pub compilation: Duration,
}

/// A robot's kernels compiled in memory for this processor (crate docs).
///
/// Every kernel asked for is compiled from the same optimised program the macro emits, and
/// computes its operations in its order: with `fma` off its results are those of the macro's
/// kernel bit for bit. Calls check the lengths of their arrays and that the state is finite,
/// so no input reaches the compiled code that it could read out of bounds. The model is
/// `Send` and `Sync`: kernels may be called from any number of threads at once. Its code is
/// freed when it is dropped.
pub struct JitModel {
    robot: String,
    joints: Vec<String>,
    nq: usize,
    nv: usize,
    frames: Vec<String>,
    parameter_names: Vec<String>,
    base_parameter_names: Vec<String>,
    parameter_symbols: Vec<String>,
    parameters: Vec<f64>,
    fused: bool,
    /// The options' `fma` and the tier, for the kernels compiled later (in lanes).
    fma: bool,
    tier: Tier,
    timings: Timings,
    kernels: Vec<Compiled>,
    /// Each kernel of `kernels` in two lanes, compiled at its first batch (`lanes.rs`).
    lanes: Vec<OnceLock<Result<LaneKernel, String>>>,
    /// Each kernel returning several matrices in two lanes with an output block per matrix,
    /// compiled at its first batch into separate arrays (`matrices.rs`).
    matrix_lanes: Vec<OnceLock<Result<LaneKernel, String>>>,
    /// States a batch computes per call: 2, or 1 as `RNE_JIT_LANES` says.
    batch_lanes: usize,
    programs: GeneratedPrograms,
    /// The memory the entries above point into, freed when the model is dropped.
    _code: Code,
}

impl JitModel {
    /// Reads the robot file `path` (TOML spec or URDF) as `scene` and `options` say and
    /// compiles the kernels the options ask for.
    pub fn load(
        path: &Path,
        scene: &Scene,
        options: &GenerationOptions,
    ) -> Result<JitModel, JitError> {
        let origin = path.display().to_string();
        let model = read_robot(path, &origin, scene, options)?;
        JitModel::compile(&model, scene, options, &origin)
    }

    /// Compiles the kernels `options` ask for, for `model` in `scene`, at [`Tier::Optimized`];
    /// `source` names the robot file in errors.
    pub fn compile(
        model: &RobotModel,
        scene: &Scene,
        options: &GenerationOptions,
        source: &str,
    ) -> Result<JitModel, JitError> {
        JitModel::compile_at(model, scene, options, source, Tier::Optimized)
    }

    /// Compiles the kernels `options` ask for, for `model` in `scene`, at `tier`.
    pub fn compile_at(
        model: &RobotModel,
        scene: &Scene,
        options: &GenerationOptions,
        source: &str,
        tier: Tier,
    ) -> Result<JitModel, JitError> {
        let Pipelined {
            programs,
            module,
            fused,
            kernels,
            timings,
        } = generate_and_compile(model, scene, options, source, tier)?;
        let lanes = kernels.iter().map(|_| OnceLock::new()).collect();
        let matrix_lanes = kernels.iter().map(|_| OnceLock::new()).collect();
        Ok(JitModel {
            robot: programs.robot.clone(),
            joints: programs.joints.clone(),
            nq: programs.nq,
            nv: programs.dims.nv,
            frames: programs.frames.clone(),
            parameter_names: programs.parameter_names.clone(),
            base_parameter_names: programs.base_parameter_names.clone(),
            parameter_symbols: programs.parameter_symbols.clone(),
            parameters: programs.parameter_values.clone(),
            fused,
            fma: options.fma,
            tier,
            timings,
            kernels,
            lanes,
            matrix_lanes,
            batch_lanes: lanes::from_env(),
            programs,
            _code: Code::new(module),
        })
    }

    /// The robot's name.
    pub fn robot(&self) -> &str {
        &self.robot
    }

    /// Joint variable names, in state order.
    pub fn joints(&self) -> &[String] {
        &self.joints
    }

    /// Size of the configuration q (NQ: NV + 1 on a floating base).
    pub fn nq(&self) -> usize {
        self.nq
    }

    /// Size of the velocity and of q̈ and τ (NV).
    pub fn nv(&self) -> usize {
        self.nv
    }

    /// The frames of the kinematics kernels (link names), in output order.
    pub fn frames(&self) -> &[String] {
        &self.frames
    }

    /// The standard parameters' names: the regressor's columns (Pinocchio's order per body).
    pub fn parameter_names(&self) -> &[String] {
        &self.parameter_names
    }

    /// The base parameters' names: the base regressor's columns.
    pub fn base_parameter_names(&self) -> &[String] {
        &self.base_parameter_names
    }

    /// The kernels compiled, in the options' order.
    pub fn kernels(&self) -> Vec<Kernel> {
        self.kernels.iter().map(|k| k.kernel).collect()
    }

    /// Whether `kernel` was compiled.
    pub fn has(&self, kernel: Kernel) -> bool {
        self.compiled(kernel).is_some()
    }

    /// The number of values `kernel` returns (matrices row-major, tuples concatenated).
    pub fn output_len(&self, kernel: Kernel) -> Option<usize> {
        self.compiled(kernel).map(|k| k.outputs)
    }

    /// Whether multiply-adds are fused: the options' `fma` on a processor with FMA.
    pub fn fused(&self) -> bool {
        self.fused
    }

    /// How long generation and compilation took.
    pub fn timings(&self) -> Timings {
        self.timings
    }

    /// The programs compiled: what the kernels compute, operation by operation.
    pub fn programs(&self) -> &GeneratedPrograms {
        &self.programs
    }

    /// The names of the run-time parameters the kernels read (`parameters: runtime`: the
    /// spec's named parameters; `base`: the base parameters); empty for constant ones.
    pub fn parameter_symbols(&self) -> &[String] {
        &self.parameter_symbols
    }

    /// Their values, the robot file's until [`JitModel::set_parameters`].
    pub fn parameters(&self) -> &[f64] {
        &self.parameters
    }

    /// Sets the run-time parameters' values, in [`JitModel::parameter_symbols`]' order.
    pub fn set_parameters(&mut self, values: &[f64]) -> Result<(), JitError> {
        if values.len() != self.parameters.len() {
            return Err(JitError::ParameterLength {
                got: values.len(),
                expected: self.parameters.len(),
            });
        }
        self.parameters.copy_from_slice(values);
        Ok(())
    }

    fn compiled(&self, kernel: Kernel) -> Option<&Compiled> {
        self.kernels.iter().find(|k| k.kernel == kernel)
    }

    /// `kernel` in two lanes (two states a call), compiled at the first call (`lanes.rs`);
    /// `None` where batches run one state a call ([`lanes::from_env`]).
    pub(crate) fn lane_kernel(&self, kernel: Kernel) -> Result<Option<&Compiled>, JitError> {
        self.compiled_lanes(&self.lanes, kernel, 0)
    }

    /// `kernel` in two lanes with an output block per matrix (`matrices.rs`), compiled at the
    /// first call; `None` where batches run one state a call.
    pub(crate) fn matrix_lane_kernel(
        &self,
        kernel: Kernel,
        matrices: usize,
    ) -> Result<Option<&Compiled>, JitError> {
        self.compiled_lanes(&self.matrix_lanes, kernel, matrices)
    }

    /// `kernel` in two lanes with `blocks` output blocks, from `cache` (one entry per
    /// kernel), compiled there at the first call.
    fn compiled_lanes<'s>(
        &'s self,
        cache: &'s [OnceLock<Result<LaneKernel, String>>],
        kernel: Kernel,
        blocks: usize,
    ) -> Result<Option<&'s Compiled>, JitError> {
        if self.batch_lanes == 1 {
            return Ok(None);
        }
        let index = self.kernels.iter().position(|k| k.kernel == kernel);
        let program = self.programs.kernels.iter().find(|k| k.kernel == kernel);
        let (Some(index), Some(program)) = (index, program) else {
            return Err(JitError::MissingKernel { kernel });
        };
        cache[index]
            .get_or_init(|| LaneKernel::compile(program, self.fma, self.tier, blocks))
            .as_ref()
            .map(|lane| Some(lane.compiled()))
            .map_err(|message| JitError::Compile {
                kernel,
                message: message.clone(),
            })
    }

    /// `kernel` at `state` into `out` (its [`JitModel::output_len`] values). The arrays the
    /// kernel takes must have the robot's lengths and finite values (an error otherwise).
    pub fn evaluate(
        &self,
        kernel: Kernel,
        state: State<'_>,
        out: &mut [f64],
    ) -> Result<(), JitError> {
        // Not `ok_or`, whose error is built and dropped at every call (it shows in profiles).
        let Some(compiled) = self.compiled(kernel) else {
            return Err(JitError::MissingKernel { kernel });
        };
        if !(self.admits(compiled, &state) && out.len() == compiled.outputs) {
            return Err(self.refusal(kernel, &state, out.len(), compiled.outputs));
        }
        self.run(compiled, state, &self.parameters, out);
        Ok(())
    }

    /// `kernel` at `state`, as a new vector.
    pub fn evaluate_vec(&self, kernel: Kernel, state: State<'_>) -> Result<Vec<f64>, JitError> {
        let len = self
            .output_len(kernel)
            .ok_or(JitError::MissingKernel { kernel })?;
        let mut out = vec![0.0; len];
        self.evaluate(kernel, state, &mut out)?;
        Ok(out)
    }

    /// The base parameters π_b of the standard parameters `standard` (the `base_parameters`
    /// kernel; NP values in, NB out).
    pub fn base_parameters(&self, standard: &[f64]) -> Result<Vec<f64>, JitError> {
        let kernel = Kernel::BaseParameters;
        let compiled = self
            .compiled(kernel)
            .ok_or(JitError::MissingKernel { kernel })?;
        let expected = self.parameter_names.len();
        if standard.len() != expected {
            return Err(JitError::InputLength {
                kernel,
                input: Input::Standard,
                got: standard.len(),
                expected,
            });
        }
        admit::check_finite(kernel, Input::Standard, standard)?;
        let mut out = vec![0.0; compiled.outputs];
        self.run(compiled, State::default(), standard, &mut out);
        Ok(out)
    }

    /// Runs every part of `compiled`; the arrays are checked.
    #[inline]
    pub(crate) fn run(
        &self,
        compiled: &Compiled,
        state: State<'_>,
        parameters: &[f64],
        out: &mut [f64],
    ) {
        if compiled.scratch == 0 {
            return self.run_in(compiled, state, parameters, Out::Whole(out), &mut []);
        }
        let reused = SCRATCH.try_with(|cell| {
            let Ok(mut scratch) = cell.try_borrow_mut() else {
                return false;
            };
            if scratch.len() < compiled.scratch {
                scratch.resize(compiled.scratch, 0.0);
            }
            self.run_in(compiled, state, parameters, Out::Whole(out), &mut scratch);
            true
        });
        if !matches!(reused, Ok(true)) {
            let scratch = &mut compiled.scratch();
            self.run_in(compiled, state, parameters, Out::Whole(out), scratch);
        }
    }

    /// [`JitModel::run`] with the kernel's scratch array given (`compiled.scratch()`), so that
    /// a batch allocates it once.
    pub(crate) fn run_in(
        &self,
        compiled: &Compiled,
        state: State<'_>,
        parameters: &[f64],
        out: Out<'_, '_>,
        scratch: &mut [f64],
    ) {
        let arrays = Arrays {
            q: state.q,
            qd: state.qd,
            qdd: state.qdd,
            tau: state.tau,
            parameters,
        };
        compiled
            .run(arrays, out, scratch)
            .expect("the arrays were checked against the kernel's inputs");
    }

    /// The compiled kernel, for the batch functions.
    pub(crate) fn compiled_kernel(&self, kernel: Kernel) -> Result<&Compiled, JitError> {
        self.compiled(kernel)
            .ok_or(JitError::MissingKernel { kernel })
    }
}

impl Compiled {
    /// The kernel.
    pub(crate) fn kernel(&self) -> Kernel {
        self.kernel
    }

    /// The arrays the kernel takes, as bits (`admit.rs`).
    pub(crate) fn taken(&self) -> u8 {
        self.taken
    }

    /// Values per call.
    pub(crate) fn outputs(&self) -> usize {
        self.outputs
    }

    /// A scratch array for one call at a time (empty for a kernel of one part).
    pub(crate) fn scratch(&self) -> Vec<f64> {
        vec![0.0; self.scratch]
    }

    /// Runs the kernel's functions in turn, or `None` when an array is shorter than a
    /// function reaches ([`Entry::call`]).
    #[inline]
    pub(crate) fn run(
        &self,
        arrays: Arrays<'_>,
        mut out: Out<'_, '_>,
        scratch: &mut [f64],
    ) -> Option<()> {
        for part in &self.parts {
            part.call(arrays, out.reborrow(), scratch)?;
        }
        Some(())
    }
}

/// Lowers the kernels' programs to Cranelift IR in `lanes` lanes with `blocks` output blocks
/// (0: none; [`Lowering::blocks`]), compiles all their functions in one pool (longest first)
/// and finalises the code: the module that owns it, whether multiply-adds are fused, and each
/// kernel's entry points.
pub(crate) fn compile_programs(
    kernels: &[&KernelProgram],
    fma: bool,
    tier: Tier,
    (lanes, blocks): (usize, usize),
) -> Result<(JITModule, bool, Vec<Compiled>), JitError> {
    let (mut module, isa, fused) = host_module(fma, tier)?;
    let first = kernels
        .first()
        .map_or(Kernel::InverseDynamics, |k| k.kernel);
    let mut lowering =
        Lowering::new(&mut module, fused, lanes, tier).map_err(|message| JitError::Compile {
            kernel: first,
            message,
        })?;
    lowering.blocks = blocks;
    let lowered = lower_all(&mut module, &mut lowering, kernels)?;
    let functions: Vec<Arc<Lowered>> = lowered
        .iter()
        .flat_map(|(_, _, parts)| parts.iter().cloned())
        .collect();
    let mut outcomes = compile::compile_all(&*isa, &functions).into_iter();
    let compiled = lowered
        .into_iter()
        .map(|(kernel, outputs, parts)| {
            let parts = parts
                .into_iter()
                .map(|part| (part, outcomes.next().expect("one outcome a function")))
                .collect();
            (kernel, outputs, parts)
        })
        .collect();
    let kernels = define_kernels(&mut module, compiled)?;
    Ok((module, fused, kernels))
}

/// A kernel, its number of outputs and its functions, each with how its compilation went.
pub(crate) type CompiledParts = (Kernel, usize, Vec<(Arc<Lowered>, compile::Outcome)>);

/// Defines the functions of `kernels` in `module` from their outcomes, in the kernels' order
/// (the code and its layout do not depend on the order they were compiled in), finalises the
/// code and gives each kernel's entry points. A failure names the kernel whose function failed.
pub(crate) fn define_kernels(
    module: &mut JITModule,
    kernels: Vec<CompiledParts>,
) -> Result<Vec<Compiled>, JitError> {
    let first = kernels
        .first()
        .map_or(Kernel::InverseDynamics, |(kernel, _, _)| *kernel);
    let (mut owners, mut functions, mut outcomes) = (Vec::new(), Vec::new(), Vec::new());
    let mut layout = Vec::with_capacity(kernels.len());
    for (kernel, outputs, parts) in kernels {
        let mut own = Vec::with_capacity(parts.len());
        for (part, outcome) in parts {
            owners.push(kernel);
            functions.push(Arc::clone(&part));
            outcomes.push(outcome);
            own.push(part);
        }
        layout.push((kernel, outputs, own));
    }
    compile::define(module, &functions, outcomes).map_err(|(k, message)| JitError::Compile {
        kernel: owners[k],
        message,
    })?;
    module
        .finalize_definitions()
        .map_err(|e| JitError::Compile {
            kernel: first,
            message: e.to_string(),
        })?;
    Ok(layout
        .into_iter()
        .map(|(kernel, outputs, parts)| entries(module, kernel, outputs, &parts))
        .collect())
}

/// A kernel, its number of outputs and its lowered functions.
type KernelParts = (Kernel, usize, Vec<Arc<Lowered>>);

/// Every kernel of `kernels` lowered in `module`: the kernel, its number of outputs and its
/// functions.
fn lower_all(
    module: &mut JITModule,
    lowering: &mut Lowering,
    kernels: &[&KernelProgram],
) -> Result<Vec<KernelParts>, JitError> {
    kernels
        .iter()
        .map(|k| {
            let parts = lower_kernel(module, lowering, k)?;
            Ok((k.kernel, k.program.outputs.len(), parts))
        })
        .collect()
}

/// One kernel's program lowered in `module`: its functions, in order.
pub(crate) fn lower_kernel(
    module: &mut JITModule,
    lowering: &mut Lowering,
    k: &KernelProgram,
) -> Result<Vec<Arc<Lowered>>, JitError> {
    let parts = lowering
        .lower(module, k.kernel.name(), &k.program)
        .map_err(|message| JitError::Compile {
            kernel: k.kernel,
            message,
        })?;
    Ok(parts.into_iter().map(Arc::new).collect())
}

/// The entries into `kernel`'s finalized `parts` in `module`.
pub(crate) fn entries(
    module: &JITModule,
    kernel: Kernel,
    outputs: usize,
    parts: &[Arc<Lowered>],
) -> Compiled {
    let scratch = parts.iter().map(|p| p.extents.scratch).max().unwrap_or(0);
    let parts = parts
        .iter()
        .map(|part| {
            let address = module.get_finalized_function(part.id);
            // SAFETY: `part.id` was defined with the kernels' signature from the IR
            // `Lowering` built, which recorded `part.extents`; `module` becomes the model's
            // `Code`, which outlives the entries (code.rs).
            unsafe { Entry::new(address, part.extents) }
        })
        .collect();
    Compiled {
        kernel,
        taken: admit::taken(kernel),
        parts,
        outputs,
        scratch,
    }
}

/// Whether this processor has a JIT backend: `Err(`[`JitError::UnsupportedHost`]`)` saying why
/// not, where callers fall back to the interpreter.
pub fn host_support() -> Result<(), JitError> {
    host_module(false, Tier::Fast).map(|_| ())
}

/// A JIT module for this processor (below), the processor's ISA, shared with the module, for
/// compiling outside it, and whether multiply-adds are fused.
///
/// The module is for this processor, its features detected at run time, with the runtime's
/// sines and cosines linked in; multiply-adds are fused when `fma` is asked for and the
/// processor has FMA.
pub(crate) fn host_module(
    fma: bool,
    tier: Tier,
) -> Result<(JITModule, OwnedTargetIsa, bool), JitError> {
    let mut flags = settings::builder();
    let set = |flags: &mut settings::Builder, name: &str, value: &str| {
        flags
            .set(name, value)
            .map_err(|e| JitError::UnsupportedHost(format!("setting {name}: {e}")))
    };
    let (optimizer, allocator) = match tier {
        Tier::Optimized => ("none", "backtracking"),
        Tier::Fast => ("none", "single_pass"),
    };
    set(&mut flags, "opt_level", optimizer)?;
    set(&mut flags, "regalloc_algorithm", allocator)?;
    set(&mut flags, "use_colocated_libcalls", "false")?;
    set(&mut flags, "is_pic", "false")?;
    set(
        &mut flags,
        "enable_verifier",
        if cfg!(debug_assertions) {
            "true"
        } else {
            "false"
        },
    )?;
    let isa = cranelift_native::builder()
        .map_err(|e| JitError::UnsupportedHost(e.to_owned()))?
        .finish(settings::Flags::new(flags))
        .map_err(|e| JitError::UnsupportedHost(e.to_string()))?;
    // AArch64 always has fused multiply-add; x86-64 when the processor reports FMA.
    let processor_fuses = cfg!(target_arch = "aarch64")
        || isa
            .isa_flags()
            .iter()
            .any(|flag| flag.name == "has_fma" && flag.as_bool() == Some(true));
    let mut builder = JITBuilder::with_isa(isa.clone(), default_libcall_names());
    builder.symbol(SIN_COS, code::sin_cos_array as *const u8);
    Ok((JITModule::new(builder), isa, fma && processor_fuses))
}
