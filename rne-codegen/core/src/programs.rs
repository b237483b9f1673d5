//! Every kernel of a scene as the optimised straight-line [`Program`] that [`generate`]
//! emits, with the facts about the module an emitter for another language needs (sizes,
//! names, parameters): the pipeline of [`generate`] without its Rust text, for the C
//! emitter (`emit_c`).
//!
//! The kernels are built one after the other on the calling thread, each by
//! [`build_kernel_with`] from the same dynamics and setup as in [`generate`], so each program
//! is the one [`generate`] emits as Rust — with one exception: the derivative kernels are
//! always built in scalars (the lanes of `derivatives: lanes` are vectors of the Rust
//! runtime).
//!
//! [`generate`]: crate::generate

use rne_symbolic::dynamics::base_parameters::BaseParameters;
use rne_symbolic::model::Parameter;
use rne_symbolic::{RobotModel, SymbolicDynamics};

use crate::error::CodegenError;
use crate::kernel::{articulated_applies, Dims, Kernel, KernelSetup};
use crate::module::{build_kernel_with, choose_forward_dynamics, reads_base};
use crate::module::{BuiltKernel, ForwardDynamicsChoice};
use crate::program::Program;
use crate::scene::{ForwardDynamicsMethod, ParameterMode, Scene};

/// The programs of a scene's kernels and what a module built from them declares.
#[derive(Clone, Debug)]
pub struct ModulePrograms {
    /// The robot's name (from its file).
    pub robot: String,
    /// Number of joint variables (after locking).
    pub ndof: usize,
    /// Size of the configuration `q` (NDOF, after 7 coordinates of a floating base).
    pub nq: usize,
    /// Whether the base is floating.
    pub floating_base: bool,
    /// Joint variable names, in state order.
    pub joints: Vec<String>,
    /// The frames (link names) of the kinematics kernels, in output order.
    pub frames: Vec<String>,
    /// The standard parameters π (the regressor's columns), in order.
    pub standard_parameters: Vec<String>,
    /// The base parameters π_b (the base regressor's columns), when a kernel or the
    /// parameter mode needs them; empty otherwise.
    pub base_parameter_names: Vec<String>,
    /// The base parameters themselves, in the same cases.
    pub base_parameters: Option<BaseParameters>,
    /// How parameters enter the kernels.
    pub parameter_mode: ParameterMode,
    /// The parameters read at run time (`Runtime`: the spec's; `Base`: the base parameters
    /// as identifiers), with the values of the robot file; empty for `Constant`.
    pub runtime_parameters: Vec<Parameter>,
    /// The name of each parameter symbol (`Symbol::Parameter(i)`) the programs read, by
    /// index: a runtime parameter's (`base_parameters`, which reads the standard parameters
    /// `standard[i]` instead, aside).
    pub parameter_symbols: Vec<String>,
    /// The sizes of the module's arrays.
    pub dims: Dims,
    /// Each kernel of the scene ([`Scene::kernels`]) and its program (fused multiply-adds with
    /// `fma: true`, as [`generate`](crate::generate) emits it), in the scene's order.
    pub kernels: Vec<(Kernel, Program)>,
    /// When `forward_dynamics` was built and both algorithms apply: the choice between them.
    pub forward_dynamics_choice: Option<ForwardDynamicsChoice>,
}

