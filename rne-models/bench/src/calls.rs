//! One kernel of a model called on its own inputs: in timed batches, and state by state for its
//! error. Every implementation the benchmark compares is a [`Dynamics`] — the generated
//! modules' `Model`s, and the interpreted programs and the numeric reference as
//! [`RuntimeModel`](rne_interpreted::RuntimeModel)s — called through the trait's methods, which
//! the generated `Model`s inline into the free functions user code calls.

use std::hint::black_box;

use rne_codegen::{Dynamics, Kernel, OrderedReal};

use crate::timing::Timed;

/// One state as a generated function takes it: fixed-size arrays of its scalar `T`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Input<T, const N: usize> {
    /// Joint positions.
    pub q: [T; N],
    /// Joint velocities.
    pub qd: [T; N],
    /// Joint accelerations (inverse dynamics).
    pub qdd: [T; N],
    /// Joint torques (forward dynamics).
    pub tau: [T; N],
}

/// Calls of one kernel that can be timed and whose results can be read as `f64`.
pub trait KernelCalls: Timed {
    /// Number of input states.
    fn states(&self) -> usize;
    /// Replaces `out` with the result on input state `k` (`k < states()`), matrices row by
    /// row, as `f64` (`f32` results convert exactly); empty if the model lacks the kernel.
    fn evaluate(&mut self, k: usize, out: &mut Vec<f64>);
}

/// Input states of one kind, the first `pool` of which are cycled through in order while
/// timing.
#[derive(Clone, Debug)]
pub struct Pool<I> {
    inputs: Vec<I>,
    pool: usize,
    next: usize,
}

impl<I> Pool<I> {
    /// `inputs`, timed on the first `pool` of them (at least one).
    pub fn new(inputs: Vec<I>, pool: usize) -> Self {
        let pool = pool.clamp(1, inputs.len().max(1));
        Pool {
            inputs,
            pool,
            next: 0,
        }
    }

    /// Number of input states.
    pub fn len(&self) -> usize {
        self.inputs.len()
    }

    /// Whether there is no input state.
    pub fn is_empty(&self) -> bool {
        self.inputs.is_empty()
    }

    /// Input state `k`.
    pub fn get(&self, k: usize) -> &I {
        &self.inputs[k]
    }

    /// Makes `calls` calls of `f` on the timing pool, each input and result passed through
    /// [`black_box`].
    pub fn cycle<R>(&mut self, calls: u64, mut f: impl FnMut(&I) -> R) {
        if self.inputs.is_empty() {
            return;
        }
        for _ in 0..calls {
            let input = black_box(&self.inputs[self.next]);
            self.next = if self.next + 1 == self.pool {
                0
            } else {
                self.next + 1
            };
            black_box(f(input));
        }
    }
}

/// `kernel` of `model` on `inputs`, timed on the first `pool` of them (cycled through in
/// order), each input and result passed through [`black_box`].
pub struct Calls<D: Dynamics<N, N>, const N: usize> {
    model: D,
    kernel: Kernel,
    inputs: Pool<Input<D::Scalar, N>>,
}

impl<D: Dynamics<N, N>, const N: usize> Calls<D, N> {
    /// `kernel` of `model` on `inputs`, timed on the first `pool` of them (at least one).
    pub fn new(model: D, kernel: Kernel, inputs: Vec<Input<D::Scalar, N>>, pool: usize) -> Self {
        Calls {
            model,
            kernel,
            inputs: Pool::new(inputs, pool),
        }
    }

    /// Makes `calls` calls of `f` on the timing pool.
    fn cycle<R>(&mut self, calls: u64, f: impl Fn(&D, &Input<D::Scalar, N>) -> R) {
        let model = &self.model;
        self.inputs.cycle(calls, |input| f(model, input));
    }
}

