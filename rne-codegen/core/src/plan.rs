//! The first two stages of generation: validate the scene against the robot, then plan the
//! module — the dynamics every kernel is built from, the frames, the parameters and the sizes
//! of its arrays. Nothing here builds a kernel; [`crate::schedule`] does.

use rne_symbolic::dynamics::base_parameters::BaseParameters;
use rne_symbolic::{RobotModel, SymbolicDynamics};

use crate::emit::{is_valid_parameter_name, parameter_fields};
use crate::error::CodegenError;
use crate::generation_options::{GenerationOptions, ParameterMode, ScalarType};
use crate::kernel::{Dims, Kernel, KernelSetup};
use crate::scene::Scene;

/// What a module is generated from: the robot as the scene sees it, the options, and
/// everything decided before the first kernel is built.
#[derive(Clone, Debug)]
pub struct Plan<'a> {
    /// How the code is generated.
    pub options: &'a GenerationOptions,
    /// The robot file, as the module's docs name it.
    pub source: &'a str,
    /// The model with the scene applied (base, mimic, gravity, locks).
    pub model: RobotModel,
    /// The dynamics every kernel is built from: at rest, with friction or in base parameters
    /// as the scene says; nothing built in it yet.
    pub dynamics: SymbolicDynamics,
    /// The base parameters when every kernel is a function of them (`parameters: base`).
    pub base_mode: Option<BaseParameters>,
    /// The kernels, in emission order ([`GenerationOptions::kernels`]).
    pub kernels: Vec<Kernel>,
    /// What the kernels are built with besides the dynamics; its base parameters are found
    /// while building when [`Plan::finds_base_parameters`].
    pub setup: KernelSetup,
    /// Whether a kernel reads the base parameters and they are not known yet.
    pub finds_base_parameters: bool,
    /// The standard parameters' names (`PARAMETERS`).
    pub parameter_names: Vec<String>,
    /// The `Params` field of each parameter symbol.
    pub fields: Vec<String>,
    /// The sizes of the module's arrays (NB once the base parameters are found).
    pub dims: Dims,
}

impl<'a> Plan<'a> {
    /// Validates `scene` and `options` against `model` and plans the module; `source` names
    /// the robot file.
    pub fn new(
        model: &RobotModel,
        scene: &Scene,
        options: &'a GenerationOptions,
        source: &'a str,
    ) -> Result<Plan<'a>, CodegenError> {
        let mut model = validate(model, scene, options, source)?;
        model.graph.set_node_limit(options.node_limit);
        let mut dynamics = SymbolicDynamics::new(&model);
        if scene.at_rest {
            dynamics = dynamics.at_rest();
        }
        if scene.friction {
            dynamics = dynamics.with_friction();
        }
        let base_mode = (options.parameters == ParameterMode::Base).then(|| {
            let (in_base, base) = dynamics.in_base_parameters();
            dynamics = in_base;
            base
        });
        let kernels = options.kernels();
        let setup = KernelSetup {
            frames: options.frame_indices(dynamics.frames())?,
            base_parameters: base_mode.clone(),
            articulated: false,
            derivative_lanes: options.derivative_lanes && options.scalar == ScalarType::F64,
        };
        let parameter_names = dynamics.parameter_names();
        let dims = Dims {
            nv: dynamics.layout().nv(),
            nf: setup.frames.len(),
            np: parameter_names.len(),
            nb: base_mode.as_ref().map_or(0, BaseParameters::len),
        };
        Ok(Plan {
            options,
            source,
            finds_base_parameters: base_mode.is_none() && kernels.iter().any(|k| reads_base(*k)),
            fields: parameter_fields(dynamics.model.graph.symbols()),
            model,
            dynamics,
            base_mode,
            kernels,
            setup,
            parameter_names,
            dims,
        })
    }
}

/// The model as `scene` sees it, once the scene and `options` are known to apply: the kernels
/// that solve with M need every joint to move some mass, runtime parameters need names that
/// are Rust fields, and base parameters are found at numeric geometry.
fn validate(
    model: &RobotModel,
    scene: &Scene,
    options: &GenerationOptions,
    source: &str,
) -> Result<RobotModel, CodegenError> {
    options.runtime_path()?;
    let model = scene.apply(model)?;
    let inverting: Vec<Kernel> = options
        .outputs
        .iter()
        .copied()
        .filter(|k| k.inverts_mass_matrix())
        .collect();
    if !inverting.is_empty() {
        model
            .check_mass_matrix_invertible()
            .map_err(|joint| CodegenError::Massless {
                robot: source.to_owned(),
                kernels: inverting,
                joint,
            })?;
    }
    if options.parameters == ParameterMode::Runtime {
        if let Some(bad) = model
            .parameters
            .iter()
            .find(|p| !is_valid_parameter_name(&p.name))
        {
            return Err(CodegenError::ParameterName(bad.name.clone()));
        }
    }
    if options.parameters == ParameterMode::Base && !model.graph.symbols().parameters().is_empty() {
        return Err(CodegenError::SymbolicBaseParameters {
            robot: source.to_owned(),
        });
    }
    Ok(model)
}

/// Whether `kernel` is built from the base parameters.
pub(crate) fn reads_base(kernel: Kernel) -> bool {
    matches!(kernel, Kernel::BaseRegressor | Kernel::BaseParameters)
}
