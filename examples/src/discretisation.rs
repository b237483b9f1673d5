//! The discrete-time dynamics x_{k+1} = f(x_k, u_k) that iLQR optimises over, and its
//! Jacobians: a classical fourth-order Runge–Kutta step of a robot's generated forward
//! dynamics, differentiated exactly by the chain rule through the four stages with the
//! generated ∂q̈/∂q, ∂q̈/∂q̇ and M⁻¹.

use std::time::{Duration, Instant};

use nalgebra::{SMatrix, SVector};
use rne_codegen::{Dynamics, Kernel};

use crate::error::Error;

/// A discrete-time system x_{k+1} = f(x_k, u_k) with NX states and NU controls.
pub trait Discretisation<const NX: usize, const NU: usize> {
    /// One step: x_{k+1} = f(x_k, u_k).
    fn step(&self, x: &SVector<f64, NX>, u: &SVector<f64, NU>) -> SVector<f64, NX>;

    /// The Jacobians ∂f/∂x and ∂f/∂u at every (x_k, u_k) of a trajectory.
    fn linearise(
        &self,
        states: &[SVector<f64, NX>],
        controls: &[SVector<f64, NU>],
    ) -> Linearisation<NX, NU>;
}

/// The Jacobians of f along a trajectory, and what computing them cost.
#[derive(Clone, Debug)]
pub struct Linearisation<const NX: usize, const NU: usize> {
    /// ∂f/∂x at each step (A_k).
    pub fx: Vec<SMatrix<f64, NX, NX>>,
    /// ∂f/∂u at each step (B_k).
    pub fu: Vec<SMatrix<f64, NX, NU>>,
    /// Wall time spent inside the model's derivative kernels, included in the linearisation's
    /// own time (zero for a model without such kernels).
    pub derivative_kernels: Duration,
    /// How many derivative-kernel calls that time covers.
    pub derivative_kernel_calls: usize,
}

/// The classical Runge–Kutta step of ẋ = (q̇, FD(q, q̇, u)) with the control held over the
/// step, for a fixed-base robot of N joints whose state is x = (q, q̇), NX = 2N:
///
/// k₁ = ẋ(x), k₂ = ẋ(x + h/2 k₁), k₃ = ẋ(x + h/2 k₂), k₄ = ẋ(x + h k₃),
/// x_{k+1} = x + h/6 (k₁ + 2k₂ + 2k₃ + k₄).
///
/// The forward dynamics is the thesis's (6.2), q̈ = M⁻¹ (u − C q̇ − g), from the robot's
/// generated `forward_dynamics`; its Jacobian, the generated
/// `forward_dynamics_derivatives`, gives each stage's
/// `A_s = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]]` and `B_s = [[0], [M⁻¹]]`, and the chain rule through the
/// stages is exact for this scheme (see [`Rk4::linearise`]).
#[derive(Clone, Debug)]
pub struct Rk4<R, const N: usize> {
    robot: R,
    step: f64,
}

/// The generated kernels the step and its Jacobians need.
const NEEDED: [Kernel; 2] = [Kernel::ForwardDynamics, Kernel::ForwardDynamicsDerivatives];

impl<R: Dynamics<N, N, Scalar = f64>, const N: usize> Rk4<R, N> {
    /// The step of length `step` (seconds) for `robot`, whose generated module must have
    /// `forward_dynamics` and `forward_dynamics_derivatives`.
    pub fn new(robot: R, step: f64) -> Result<Self, Error> {
        if let Some(&kernel) = NEEDED.iter().find(|&&k| !robot.has(k)) {
            return Err(Error::MissingKernel {
                robot: R::NAME,
                kernel,
            });
        }
        if !(step.is_finite() && step > 0.0) {
            return Err(Error::InvalidTimeStep { step });
        }
        Ok(Rk4 { robot, step })
    }

    /// The step length h in seconds.
    pub fn time_step(&self) -> f64 {
        self.step
    }

    /// ẋ = (q̇, q̈) at `x` under the control `u`.
    fn rate<const NX: usize>(&self, x: &SVector<f64, NX>, u: &[f64; N]) -> SVector<f64, NX> {
        let (q, qd) = split::<N, NX>(x);
        let qdd = self
            .robot
            .forward_dynamics(&q, &qd, u)
            .expect("Rk4::new checked that forward_dynamics is generated");
        join(&qd, &qdd)
    }

    /// The four stage states x, x + h/2 k₁, x + h/2 k₂, x + h k₃ and the next state.
    fn stages<const NX: usize>(
        &self,
        x: &SVector<f64, NX>,
        u: &[f64; N],
    ) -> ([SVector<f64, NX>; 4], SVector<f64, NX>) {
        let h = self.step;
        let k1 = self.rate(x, u);
        let x2 = x + k1 * (h / 2.0);
        let k2 = self.rate(&x2, u);
        let x3 = x + k2 * (h / 2.0);
        let k3 = self.rate(&x3, u);
        let x4 = x + k3 * h;
        let k4 = self.rate(&x4, u);
        let next = x + (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0);
        ([*x, x2, x3, x4], next)
    }

