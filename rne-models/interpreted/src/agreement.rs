//! Every kernel of a robot against the independent numeric reference: the check `rne verify`,
//! `rne corpus` and the backends' tests share.
//!
//! An [`Engine`] evaluates a robot's kernels (the interpreted programs, a JIT-compiled model,
//! the compiled modules); [`check_kernels`] evaluates each kernel it has at seeded random
//! states and compares it with what the reference (spatial RNEA, CRBA, ABA and their
//! dual-number derivatives, which share no code with the symbolic recursion) gives for the
//! same quantity.
//!
//! Errors are normwise over all the states: the largest |engine − reference| of a kernel's
//! entries, over the largest |reference| entry of that kernel at any state — so an entry that
//! vanishes at one state is measured against the kernel's size elsewhere. Three kernels are
//! compared through a product, as their values are defined by it:
//! - outputs of the form M⁻¹ x (forward dynamics, its derivatives, M⁻¹) are compared in force
//!   space, M (x_engine − x_reference) against M x_reference (against the identity for M⁻¹),
//!   so that the measure does not grow with the conditioning of M;
//! - the Coriolis matrix as C(q, q̇) q̇ against the reference's bias without gravity;
//! - the base regressor and base parameters as Y_b(q, q̇, q̈) π_b(π) against the reference's
//!   torques, π the reference's standard parameters.

use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_codegen::Kernel;
use rne_reference::Reference;
use rne_symbolic::RobotModel;

use crate::{Error, JointState, StateRef};

/// What evaluates a robot's kernels at run time.
pub trait Engine {
    /// Whether the engine has `kernel`.
    fn has(&self, kernel: Kernel) -> bool;
    /// `kernel` at `state`, matrices row-major, tuples concatenated.
    fn evaluate(&self, kernel: Kernel, state: StateRef<'_>) -> Result<Vec<f64>, Error>;
    /// `base_parameters` of the standard parameters `standard`.
    fn base_parameters(&self, standard: &[f64]) -> Result<Vec<f64>, Error>;
    /// The frames of the kinematics kernels (link names), in output order.
    fn frames(&self) -> Vec<String>;
}

/// The largest error of one kernel over the states.
#[derive(Clone, Debug, PartialEq)]
pub struct KernelAgreement {
    /// The kernel.
    pub kernel: Kernel,
    /// Largest normwise relative error (module docs); NaN counts as infinite.
    pub max_error: f64,
}

/// `count` seeded random states of a model with `nq` and `nv` entries: a free-flyer's position
/// in [−1, 1]³ and a uniformly random unit quaternion when `nq > nv`, joint positions in
/// [−π, π], velocities and accelerations in [−2, 2], torques in [−10, 10].
pub fn random_states(nq: usize, nv: usize, count: usize, seed: u64) -> Vec<JointState> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut uniform = |n: usize, bound: f64| -> Vec<f64> {
        (0..n).map(|_| rng.gen_range(-bound..=bound)).collect()
    };
    (0..count)
        .map(|_| {
            let mut q = Vec::with_capacity(nq);
            if nq > nv {
                q.extend(uniform(3, 1.0));
                // Uniform on the sphere: a point of the cube, kept when inside the ball.
                let quaternion = loop {
                    let x = uniform(4, 1.0);
                    let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
                    if norm > 0.1 && norm <= 1.0 {
                        break x.iter().map(|v| v / norm).collect::<Vec<_>>();
                    }
                };
                q.extend(quaternion);
            }
            q.extend(uniform(nq - q.len(), std::f64::consts::PI));
            JointState {
                q,
                qd: uniform(nv, 2.0),
                qdd: uniform(nv, 2.0),
                tau: uniform(nv, 10.0),
            }
        })
        .collect()
}

/// The error of each kernel of `kernels` that `engine` has, at `states`, against the reference
/// built from `model` — the model as the engine's generator saw it (its scene applied), with
/// joint friction in the dynamics when `friction` is set (the scene's `friction: include`). A
/// kernel the reference cannot evaluate is an error; the states of a scene at rest must have
/// zero velocities.
pub fn check_kernels(
    model: &RobotModel,
    friction: bool,
    engine: &dyn Engine,
    kernels: &[Kernel],
    states: &[JointState],
) -> Result<Vec<KernelAgreement>, Error> {
    let mut expected = Expected::new(model, friction, engine)?;
    kernels
        .iter()
        .copied()
        .filter(|&k| engine.has(k))
        .map(|kernel| {
            let mut pairs = Vec::with_capacity(states.len());
            for state in states {
                pairs.push(expected.pair(engine, kernel, state.as_ref())?);
            }
            Ok(KernelAgreement {
                kernel,
                max_error: normwise_error(&pairs),
            })
        })
        .collect()
}

