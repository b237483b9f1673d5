//! The functions a generated module can contain (docs/design.md §4): the runtime's [`Kernel`],
//! with their names, inputs and shapes, and here their symbolic construction.

use rne_symbolic::dynamics::base_parameters::BaseParameters;
use rne_symbolic::{Id, Symbol, SymbolicDynamics};

pub use rne_runtime::{Input, Kernel, Shape, UnknownKernel};

/// What the kinematics and identification kernels need besides the dynamics: the frames they
/// are about and the base parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct KernelSetup {
    /// Indices into [`SymbolicDynamics::frames`] of the frames of the kinematics kernels, in
    /// output order (the `frames:` setting; every frame by default).
    pub frames: Vec<usize>,
    /// The base parameters, when an identification kernel is generated.
    pub base_parameters: Option<BaseParameters>,
    /// Whether `forward_dynamics` is built by the articulated-body algorithm (where the model
    /// allows it) rather than the LᵀDL factorisation of M.
    pub articulated: bool,
    /// Whether the derivative kernels are built in lanes (the `derivatives: lanes` setting,
    /// [`crate::GenerationOptions::derivative_lanes`]).
    pub derivative_lanes: bool,
}

impl KernelSetup {
    /// Every frame, and the base parameters when `kernels` has a kernel built from them
    /// (`base_regressor`, `base_parameters`; a module with any identification kernel has
    /// `base_parameters`, [`crate::GenerationOptions::kernels`]).
    pub fn new(dynamics: &SymbolicDynamics, kernels: &[Kernel]) -> KernelSetup {
        KernelSetup {
            frames: (0..dynamics.frames().len()).collect(),
            base_parameters: kernels
                .iter()
                .any(|k| matches!(k, Kernel::BaseRegressor | Kernel::BaseParameters))
                .then(|| dynamics.base_parameters()),
            articulated: false,
            derivative_lanes: false,
        }
    }
}

/// The sizes of a module's arrays: NV velocities, NF frames, NP standard and NB base
/// parameters.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct Dims {
    /// Velocity variables.
    pub nv: usize,
    /// Frames of the kinematics kernels.
    pub nf: usize,
    /// Standard parameters.
    pub np: usize,
    /// Base parameters.
    pub nb: usize,
}

/// Builds `kernel`'s outputs (flattened row-major for matrices, tuples in order) into the
/// dynamics' graph.
///
/// `base_parameters` reads the standard parameters as `Symbol::Parameter(i)` = π_i: its
/// coefficients are numbers, so it never reads a model parameter, and the emitter gives it
/// `standard[i]` for them.
///
/// # Panics
/// For an identification kernel when `setup` has no base parameters ([`KernelSetup::new`]
/// finds them whenever they are needed).
pub(crate) fn build_outputs(
    kernel: Kernel,
    dynamics: &mut SymbolicDynamics,
    setup: &KernelSetup,
) -> Vec<Id> {
    let frames = &setup.frames;
    match kernel {
        Kernel::InverseDynamics => dynamics.inverse_dynamics(),
        Kernel::MassMatrix => dynamics.mass_matrix().concat(),
        Kernel::CoriolisMatrix => dynamics.coriolis_matrix().concat(),
        Kernel::GravityTorques => dynamics.gravity_torques(),
        Kernel::BiasTorques => dynamics.bias_torques(),
        Kernel::ForwardDynamics if setup.articulated && articulated_applies(dynamics) => dynamics
            .forward_dynamics_articulated()
            .unwrap_or_else(|| dynamics.forward_dynamics()),
        Kernel::ForwardDynamics => dynamics.forward_dynamics(),
        Kernel::KineticEnergy => vec![dynamics.kinetic_energy()],
        Kernel::PotentialEnergy => vec![dynamics.potential_energy()],
        Kernel::InverseDynamicsDerivatives => {
            let (dq, dv) = dynamics.inverse_dynamics_derivatives();
            [dq.concat(), dv.concat()].concat()
        }
        Kernel::ForwardDynamicsDerivatives => {
            let (dq, dv, inverse) = dynamics.forward_dynamics_derivatives();
            [dq.concat(), dv.concat(), inverse.concat()].concat()
        }
        Kernel::MassMatrixInverse => dynamics.mass_matrix_inverse().concat(),
        Kernel::FramePlacements => dynamics
            .frame_placements(frames)
            .into_iter()
            .flat_map(|(rotation, position)| rotation.concat().into_iter().chain(position))
            .collect(),
        Kernel::FrameJacobians => dynamics
            .frame_jacobians(frames)
            .into_iter()
            .flat_map(|j| j.concat())
            .collect(),
        Kernel::FrameJacobianDotQd => dynamics
            .frame_jacobian_dot_qd(frames)
            .into_iter()
            .flatten()
            .collect(),
        Kernel::FrictionTorques => dynamics.friction_torques(),
        Kernel::Regressor => dynamics.regressor().concat(),
        Kernel::BaseRegressor => {
            let base = base_parameters(setup, kernel);
            dynamics
                .regressor()
                .iter()
                .flat_map(|row| base.independent.iter().map(|&c| row[c]))
                .collect()
        }
        Kernel::BaseParameters => {
            let base = base_parameters(setup, kernel);
            let g = &mut dynamics.model.graph;
            let standard = |g: &mut rne_symbolic::ExprGraph, i: usize| {
                g.symbol(Symbol::Parameter(
                    u16::try_from(i).expect("at most 65 536 standard parameters"),
                ))
            };
            base.independent
                .iter()
                .zip(&base.k)
                .map(|(&i, row)| {
                    let mut terms = vec![standard(g, i)];
                    for (&k, &d) in row.iter().zip(&base.dependent) {
                        if k != 0.0 {
                            let coefficient = g.constant(k);
                            let pi = standard(g, d);
                            terms.push(g.mul(coefficient, pi));
                        }
                    }
                    g.sum(terms)
                })
                .collect()
        }
        other => unreachable!("the generator has no construction for `{other}`"),
    }
}

/// Whether the articulated-body algorithm builds this model's forward dynamics: a fixed base,
/// no mimic couplings and no armature (the recursion does not add reflected rotor inertia).
pub(crate) fn articulated_applies(dynamics: &SymbolicDynamics) -> bool {
    let model = &dynamics.model;
    !model.is_floating()
        && !model.has_couplings()
        && model.links.iter().all(|l| l.armature.is_none())
}

fn base_parameters(setup: &KernelSetup, kernel: Kernel) -> &BaseParameters {
    setup
        .base_parameters
        .as_ref()
        .unwrap_or_else(|| panic!("`{kernel}` needs the base parameters in its KernelSetup"))
}
