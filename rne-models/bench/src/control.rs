//! The control and identification kernels of the URDF robots, which `rne bench --pinocchio`
//! sets beside Pinocchio's algorithms and its CppADCodeGen code (issues 13, 14, 15): the
//! inverse- and forward-dynamics derivatives and M⁻¹ (on [`rne_codegen::Dynamics`]), the frame
//! Jacobians and J̇q̇ (on [`Kinematics`]) and the joint-torque regressor (on
//! [`Identification`]), each
//! from the robot's generated `control` module of [`rne_models::generated::variants`].
//!
//! Errors are measured as for the dynamics kernels ([`crate::kernels`]): against the
//! double-double value of the same optimised programs, built here by
//! [`Interpreted::with_kernels`] with the module's (default) scene.

use rne_codegen::{Identification, Kernel, Kinematics};
use rne_interpreted::Interpreted;
use rne_models::generated::variants;

use crate::calls::{Calls, Input, KernelCalls, Pool};
use crate::error::BenchError;
use crate::implementation::{Case, Implementation};
use crate::kernels::{errors_with, time, KernelRow, RobotKernels};
use crate::precision::exact;
use crate::robots::{Candidate, Cases};
use crate::timing::{Plan, Timed};

/// The control and identification kernels of the `control` modules, in docs/design.md §4 order.
pub const CONTROL: [Kernel; 6] = [
    Kernel::InverseDynamicsDerivatives,
    Kernel::ForwardDynamicsDerivatives,
    Kernel::MassMatrixInverse,
    Kernel::FrameJacobians,
    Kernel::FrameJacobianDotQd,
    Kernel::Regressor,
];

/// `kernel` (frame Jacobians, J̇q̇ or the regressor) of `model` on `inputs`, timed on the
/// first states (see [`Pool`]); the Dynamics kernels of `model` go through [`Calls`].
pub struct KinematicsCalls<M, const N: usize, const NF: usize, const NP: usize, const NB: usize> {
    model: M,
    kernel: Kernel,
    inputs: Pool<Input<f64, N>>,
}

impl<M, const N: usize, const NF: usize, const NP: usize, const NB: usize>
    KinematicsCalls<M, N, NF, NP, NB>
where
    M: Kinematics<N, N, NF, Scalar = f64> + Identification<N, N, NP, NB>,
{
    /// `kernel` of `model` on `inputs`, timed on the first `pool` of them (at least one).
    pub fn new(model: M, kernel: Kernel, inputs: Vec<Input<f64, N>>, pool: usize) -> Self {
        KinematicsCalls {
            model,
            kernel,
            inputs: Pool::new(inputs, pool),
        }
    }
}

impl<M, const N: usize, const NF: usize, const NP: usize, const NB: usize> Timed
    for KinematicsCalls<M, N, NF, NP, NB>
where
    M: Kinematics<N, N, NF, Scalar = f64> + Identification<N, N, NP, NB>,
{
    fn run(&mut self, calls: u64) {
        let m = &self.model;
        match self.kernel {
            Kernel::FrameJacobians => self.inputs.cycle(calls, |s| m.frame_jacobians(&s.q)),
            Kernel::FrameJacobianDotQd => self
                .inputs
                .cycle(calls, |s| m.frame_jacobian_dot_qd(&s.q, &s.qd)),
            _ => self
                .inputs
                .cycle(calls, |s| m.regressor(&s.q, &s.qd, &s.qdd)),
        }
    }
}

impl<M, const N: usize, const NF: usize, const NP: usize, const NB: usize> KernelCalls
    for KinematicsCalls<M, N, NF, NP, NB>
where
    M: Kinematics<N, N, NF, Scalar = f64> + Identification<N, N, NP, NB>,
{
    fn states(&self) -> usize {
        self.inputs.len()
    }

    fn evaluate(&mut self, k: usize, out: &mut Vec<f64>) {
        out.clear();
        let (s, m) = (self.inputs.get(k), &self.model);
        match self.kernel {
            Kernel::FrameJacobians => out.extend(
                m.frame_jacobians(&s.q)
                    .into_iter()
                    .flatten()
                    .flatten()
                    .flatten(),
            ),
            Kernel::FrameJacobianDotQd => out.extend(
                m.frame_jacobian_dot_qd(&s.q, &s.qd)
                    .into_iter()
                    .flatten()
                    .flatten(),
            ),
            Kernel::Regressor => out.extend(
                m.regressor(&s.q, &s.qd, &s.qdd)
                    .into_iter()
                    .flatten()
                    .flatten(),
            ),
            _ => {}
        }
    }
}