/// max |a − b| over max |b|, over all the pairs (a, b) of equal length; the absolute error when
/// every b is zero, infinite when any entry is NaN.
fn normwise_error(pairs: &[(Vec<f64>, Vec<f64>)]) -> f64 {
    let (mut difference, mut scale) = (0.0f64, 0.0f64);
    for (a, b) in pairs {
        if a.len() != b.len() {
            return f64::INFINITY;
        }
        for (x, y) in a.iter().zip(b) {
            let d = (x - y).abs();
            if d.is_nan() {
                return f64::INFINITY;
            }
            difference = difference.max(d);
            scale = scale.max(y.abs());
        }
    }
    if scale > 0.0 {
        difference / scale
    } else {
        difference
    }
}

/// The reference's side of every comparison.
struct Expected {
    reference: Reference,
    /// The same model without gravity: C(q, q̇) q̇ is its bias.
    weightless: Reference,
    /// The reference's standard parameters π, in the engine's column order.
    standard: Vec<f64>,
    /// The reference's index of each of the engine's frames.
    frames: Vec<usize>,
}

impl Expected {
    fn new(model: &RobotModel, friction: bool, engine: &dyn Engine) -> Result<Expected, Error> {
        let numeric = model.to_numeric();
        let mut weightless = numeric.clone();
        weightless.gravity = [0.0; 3];
        let reference = Reference::try_new(&numeric)?.with_friction(friction);
        let frames = engine
            .frames()
            .iter()
            .map(|name| {
                reference
                    .link_names()
                    .iter()
                    .position(|l| l == name)
                    .ok_or_else(|| Error::Frame(name.clone()))
            })
            .collect::<Result<_, _>>()?;
        Ok(Expected {
            standard: reference.standard_parameters(),
            weightless: Reference::try_new(&weightless)?,
            reference,
            frames,
        })
    }

    /// (the engine's value, the reference's value) of `kernel` at `state`, each as the module
    /// docs say it is compared.
    fn pair(
        &mut self,
        engine: &dyn Engine,
        kernel: Kernel,
        state: StateRef<'_>,
    ) -> Result<(Vec<f64>, Vec<f64>), Error> {
        let StateRef { q, qd, qdd, .. } = state;
        let reference = &mut self.reference;
        let value = |kernel| engine.evaluate(kernel, state);
        let nv = reference.nv();
        let vector = |v: DVector<f64>| v.as_slice().to_vec();
        Ok(match kernel {
            Kernel::InverseDynamics => (
                value(kernel)?,
                vector(reference.inverse_dynamics(q, qd, qdd)?),
            ),
            Kernel::MassMatrix => (value(kernel)?, rows(&reference.mass_matrix(q)?)),
            Kernel::CoriolisMatrix => {
                let c = DMatrix::from_row_slice(nv, nv, &value(kernel)?);
                let c_qd = c * DVector::from_column_slice(qd);
                let bias = self.weightless.bias_torques(q, qd)?;
                (vector(c_qd), vector(bias))
            }
            Kernel::GravityTorques => (value(kernel)?, vector(reference.gravity_torques(q)?)),
            Kernel::BiasTorques => (value(kernel)?, vector(reference.bias_torques(q, qd)?)),
            Kernel::KineticEnergy => (value(kernel)?, vec![reference.kinetic_energy(q, qd)?]),
            Kernel::PotentialEnergy => (value(kernel)?, vec![reference.potential_energy(q)?]),
            Kernel::InverseDynamicsDerivatives => {
                let (dq, dv) = reference.inverse_dynamics_derivatives(q, qd, qdd)?;
                (value(kernel)?, [rows(&dq), rows(&dv)].concat())
            }
            Kernel::ForwardDynamics
            | Kernel::ForwardDynamicsDerivatives
            | Kernel::MassMatrixInverse => self.force_space_pair(engine, kernel, state)?,
            Kernel::FramePlacements | Kernel::FrameJacobians | Kernel::FrameJacobianDotQd => {
                self.frames_pair(engine, kernel, state)?
            }
            Kernel::FrictionTorques => (value(kernel)?, vector(reference.friction_torques(qd)?)),
            Kernel::Regressor => (value(kernel)?, rows(&reference.regressor(q, qd, qdd)?)),
            Kernel::BaseRegressor | Kernel::BaseParameters => {
                let base = engine.base_parameters(&self.standard)?;
                let y = DMatrix::from_row_slice(nv, base.len(), &value(Kernel::BaseRegressor)?);
                let product = y * DVector::from_vec(base);
                (
                    vector(product),
                    vector(reference.inverse_dynamics(q, qd, qdd)?),
                )
            }
            other => return Err(Error::MissingKernel { kernel: other }),
        })
    }

