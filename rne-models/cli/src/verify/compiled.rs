//! A built-in robot's compiled module (`derive_dynamics!` at build time, the dynamics kernels)
//! as an engine of the agreement check, run through [`rne_models::BuiltinRobot::visit`].

use std::marker::PhantomData;

use rne_codegen::{Dynamics, Kernel};
use rne_interpreted::agreement::{check_kernels, Engine, KernelAgreement};
use rne_interpreted::{Error, JointState, StateRef};
use rne_models::Visitor;
use rne_symbolic::RobotModel;

/// The errors of every kernel a built-in robot's compiled module has, against the reference
/// built from `model` (the robot as its generator saw it), at `states`.
pub struct CompiledErrors<'a> {
    /// The robot as the generator saw it.
    pub model: &'a RobotModel,
    /// The seeded states.
    pub states: &'a [JointState],
}

impl Visitor for CompiledErrors<'_> {
    type Output = Result<Vec<KernelAgreement>, Error>;

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) -> Self::Output {
        let engine = Compiled::<D, N> {
            model,
            joints: PhantomData,
        };
        check_kernels(self.model, false, &engine, &Kernel::ALL, self.states)
    }
}

/// A compiled module as an [`Engine`]: the kernels it was generated with.
struct Compiled<D, const N: usize> {
    model: D,
    joints: PhantomData<[f64; N]>,
}

impl<const N: usize, D: Dynamics<N, N, Scalar = f64>> Engine for Compiled<D, N> {
    fn has(&self, kernel: Kernel) -> bool {
        D::KERNELS.contains(&kernel)
    }

    fn evaluate(&self, kernel: Kernel, state: StateRef<'_>) -> Result<Vec<f64>, Error> {
        rne_interpreted::evaluate(&self.model, kernel, state)
    }

    /// The built-in modules have no identification kernels: nothing to map.
    fn base_parameters(&self, _standard: &[f64]) -> Result<Vec<f64>, Error> {
        Ok(Vec::new())
    }

    /// The built-in modules have no kinematics kernels: no frames.
    fn frames(&self) -> Vec<String> {
        Vec::new()
    }
}
