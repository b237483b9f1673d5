//! The functions a generated module can contain (DESIGN.md §4): the runtime's [`Kernel`],
//! with their names, inputs and shapes, and here their symbolic construction.

use rne_symbolic::{Id, SymbolicDynamics};

pub use rne_runtime::{Input, Kernel, Shape, UnknownKernel};

/// Builds `kernel`'s outputs (flattened row-major for matrices) into the dynamics' graph.
///
/// # Panics
/// For a kernel of the runtime that the generator cannot build yet; every kernel of
/// [`Kernel::ALL`] has a construction (a test checks it).
pub fn build_outputs(kernel: Kernel, dynamics: &mut SymbolicDynamics) -> Vec<Id> {
    match kernel {
        Kernel::InverseDynamics => dynamics.inverse_dynamics(),
        Kernel::MassMatrix => dynamics.mass_matrix().concat(),
        Kernel::CoriolisMatrix => dynamics.coriolis_matrix().concat(),
        Kernel::GravityTorques => dynamics.gravity_torques(),
        Kernel::BiasTorques => dynamics.bias_torques(),
        Kernel::ForwardDynamics => dynamics.forward_dynamics(),
        Kernel::KineticEnergy => vec![dynamics.kinetic_energy()],
        Kernel::PotentialEnergy => vec![dynamics.potential_energy()],
        other => unreachable!("the generator has no construction for `{other}`"),
    }
}