    /// [`Expected::pair`] of a kernel whose output is M⁻¹ x: forward dynamics, its
    /// derivatives and M⁻¹, compared in force space.
    fn force_space_pair(
        &mut self,
        engine: &dyn Engine,
        kernel: Kernel,
        state: StateRef<'_>,
    ) -> Result<(Vec<f64>, Vec<f64>), Error> {
        let StateRef { q, qd, tau, .. } = state;
        let reference = &mut self.reference;
        let value = |kernel| engine.evaluate(kernel, state);
        Ok(match kernel {
            Kernel::ForwardDynamics => {
                let m = reference.mass_matrix(q)?;
                let expected = reference.forward_dynamics(q, qd, tau)?;
                in_force_space(&m, &value(kernel)?, expected.as_slice(), 1)
            }
            Kernel::ForwardDynamicsDerivatives => {
                let m = reference.mass_matrix(q)?;
                let d = reference.forward_dynamics_derivatives(q, qd, tau)?;
                let expected = [
                    rows(&d.dqdd_dq),
                    rows(&d.dqdd_dqd),
                    rows(&d.mass_matrix_inverse),
                ]
                .concat();
                in_force_space(&m, &value(kernel)?, &expected, 3)
            }
            Kernel::MassMatrixInverse => {
                let m = reference.mass_matrix(q)?;
                let inverse = reference.forward_dynamics_derivatives(q, qd, tau)?;
                in_force_space(&m, &value(kernel)?, &rows(&inverse.mass_matrix_inverse), 1)
            }
            other => return Err(Error::MissingKernel { kernel: other }),
        })
    }

    /// [`Expected::pair`] of a kinematics kernel: the engine's frames' placements (rotation
    /// row-major, then origin), Jacobians or J̇ q̇, one frame after the other.
    fn frames_pair(
        &mut self,
        engine: &dyn Engine,
        kernel: Kernel,
        state: StateRef<'_>,
    ) -> Result<(Vec<f64>, Vec<f64>), Error> {
        let StateRef { q, qd, .. } = state;
        let reference = &mut self.reference;
        let value = |kernel| engine.evaluate(kernel, state);
        Ok(match kernel {
            Kernel::FramePlacements => {
                let placements = reference.frame_placements(q)?;
                let expected = self.frames.iter().flat_map(|&f| {
                    let (rotation, origin) = &placements[f];
                    let r: Vec<f64> = (0..3)
                        .flat_map(|i| (0..3).map(move |j| rotation[(i, j)]))
                        .collect();
                    r.into_iter().chain(origin.iter().copied())
                });
                (value(kernel)?, expected.collect())
            }
            Kernel::FrameJacobians => {
                let jacobians = reference.frame_jacobians(q)?;
                let expected = self.frames.iter().flat_map(|&f| rows(&jacobians[f]));
                (value(kernel)?, expected.collect())
            }
            Kernel::FrameJacobianDotQd => {
                let jdot = reference.frame_jacobian_dot_qd(q, qd)?;
                let expected = self.frames.iter().flat_map(|&f| jdot[f].iter().copied());
                (value(kernel)?, expected.collect())
            }
            other => return Err(Error::MissingKernel { kernel: other }),
        })
    }
}

/// `(M x, M x_expected)` for `x` and `expected` each `blocks` row-major matrices of NV rows
/// stacked one under the other (q̈ is one block of one column, ∂FD three of NV columns): M
/// applied to each block.
fn in_force_space(
    m: &DMatrix<f64>,
    x: &[f64],
    expected: &[f64],
    blocks: usize,
) -> (Vec<f64>, Vec<f64>) {
    let nv = m.nrows();
    let columns = x.len() / (blocks * nv).max(1);
    if x.len() != expected.len() || x.len() != blocks * nv * columns || columns == 0 {
        return (x.to_vec(), expected.to_vec());
    }
    let apply = |values: &[f64]| -> Vec<f64> {
        values
            .chunks(nv * columns)
            .flat_map(|b| rows(&(m * DMatrix::from_row_slice(nv, columns, b))))
            .collect()
    };
    (apply(x), apply(expected))
}

/// A matrix's entries row by row.
fn rows(m: &DMatrix<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

impl Engine for rne_jit::JitModel {
    fn has(&self, kernel: Kernel) -> bool {
        rne_jit::JitModel::has(self, kernel)
    }

    fn evaluate(&self, kernel: Kernel, state: StateRef<'_>) -> Result<Vec<f64>, Error> {
        let StateRef { q, qd, qdd, tau } = state;
        self.evaluate_vec(kernel, rne_jit::State { q, qd, qdd, tau })
            .map_err(Error::from)
    }

    fn base_parameters(&self, standard: &[f64]) -> Result<Vec<f64>, Error> {
        rne_jit::JitModel::base_parameters(self, standard).map_err(Error::from)
    }

    fn frames(&self) -> Vec<String> {
        rne_jit::JitModel::frames(self).to_vec()
    }
}