impl<D: Dynamics<N, N>, const N: usize> Timed for Calls<D, N> {
    fn run(&mut self, calls: u64) {
        match self.kernel {
            Kernel::InverseDynamics => {
                self.cycle(calls, |m, s| m.inverse_dynamics(&s.q, &s.qd, &s.qdd))
            }
            Kernel::MassMatrix => self.cycle(calls, |m, s| m.mass_matrix(&s.q)),
            Kernel::CoriolisMatrix => self.cycle(calls, |m, s| m.coriolis_matrix(&s.q, &s.qd)),
            Kernel::GravityTorques => self.cycle(calls, |m, s| m.gravity_torques(&s.q)),
            Kernel::BiasTorques => self.cycle(calls, |m, s| m.bias_torques(&s.q, &s.qd)),
            Kernel::ForwardDynamics => {
                self.cycle(calls, |m, s| m.forward_dynamics(&s.q, &s.qd, &s.tau))
            }
            Kernel::KineticEnergy => self.cycle(calls, |m, s| m.kinetic_energy(&s.q, &s.qd)),
            Kernel::InverseDynamicsDerivatives => self.cycle(calls, |m, s| {
                m.inverse_dynamics_derivatives(&s.q, &s.qd, &s.qdd)
            }),
            Kernel::ForwardDynamicsDerivatives => self.cycle(calls, |m, s| {
                m.forward_dynamics_derivatives(&s.q, &s.qd, &s.tau)
            }),
            Kernel::MassMatrixInverse => self.cycle(calls, |m, s| m.mass_matrix_inverse(&s.q)),
            Kernel::PotentialEnergy => self.cycle(calls, |m, s| m.potential_energy(&s.q)),
            Kernel::FrictionTorques => self.cycle(calls, |m, s| m.friction_torques(&s.qd)),
            // The frames' kernels and the regressors have no method of `Dynamics`: nothing
            // to call (`rne bench` times them on the JIT alone, `BuiltinRobot::visit_having`).
            _ => {}
        }
    }
}

