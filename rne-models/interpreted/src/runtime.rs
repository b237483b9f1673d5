//! Run-time models as [`Dynamics`]: the one adapter through which code written over the trait
//! (simulation, benchmarks) runs a model that was not generated — a robot file's kernels
//! compiled in memory ([`JitModel`]), its [`Interpreted`] programs, or the numeric reference —
//! once its number of joints N is known.

use std::cell::RefCell;

use rne_codegen::{Dynamics, Kernel};
use rne_jit::JitModel;
use rne_models::Visitor;
use rne_reference::Reference;

use crate::error::Error;
use crate::interpreted::Interpreted;
use crate::state::StateRef;

/// The largest number of joints [`Interpreted::visit`] instantiates code for.
pub const MAX_DOF: usize = 8;

/// The kernels the numeric reference computes: every kernel but the Christoffel matrix (it
/// computes C(q, q̇) q̇ inside the bias, not C).
const REFERENCE_KERNELS: [Kernel; 7] = [
    Kernel::InverseDynamics,
    Kernel::MassMatrix,
    Kernel::GravityTorques,
    Kernel::BiasTorques,
    Kernel::ForwardDynamics,
    Kernel::KineticEnergy,
    Kernel::PotentialEnergy,
];

/// What computes the kernels.
enum Engine<'a> {
    /// The optimised programs compiled in memory (what the generated kernels compute, bit for
    /// bit with `fma` off).
    Jit(&'a JitModel),
    /// The optimised programs, in `f64` (what the generated kernels compute, bit for bit).
    Interpreted(&'a Interpreted),
    /// The numeric reference through its allocation-free `*_into` methods; they need a
    /// mutable workspace (boxed: it is large beside a reference).
    Reference(Box<RefCell<Reference>>),
}

/// A model evaluated at run time, with N joints and a fixed base, as [`Dynamics<N, N>`].
///
/// What the trait fixes at compile time it cannot know: `NAME` is `"run-time model"`,
/// `JOINTS` and `KERNELS` are empty (no kernel was generated), and [`Dynamics::has`] answers
/// at run time. A failure of the reference at one state (e.g. a singular M) gives NaN values,
/// as the arithmetic of a generated kernel would. The programs allocate their result at every
/// evaluation; the reference does not.
pub struct RuntimeModel<'a, const N: usize> {
    engine: Engine<'a>,
}

impl<'a, const N: usize> RuntimeModel<'a, N> {
    /// The programs of `interpreted`, which must have N joints.
    pub fn interpreted(interpreted: &'a Interpreted) -> Result<Self, Error> {
        check::<N>(interpreted.dof())?;
        Ok(RuntimeModel {
            engine: Engine::Interpreted(interpreted),
        })
    }

    /// The compiled kernels of `jit`, which must have N configuration and N velocity variables.
    pub fn jit(jit: &'a JitModel) -> Result<Self, Error> {
        check::<N>(jit.nq())?;
        check::<N>(jit.nv())?;
        Ok(RuntimeModel {
            engine: Engine::Jit(jit),
        })
    }

    /// The numeric reference, which must have N configuration and N velocity variables.
    pub fn reference(reference: Reference) -> Result<Self, Error> {
        check::<N>(reference.nq())?;
        check::<N>(reference.nv())?;
        Ok(RuntimeModel {
            engine: Engine::Reference(Box::new(RefCell::new(reference))),
        })
    }

    /// Writes `kernel` at `state` into `out`; `false` if the engine has no such kernel.
    fn write(&self, kernel: Kernel, state: StateRef<'_>, out: &mut [f64]) -> bool {
        match &self.engine {
            Engine::Jit(jit) => {
                let StateRef { q, qd, qdd, tau } = state;
                let state = rne_jit::State { q, qd, qdd, tau };
                // A state the JIT refuses (NaN) gives NaN, as a generated kernel's arithmetic.
                match jit.evaluate(kernel, state, out) {
                    Ok(()) => true,
                    Err(rne_jit::JitError::NonFinite { .. }) => {
                        out.fill(f64::NAN);
                        true
                    }
                    Err(_) => false,
                }
            }
            Engine::Interpreted(programs) => match programs.eval(kernel, state) {
                Some(values) if values.len() == out.len() => {
                    out.copy_from_slice(&values);
                    true
                }
                _ => false,
            },
            Engine::Reference(reference) => {
                if !REFERENCE_KERNELS.contains(&kernel) {
                    return false;
                }
                let mut r = reference.borrow_mut();
                let StateRef { q, qd, qdd, tau } = state;
                let result = match kernel {
                    Kernel::InverseDynamics => r.inverse_dynamics_into(q, qd, qdd, out),
                    Kernel::MassMatrix => r.mass_matrix_into(q, out),
                    Kernel::GravityTorques => r.gravity_torques_into(q, out),
                    Kernel::BiasTorques => r.bias_torques_into(q, qd, out),
                    Kernel::ForwardDynamics => r.forward_dynamics_into(q, qd, tau, out),
                    Kernel::KineticEnergy => r.kinetic_energy(q, qd).map(|t| out[0] = t),
                    _ => r.potential_energy(q).map(|v| out[0] = v),
                };
                if result.is_err() {
                    out.fill(f64::NAN);
                }
                true
            }
        }
    }

