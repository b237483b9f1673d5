//! One kernel of any [`Dynamics`] at a state whose size is known only at run time: how the
//! command line and the checks read a model's outputs as flat lists.

use rne_codegen::{Dynamics, Input, Kernel};

use crate::error::Error;
use crate::state::StateRef;

/// The array `input` of `state` as a fixed-size array, or the dimension error naming it.
fn array<'s, T, const L: usize>(state: StateRef<'s, T>, input: Input) -> Result<&'s [T; L], Error> {
    let values = match input {
        Input::Q => state.q,
        Input::Qd => state.qd,
        Input::Qdd => state.qdd,
        Input::Tau => state.tau,
        Input::Standard => &[],
    };
    values.try_into().map_err(|_| Error::Dimension {
        input,
        got: values.len(),
        expected: L,
    })
}

/// `kernel` of `model` at `state`, matrices flattened row-major (several matrices one after
/// the other, in the order the kernel returns them). The arrays the kernel takes
/// must have the model's lengths (NQ positions, NV of the others); the others are ignored.
pub fn evaluate<const NQ: usize, const NV: usize, D: Dynamics<NQ, NV>>(
    model: &D,
    kernel: Kernel,
    state: StateRef<'_, D::Scalar>,
) -> Result<Vec<D::Scalar>, Error> {
    let q = || array::<_, NQ>(state, Input::Q);
    let qd = || array::<_, NV>(state, Input::Qd);
    let qdd = || array::<_, NV>(state, Input::Qdd);
    let tau = || array::<_, NV>(state, Input::Tau);
    let values = match kernel {
        Kernel::InverseDynamics => model
            .inverse_dynamics(q()?, qd()?, qdd()?)
            .map(|v| v.to_vec()),
        Kernel::MassMatrix => model.mass_matrix(q()?).map(|m| m.as_flattened().to_vec()),
        Kernel::CoriolisMatrix => model
            .coriolis_matrix(q()?, qd()?)
            .map(|m| m.as_flattened().to_vec()),
        Kernel::GravityTorques => model.gravity_torques(q()?).map(|v| v.to_vec()),
        Kernel::BiasTorques => model.bias_torques(q()?, qd()?).map(|v| v.to_vec()),
        Kernel::ForwardDynamics => model
            .forward_dynamics(q()?, qd()?, tau()?)
            .map(|v| v.to_vec()),
        Kernel::KineticEnergy => model.kinetic_energy(q()?, qd()?).map(|t| vec![t]),
        Kernel::PotentialEnergy => model.potential_energy(q()?).map(|v| vec![v]),
        Kernel::InverseDynamicsDerivatives => model
            .inverse_dynamics_derivatives(q()?, qd()?, qdd()?)
            .map(|(dq, dqd)| [dq.as_flattened(), dqd.as_flattened()].concat()),
        Kernel::ForwardDynamicsDerivatives => model
            .forward_dynamics_derivatives(q()?, qd()?, tau()?)
            .map(|(dq, dqd, minv)| {
                [dq.as_flattened(), dqd.as_flattened(), minv.as_flattened()].concat()
            }),
        Kernel::MassMatrixInverse => model
            .mass_matrix_inverse(q()?)
            .map(|m| m.as_flattened().to_vec()),
        Kernel::FrictionTorques => model.friction_torques(qd()?).map(|v| v.to_vec()),
        // Kinematics and identification kernels belong to other traits.
        _ => None,
    };
    values.ok_or(Error::MissingKernel { kernel })
}