/// The [`CONTROL`] kernels of `model` as candidates, each on the robot's full sample, with
/// their kernels.
fn candidates<'a, M, const N: usize, const NF: usize, const NP: usize, const NB: usize>(
    cases: &'a Cases,
    pool: usize,
    model: M,
) -> Result<Vec<(Kernel, Candidate<'a>)>, BenchError>
where
    M: Kinematics<N, N, NF, Scalar = f64> + Identification<N, N, NP, NB> + Copy + 'a,
{
    let inputs = cases
        .sample(Case::Full)
        .inputs::<f64, N>()
        .map_err(|cause| BenchError::Evaluation {
            robot: cases.robot.name.to_owned(),
            cause,
        })?;
    Ok(CONTROL
        .iter()
        .filter(|&&kernel| model.has(kernel))
        .map(|&kernel| {
            let calls: Box<dyn KernelCalls + 'a> =
                if kernel.is_kinematics() || kernel.is_identification() {
                    Box::new(KinematicsCalls::<M, N, NF, NP, NB>::new(
                        model,
                        kernel,
                        inputs.clone(),
                        pool,
                    ))
                } else {
                    Box::new(Calls::new(model, kernel, inputs.clone(), pool))
                };
            let implementation = Implementation::Generated;
            (
                kernel,
                Candidate {
                    implementation,
                    calls,
                },
            )
        })
        .collect())
}

/// Whether the built-in robot `robot` has a `control` module.
pub fn has_control(robot: &str) -> bool {
    matches!(robot, "ur5" | "panda-arm" | "panda")
}

/// The programs of the [`CONTROL`] kernels of the robot of `cases`, whose double-double
/// values are the exact ones of the `control` module.
pub fn programs(cases: &Cases) -> Interpreted {
    Interpreted::with_kernels(&cases.model, &CONTROL)
}

/// The [`CONTROL`] kernels of the `control` module of the robot of `cases` (one with such a
/// module, [`has_control`]) as candidates on its full sample, timed on the first `pool`
/// states, with their kernels.
pub fn generated(cases: &Cases, pool: usize) -> Result<Vec<(Kernel, Candidate<'_>)>, BenchError> {
    use variants::{panda, panda_arm, ur5};
    Ok(match cases.robot.name {
        "ur5" => candidates::<
            _,
            { ur5::control::NV },
            { ur5::control::NF },
            { ur5::control::NP },
            { ur5::control::NB },
        >(cases, pool, ur5::control::Model)?,
        "panda-arm" => candidates::<
            _,
            { panda_arm::control::NV },
            { panda_arm::control::NF },
            { panda_arm::control::NP },
            { panda_arm::control::NB },
        >(cases, pool, panda_arm::control::Model)?,
        "panda" => candidates::<
            _,
            { panda::control::NV },
            { panda::control::NF },
            { panda::control::NP },
            { panda::control::NB },
        >(cases, pool, panda::control::Model)?,
        other => {
            return Err(BenchError::Variants {
                robot: other.to_owned(),
                problem: "no `control` module: add one in rne_models::generated::variants".into(),
            })
        }
    })
}

/// Measures the [`CONTROL`] kernels of the robot of `cases` (one with a `control` module,
/// [`has_control`]): errors over the whole sample against the double-double value of
/// `program` ([`programs`]), times on the first `pool` states, all kernels timed together
/// (`relative_time` is 1: each row is its own kernel's generated implementation).
pub fn measure(
    cases: &Cases,
    program: &Interpreted,
    plan: &Plan,
    pool: usize,
) -> Result<RobotKernels, BenchError> {
    let (kernels, mut list): (Vec<Kernel>, Vec<Candidate<'_>>) =
        generated(cases, pool)?.into_iter().unzip();
    let full = cases.sample(Case::Full);
    let mut summaries = Vec::new();
    for (&kernel, candidate) in kernels.iter().zip(list.iter_mut()) {
        let exact = |_: Case, k: usize| exact(program, kernel, full.state(k));
        summaries.extend(errors_with(exact, std::slice::from_mut(candidate)));
    }
    let timings = time(&mut list, plan);
    let rows = kernels
        .into_iter()
        .zip(timings)
        .zip(summaries)
        .map(|((kernel, timing), errors)| KernelRow {
            kernel,
            implementation: Implementation::Generated,
            timing,
            relative_time: 1.0,
            errors,
        })
        .collect();
    Ok(RobotKernels {
        robot: cases.robot.name,
        dof: cases.model.dof(),
        rows,
    })
}