    /// A_s = ∂ẋ/∂x and B_s = ∂ẋ/∂u at the stage state `x`, from the generated derivative
    /// kernel's (∂q̈/∂q, ∂q̈/∂q̇, M⁻¹).
    fn stage_jacobians<const NX: usize>(
        (dq, dqd, minv): &Derivatives<N>,
    ) -> (SMatrix<f64, NX, NX>, SMatrix<f64, NX, N>) {
        let mut a = SMatrix::<f64, NX, NX>::zeros();
        let mut b = SMatrix::<f64, NX, N>::zeros();
        for i in 0..N {
            a[(i, N + i)] = 1.0;
            for j in 0..N {
                a[(N + i, j)] = dq[i][j];
                a[(N + i, N + j)] = dqd[i][j];
                b[(N + i, j)] = minv[i][j];
            }
        }
        (a, b)
    }
}

/// (∂q̈/∂q, ∂q̈/∂q̇, M⁻¹), row-major, as the generated kernel returns them.
type Derivatives<const N: usize> = ([[f64; N]; N], [[f64; N]; N], [[f64; N]; N]);

impl<R: Dynamics<N, N, Scalar = f64>, const N: usize, const NX: usize> Discretisation<NX, N>
    for Rk4<R, N>
{
    fn step(&self, x: &SVector<f64, NX>, u: &SVector<f64, N>) -> SVector<f64, NX> {
        self.stages(x, &(*u).into()).1
    }

    /// The exact Jacobian of the Runge–Kutta step. With X_s the stage states and
    /// k_s = ẋ(X_s, u):
    ///
    /// ∂k₁/∂x = A₁, ∂k_s/∂x = A_s (I + c_s ∂k_{s−1}/∂x),
    /// ∂k₁/∂u = B₁, ∂k_s/∂u = A_s c_s ∂k_{s−1}/∂u + B_s, with c = (h/2, h/2, h),
    /// ∂f/∂x = I + h/6 Σ w_s ∂k_s/∂x, ∂f/∂u = h/6 Σ w_s ∂k_s/∂u, w = (1, 2, 2, 1).
    ///
    /// The stage states come first (generated `forward_dynamics`), then the derivative kernel
    /// at all 4 N_steps stage states in one timed loop, then the chain rule, so that the time
    /// in the generated derivatives is measured without a clock read per call.
    fn linearise(
        &self,
        states: &[SVector<f64, NX>],
        controls: &[SVector<f64, N>],
    ) -> Linearisation<NX, N> {
        let controls: Vec<[f64; N]> = controls.iter().map(|&u| u.into()).collect();
        let stages: Vec<[SVector<f64, NX>; 4]> = states
            .iter()
            .zip(&controls)
            .map(|(x, u)| self.stages(x, u).0)
            .collect();
        let start = Instant::now();
        let derivatives: Vec<[Derivatives<N>; 4]> = stages
            .iter()
            .zip(&controls)
            .map(|(stage, u)| {
                stage.map(|x| {
                    let (q, qd) = split::<N, NX>(&x);
                    self.robot
                        .forward_dynamics_derivatives(&q, &qd, u)
                        .expect("Rk4::new checked that forward_dynamics_derivatives is generated")
                })
            })
            .collect();
        let derivative_kernels = start.elapsed();
        let h = self.step;
        let identity = SMatrix::<f64, NX, NX>::identity();
        let (fx, fu) = derivatives
            .iter()
            .map(|stage| {
                let (a1, b1) = Self::stage_jacobians::<NX>(&stage[0]);
                let (mut dk_dx, mut dk_du) = (a1, b1);
                let (mut sum_x, mut sum_u) = (a1, b1);
                for (derivative, c, w) in [(&stage[1], h / 2.0, 2.0), (&stage[2], h / 2.0, 2.0)]
                    .into_iter()
                    .chain([(&stage[3], h, 1.0)])
                {
                    let (a, b) = Self::stage_jacobians::<NX>(derivative);
                    dk_du = a * (dk_du * c) + b;
                    dk_dx = a * (identity + dk_dx * c);
                    sum_x += dk_dx * w;
                    sum_u += dk_du * w;
                }
                (identity + sum_x * (h / 6.0), sum_u * (h / 6.0))
            })
            .unzip();
        Linearisation {
            fx,
            fu,
            derivative_kernels,
            derivative_kernel_calls: 4 * states.len().min(controls.len()),
        }
    }
}

/// (q, q̇) of the state x = (q, q̇).
fn split<const N: usize, const NX: usize>(x: &SVector<f64, NX>) -> ([f64; N], [f64; N]) {
    const {
        assert!(
            NX == 2 * N,
            "the state of an N-joint robot is (q, q̇): NX = 2N"
        )
    };
    (
        core::array::from_fn(|i| x[i]),
        core::array::from_fn(|i| x[N + i]),
    )
}

/// The state (or rate) (a, b) of two N-vectors.
fn join<const N: usize, const NX: usize>(a: &[f64; N], b: &[f64; N]) -> SVector<f64, NX> {
    const {
        assert!(
            NX == 2 * N,
            "the state of an N-joint robot is (q, q̇): NX = 2N"
        )
    };
    SVector::from_fn(|i, _| if i < N { a[i] } else { b[i - N] })
}