    fn vector(&self, kernel: Kernel, state: StateRef<'_>) -> Option<[f64; N]> {
        let mut out = [0.0; N];
        self.write(kernel, state, &mut out).then_some(out)
    }

    fn matrix(&self, kernel: Kernel, state: StateRef<'_>) -> Option<[[f64; N]; N]> {
        let mut out = [[0.0; N]; N];
        self.write(kernel, state, out.as_flattened_mut())
            .then_some(out)
    }

    fn scalar(&self, kernel: Kernel, state: StateRef<'_>) -> Option<f64> {
        let mut out = [0.0];
        self.write(kernel, state, &mut out).then_some(out[0])
    }
}

impl Interpreted {
    /// Runs `visitor` on these programs as a [`RuntimeModel<N>`] of their number of joints N,
    /// for 1 ≤ N ≤ [`MAX_DOF`]: the run-time counterpart of
    /// [`BuiltinRobot::visit`](rne_models::BuiltinRobot::visit).
    pub fn visit<V: Visitor>(&self, visitor: V) -> Result<V::Output, Error> {
        macro_rules! dispatch {
            ($($n:literal)*) => {
                match self.dof() {
                    $($n => Ok(visitor.visit(RuntimeModel::<$n>::interpreted(self)?)),)*
                    dof => Err(Error::TooManyJoints { dof, max: MAX_DOF }),
                }
            };
        }
        dispatch!(1 2 3 4 5 6 7 8)
    }
}

/// A model of `dof` joints can be a `RuntimeModel<N>`.
fn check<const N: usize>(dof: usize) -> Result<(), Error> {
    if dof == N {
        Ok(())
    } else {
        Err(Error::Size { dof, expected: N })
    }
}

/// A state of the arrays a kernel takes.
fn state<'s>(q: &'s [f64], qd: &'s [f64], qdd: &'s [f64], tau: &'s [f64]) -> StateRef<'s> {
    StateRef { q, qd, qdd, tau }
}

impl<const N: usize> Dynamics<N, N> for RuntimeModel<'_, N> {
    type Scalar = f64;
    const NAME: &'static str = "run-time model";
    const JOINTS: &'static [&'static str] = &[];
    const FLOATING_BASE: bool = false;
    const KERNELS: &'static [Kernel] = &[];

    fn has(&self, kernel: Kernel) -> bool {
        match &self.engine {
            Engine::Jit(jit) => jit.has(kernel),
            Engine::Interpreted(programs) => programs.has(kernel),
            Engine::Reference(_) => REFERENCE_KERNELS.contains(&kernel),
        }
    }

    fn inverse_dynamics(&self, q: &[f64; N], qd: &[f64; N], qdd: &[f64; N]) -> Option<[f64; N]> {
        self.vector(Kernel::InverseDynamics, state(q, qd, qdd, &[]))
    }

    fn mass_matrix(&self, q: &[f64; N]) -> Option<[[f64; N]; N]> {
        self.matrix(Kernel::MassMatrix, state(q, &[], &[], &[]))
    }

    fn coriolis_matrix(&self, q: &[f64; N], qd: &[f64; N]) -> Option<[[f64; N]; N]> {
        self.matrix(Kernel::CoriolisMatrix, state(q, qd, &[], &[]))
    }

    fn gravity_torques(&self, q: &[f64; N]) -> Option<[f64; N]> {
        self.vector(Kernel::GravityTorques, state(q, &[], &[], &[]))
    }

    fn bias_torques(&self, q: &[f64; N], qd: &[f64; N]) -> Option<[f64; N]> {
        self.vector(Kernel::BiasTorques, state(q, qd, &[], &[]))
    }

    fn forward_dynamics(&self, q: &[f64; N], qd: &[f64; N], tau: &[f64; N]) -> Option<[f64; N]> {
        self.vector(Kernel::ForwardDynamics, state(q, qd, &[], tau))
    }

    fn kinetic_energy(&self, q: &[f64; N], qd: &[f64; N]) -> Option<f64> {
        self.scalar(Kernel::KineticEnergy, state(q, qd, &[], &[]))
    }

    fn potential_energy(&self, q: &[f64; N]) -> Option<f64> {
        self.scalar(Kernel::PotentialEnergy, state(q, &[], &[], &[]))
    }
}
