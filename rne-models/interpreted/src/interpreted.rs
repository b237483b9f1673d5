//! The dynamics evaluated from the optimised straight-line programs, without compiling them:
//! what `rne eval --engine symbolic` uses for robots that are not built in, and the baseline
//! that shows what compiling the code buys. The programs are exactly what `derive_dynamics!`
//! emits, evaluated operation by operation in the same order, so in `f64` the results are
//! bit-for-bit those of the generated functions.

use rne_codegen::{kernel_program, Kernel, Program, Real};
use rne_symbolic::{RobotModel, Symbol, SymbolicDynamics};

use crate::kernels::{DimensionError, Kernels};

/// Every kernel of a robot as a straight-line program.
pub struct Interpreted {
    dynamics: SymbolicDynamics,
    programs: Vec<(Kernel, Program)>,
}

/// The values of the joint symbols at one state.
struct State<'a> {
    q: &'a [f64],
    qd: &'a [f64],
    qdd: &'a [f64],
    tau: &'a [f64],
}

impl Interpreted {
    /// Builds every kernel of `model` (numeric or symbolic parameters).
    pub fn new(model: &RobotModel) -> Interpreted {
        let dynamics = SymbolicDynamics::new(model);
        let programs = Kernel::ALL
            .iter()
            .map(|&k| (k, kernel_program(&dynamics, k)))
            .collect();
        Interpreted { dynamics, programs }
    }

    /// Evaluates one kernel in any scalar type (e.g. `DoubleDouble` for a ≈32-digit value of
    /// the same model): `q`, `qd`, `qdd`, `tau` as the kernel needs them (others may be empty).
    pub fn eval_in<T: Real>(
        &self,
        kernel: Kernel,
        q: &[T],
        qd: &[T],
        qdd: &[T],
        tau: &[T],
    ) -> Vec<T> {
        let program = &self
            .programs
            .iter()
            .find(|(k, _)| *k == kernel)
            .expect("every kernel is built")
            .1;
        let model = &self.dynamics.model;
        program.eval(|s| match s {
            Symbol::Position(k) => q[k as usize],
            Symbol::Velocity(k) => qd[k as usize],
            Symbol::Acceleration(k) => qdd[k as usize],
            Symbol::Force(k) => tau[k as usize],
            Symbol::Parameter(_) => T::from_f64(model.parameter_value(s).unwrap_or(f64::NAN)),
        })
    }

    fn check(&self, argument: &'static str, values: &[f64]) -> Result<(), DimensionError> {
        let expected = self.dynamics.dof();
        if values.len() == expected {
            Ok(())
        } else {
            Err(DimensionError {
                argument,
                got: values.len(),
                expected,
            })
        }
    }

    fn eval(&self, kernel: Kernel, state: &State) -> Vec<f64> {
        self.eval_in(kernel, state.q, state.qd, state.qdd, state.tau)
    }

    fn matrix(&self, flat: Vec<f64>) -> Vec<Vec<f64>> {
        flat.chunks(self.dynamics.dof().max(1))
            .map(<[f64]>::to_vec)
            .collect()
    }
}

impl Kernels for Interpreted {
    fn dof(&self) -> usize {
        self.dynamics.dof()
    }

    fn joints(&self) -> Vec<String> {
        self.dynamics.model.joint_names()
    }

    fn inverse_dynamics(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<Vec<f64>, DimensionError> {
        self.check("q", q)?;
        self.check("qd", qd)?;
        self.check("qdd", qdd)?;
        Ok(self.eval(
            Kernel::InverseDynamics,
            &State {
                q,
                qd,
                qdd,
                tau: &[],
            },
        ))
    }

    fn mass_matrix(&self, q: &[f64]) -> Result<Vec<Vec<f64>>, DimensionError> {
        self.check("q", q)?;
        Ok(self.matrix(self.eval(
            Kernel::MassMatrix,
            &State {
                q,
                qd: &[],
                qdd: &[],
                tau: &[],
            },
        )))
    }

    fn coriolis_matrix(&self, q: &[f64], qd: &[f64]) -> Result<Vec<Vec<f64>>, DimensionError> {
        self.check("q", q)?;
        self.check("qd", qd)?;
        Ok(self.matrix(self.eval(
            Kernel::CoriolisMatrix,
            &State {
                q,
                qd,
                qdd: &[],
                tau: &[],
            },
        )))
    }

    fn gravity_torques(&self, q: &[f64]) -> Result<Vec<f64>, DimensionError> {
        self.check("q", q)?;
        Ok(self.eval(
            Kernel::GravityTorques,
            &State {
                q,
                qd: &[],
                qdd: &[],
                tau: &[],
            },
        ))
    }

    fn bias_torques(&self, q: &[f64], qd: &[f64]) -> Result<Vec<f64>, DimensionError> {
        self.check("q", q)?;
        self.check("qd", qd)?;
        Ok(self.eval(
            Kernel::BiasTorques,
            &State {
                q,
                qd,
                qdd: &[],
                tau: &[],
            },
        ))
    }

    fn forward_dynamics(
        &self,
        q: &[f64],
        qd: &[f64],
        tau: &[f64],
    ) -> Result<Vec<f64>, DimensionError> {
        self.check("q", q)?;
        self.check("qd", qd)?;
        self.check("tau", tau)?;
        Ok(self.eval(
            Kernel::ForwardDynamics,
            &State {
                q,
                qd,
                qdd: &[],
                tau,
            },
        ))
    }

    fn kinetic_energy(&self, q: &[f64], qd: &[f64]) -> Result<f64, DimensionError> {
        self.check("q", q)?;
        self.check("qd", qd)?;
        Ok(self.eval(
            Kernel::KineticEnergy,
            &State {
                q,
                qd,
                qdd: &[],
                tau: &[],
            },
        )[0])
    }

    fn potential_energy(&self, q: &[f64]) -> Result<f64, DimensionError> {
        self.check("q", q)?;
        Ok(self.eval(
            Kernel::PotentialEnergy,
            &State {
                q,
                qd: &[],
                qdd: &[],
                tau: &[],
            },
        )[0])
    }
}