/// Builds the programs of the kernels `scene` asks for, for `model` (loaded with symbolic
/// parameters when the scene wants runtime parameters), with the checks of
/// [`generate`](crate::generate). `source` names the robot file in errors.
pub fn module_programs(
    model: &RobotModel,
    scene: &Scene,
    source: &str,
) -> Result<ModulePrograms, CodegenError> {
    let model = checked_model(model, scene, source)?;
    let mut dynamics = SymbolicDynamics::new(&model);
    if scene.zero_velocities {
        dynamics = dynamics.at_rest();
    }
    if scene.friction {
        dynamics = dynamics.with_friction();
    }
    let base_mode = (scene.parameters == ParameterMode::Base).then(|| {
        let (in_base, base) = dynamics.in_base_parameters();
        dynamics = in_base;
        base
    });
    let outputs = scene.kernels();
    let mut setup = KernelSetup {
        frames: scene.frame_indices(dynamics.frames())?,
        base_parameters: base_mode,
        articulated: false,
        derivative_lanes: false,
    };
    if setup.base_parameters.is_none() && outputs.iter().any(|&k| reads_base(k)) {
        setup.base_parameters = Some(dynamics.base_parameters());
    }
    let forward_dynamics =
        outputs.contains(&Kernel::ForwardDynamics) && articulated_applies(&dynamics);
    let (forward_dynamics_choice, mut chosen) = if forward_dynamics {
        let (choice, built) = choose_forward_dynamics(&dynamics, &setup, scene.forward_dynamics);
        (Some(choice), Some(built))
    } else {
        (None, None)
    };
    setup.articulated = forward_dynamics_choice
        .as_ref()
        .is_some_and(|c| c.chosen == ForwardDynamicsMethod::Aba);
    let programs = build_programs(&outputs, dynamics.clone(), &setup, &mut chosen, scene.fma);
    let standard_parameters = dynamics.parameter_names();
    let layout = dynamics.layout();
    let dims = Dims {
        nv: layout.nv(),
        nf: setup.frames.len(),
        np: standard_parameters.len(),
        nb: setup
            .base_parameters
            .as_ref()
            .map_or(0, BaseParameters::len),
    };
    let base_parameter_names = setup
        .base_parameters
        .as_ref()
        .map(|base| base.names(&standard_parameters))
        .unwrap_or_default();
    let runtime_parameters = match scene.parameters {
        ParameterMode::Constant => Vec::new(),
        ParameterMode::Runtime => model.parameters.clone(),
        ParameterMode::Base => dynamics.model.parameters.clone(),
    };
    Ok(ModulePrograms {
        robot: model.name.clone(),
        ndof: dynamics.dof(),
        nq: layout.nq(),
        floating_base: layout.floating,
        joints: dynamics.model.joint_names(),
        frames: setup
            .frames
            .iter()
            .map(|&f| dynamics.frames()[f].name.clone())
            .collect(),
        standard_parameters,
        base_parameter_names,
        base_parameters: setup.base_parameters,
        parameter_mode: scene.parameters,
        runtime_parameters,
        parameter_symbols: dynamics.model.graph.symbols().parameters().to_vec(),
        dims,
        kernels: outputs.into_iter().zip(programs).collect(),
        forward_dynamics_choice,
    })
}

/// `model` as `scene` sees it ([`Scene::apply`]), checked as [`generate`](crate::generate)
/// checks it: an invertible M for the kernels that invert it, numeric parameters for
/// `parameters: base`.
fn checked_model(
    model: &RobotModel,
    scene: &Scene,
    source: &str,
) -> Result<RobotModel, CodegenError> {
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
    if scene.parameters == ParameterMode::Base && !model.graph.symbols().parameters().is_empty() {
        return Err(CodegenError::SymbolicBaseParameters {
            robot: source.to_owned(),
        });
    }
    Ok(model)
}

/// The program of each of `outputs`, in order: `forward_dynamics` the one already built
/// (`chosen`) when there is one; `inverse_dynamics_derivatives` before
/// `forward_dynamics_derivatives`, which takes the sweep it chose, as in
/// [`generate`](crate::generate).
fn build_programs(
    outputs: &[Kernel],
    mut dynamics: SymbolicDynamics,
    setup: &KernelSetup,
    chosen: &mut Option<BuiltKernel>,
    fma: bool,
) -> Vec<Program> {
    let mut order: Vec<usize> = (0..outputs.len()).collect();
    order.sort_by_key(|&k| outputs[k] == Kernel::ForwardDynamicsDerivatives);
    let mut programs: Vec<Option<Program>> = vec![None; outputs.len()];
    for k in order {
        let kernel = outputs[k];
        let built = match chosen.take() {
            Some(built) if kernel == Kernel::ForwardDynamics => built,
            other => {
                *chosen = other;
                build_kernel_with(&dynamics, kernel, setup)
            }
        };
        if kernel == Kernel::InverseDynamicsDerivatives {
            if let Some(sweep) = built.dynamics.derivative_sweep() {
                dynamics = dynamics.with_derivative_sweep(sweep);
            }
        }
        programs[k] = Some(match fma {
            true => built.program.fuse_multiply_add(),
            false => built.program,
        });
    }
    programs
        .into_iter()
        .map(|p| p.expect("every kernel is built"))
        .collect()
}
