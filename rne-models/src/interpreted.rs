//! The dynamics evaluated straight from the expression graph, without generating code: what
//! `rne eval --engine symbolic` uses for robots that are not built in, and the baseline that
//! shows what code generation buys.

use rne_codegen::Kernel;
use rne_symbolic::expr::Evaluator;
use rne_symbolic::{RobotModel, Symbol, SymbolicDynamics};

use crate::kernels::{DimensionError, Kernels};

/// Every kernel of a robot as a prepared graph evaluation.
pub struct Interpreted {
    dynamics: SymbolicDynamics,
    evaluators: Vec<(Kernel, Evaluator)>,
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
        let mut dynamics = SymbolicDynamics::new(model);
        let roots: Vec<(Kernel, Vec<_>)> = Kernel::ALL
            .iter()
            .map(|&k| (k, k.build(&mut dynamics)))
            .collect();
        let evaluators = roots
            .into_iter()
            .map(|(k, ids)| (k, Evaluator::new(&dynamics.model.graph, &ids)))
            .collect();
        Interpreted {
            dynamics,
            evaluators,
        }
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
        let evaluator = &self
            .evaluators
            .iter()
            .find(|(k, _)| *k == kernel)
            .expect("every kernel is built")
            .1;
        let model = &self.dynamics.model;
        evaluator.eval(&model.graph, |s| match s {
            Symbol::Position(k) => state.q[k as usize],
            Symbol::Velocity(k) => state.qd[k as usize],
            Symbol::Acceleration(k) => state.qdd[k as usize],
            Symbol::Force(k) => state.tau[k as usize],
            Symbol::Parameter(_) => model.parameter_value(s).unwrap_or(f64::NAN),
        })
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