impl<D: Dynamics<N, N>, const N: usize> KernelCalls for Calls<D, N>
where
    D::Scalar: OrderedReal,
{
    fn states(&self) -> usize {
        self.inputs.len()
    }

    fn evaluate(&mut self, k: usize, out: &mut Vec<f64>) {
        out.clear();
        let s = self.inputs.get(k);
        let m = &self.model;
        let vector = |v: Option<[D::Scalar; N]>| v.into_iter().flatten();
        let matrix = |v: Option<[[D::Scalar; N]; N]>| v.into_iter().flatten().flatten();
        let values: Vec<D::Scalar> = match self.kernel {
            Kernel::InverseDynamics => vector(m.inverse_dynamics(&s.q, &s.qd, &s.qdd)).collect(),
            Kernel::MassMatrix => matrix(m.mass_matrix(&s.q)).collect(),
            Kernel::CoriolisMatrix => matrix(m.coriolis_matrix(&s.q, &s.qd)).collect(),
            Kernel::GravityTorques => vector(m.gravity_torques(&s.q)).collect(),
            Kernel::BiasTorques => vector(m.bias_torques(&s.q, &s.qd)).collect(),
            Kernel::ForwardDynamics => vector(m.forward_dynamics(&s.q, &s.qd, &s.tau)).collect(),
            Kernel::KineticEnergy => m.kinetic_energy(&s.q, &s.qd).into_iter().collect(),
            Kernel::InverseDynamicsDerivatives => m
                .inverse_dynamics_derivatives(&s.q, &s.qd, &s.qdd)
                .map(|(dq, dqd)| [dq, dqd])
                .into_iter()
                .flatten()
                .flatten()
                .flatten()
                .collect(),
            Kernel::ForwardDynamicsDerivatives => m
                .forward_dynamics_derivatives(&s.q, &s.qd, &s.tau)
                .map(|(dq, dqd, minv)| [dq, dqd, minv])
                .into_iter()
                .flatten()
                .flatten()
                .flatten()
                .collect(),
            Kernel::MassMatrixInverse => matrix(m.mass_matrix_inverse(&s.q)).collect(),
            Kernel::PotentialEnergy => m.potential_energy(&s.q).into_iter().collect(),
            Kernel::FrictionTorques => vector(m.friction_torques(&s.qd)).collect(),
            _ => Vec::new(),
        };
        out.extend(values.into_iter().map(OrderedReal::to_f64));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rne_codegen::Kernel;

    /// q̈ = τ − q: a model with forward dynamics only.
    struct Spring;

    impl Dynamics<1, 1> for Spring {
        type Scalar = f64;
        const NAME: &'static str = "spring";
        const JOINTS: &'static [&'static str] = &["q"];
        const FLOATING_BASE: bool = false;
        const KERNELS: &'static [Kernel] = &[Kernel::ForwardDynamics];
        fn forward_dynamics(&self, q: &[f64; 1], _: &[f64; 1], tau: &[f64; 1]) -> Option<[f64; 1]> {
            Some([tau[0] - q[0]])
        }
    }

    fn input(x: f64) -> Input<f64, 1> {
        Input {
            q: [x],
            qd: [0.0],
            qdd: [0.0],
            tau: [2.0 * x],
        }
    }

    /// Runs cycle through the pool only; evaluation reaches every input and reads the kernel
    /// asked for, nothing for a kernel the model lacks.
    #[test]
    fn pool_cycling_and_evaluation() {
        let inputs: Vec<Input<f64, 1>> = (0..10).map(|k| input(f64::from(k))).collect();
        let mut calls = Calls::new(Spring, Kernel::ForwardDynamics, inputs.clone(), 3);
        calls.run(7);
        assert_eq!(calls.inputs.next, 1);
        let mut out = Vec::new();
        calls.evaluate(9, &mut out);
        assert_eq!(out, vec![9.0]);
        assert_eq!(calls.states(), 10);
        let mut missing = Calls::new(Spring, Kernel::MassMatrix, inputs, 3);
        missing.evaluate(2, &mut out);
        assert!(out.is_empty());
    }

    /// A spring with damping: potential energy, friction torques, and the calls it counts.
    struct Damped {
        calls: std::cell::Cell<[u32; 2]>,
    }

    impl Dynamics<1, 1> for Damped {
        type Scalar = f64;
        const NAME: &'static str = "damped";
        const JOINTS: &'static [&'static str] = &["q"];
        const FLOATING_BASE: bool = false;
        const KERNELS: &'static [Kernel] = &[Kernel::PotentialEnergy, Kernel::FrictionTorques];
        fn potential_energy(&self, q: &[f64; 1]) -> Option<f64> {
            let [pe, f] = self.calls.get();
            self.calls.set([pe + 1, f]);
            Some(q[0] * q[0] / 2.0)
        }
        fn friction_torques(&self, qd: &[f64; 1]) -> Option<[f64; 1]> {
            let [pe, f] = self.calls.get();
            self.calls.set([pe, f + 1]);
            Some([-3.0 * qd[0]])
        }
    }

    /// Each kernel is timed and evaluated by its own method: the friction torques are not
    /// the potential energy, and a kernel `Dynamics` has no method for calls nothing.
    #[test]
    fn each_kernel_is_timed_and_read_by_its_own_method() {
        let damped = || Damped {
            calls: std::cell::Cell::new([0, 0]),
        };
        let inputs = vec![Input {
            q: [2.0],
            qd: [5.0],
            qdd: [0.0],
            tau: [0.0],
        }];
        let mut out = Vec::new();
        let mut friction = Calls::new(damped(), Kernel::FrictionTorques, inputs.clone(), 1);
        friction.run(4);
        assert_eq!(friction.model.calls.get(), [0, 4]);
        friction.evaluate(0, &mut out);
        assert_eq!(out, vec![-15.0]);
        let mut energy = Calls::new(damped(), Kernel::PotentialEnergy, inputs.clone(), 1);
        energy.run(3);
        assert_eq!(energy.model.calls.get(), [3, 0]);
        energy.evaluate(0, &mut out);
        assert_eq!(out, vec![2.0]);
        let mut frames = Calls::new(damped(), Kernel::FramePlacements, inputs, 1);
        frames.run(5);
        assert_eq!(frames.model.calls.get(), [0, 0]);
        frames.evaluate(0, &mut out);
        assert!(out.is_empty());
    }
}
