//! The kernels a stress case measures: their optimised programs (for the double-double value
//! before optimisation, the dependencies and the programs themselves) and the engine that
//! computes their `f64` values — the programs evaluated operation by operation, or the same
//! programs compiled in memory, which perform the same operations in the same order and so
//! return the same bits (`rne stress --engine`).

use std::ops::Deref;

use rne_codegen::Kernel;
use rne_codegen_core::{GenerationOptions, Scene};
use rne_interpreted::{Interpreted, JointState};
use rne_jit::{JitModel, State};
use rne_symbolic::RobotModel;

use crate::error::StressError;

/// What computes the `f64` values of the kernels.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Engine {
    /// The programs evaluated operation by operation ([`Interpreted::eval`]).
    #[default]
    Interpreted,
    /// The programs compiled in memory (rne-jit).
    Jit,
}

/// The chosen kernels of one robot, with the engine of their `f64` values.
pub struct Probe {
    programs: Interpreted,
    compiled: Option<JitModel>,
}

impl Probe {
    /// Builds `kernels` of `model` (named `robot` in errors) for `engine`.
    pub fn new(
        model: &RobotModel,
        kernels: &[Kernel],
        engine: Engine,
        robot: &str,
    ) -> Result<Probe, StressError> {
        let compiled = match engine {
            Engine::Interpreted => None,
            Engine::Jit => {
                let options = GenerationOptions {
                    outputs: kernels.to_vec(),
                    ..GenerationOptions::default()
                };
                let scene = Scene::default();
                let compiled =
                    JitModel::compile(model, &scene, &options, robot).map_err(|cause| {
                        StressError::Compile {
                            robot: robot.to_owned(),
                            cause,
                        }
                    })?;
                Some(compiled)
            }
        };
        Ok(Probe {
            programs: Interpreted::with_kernels(model, kernels),
            compiled,
        })
    }

    /// What the generated `f64` kernel returns at `state` (matrices row-major); `None` if the
    /// kernel was not built or its arrays do not fit the state.
    pub fn eval_f64(&self, kernel: Kernel, state: &JointState) -> Option<Vec<f64>> {
        match &self.compiled {
            None => self.programs.eval(kernel, state.as_ref()),
            Some(compiled) => {
                let state = State {
                    q: &state.q,
                    qd: &state.qd,
                    qdd: &state.qdd,
                    tau: &state.tau,
                };
                compiled.evaluate_vec(kernel, state).ok()
            }
        }
    }
}

impl Deref for Probe {
    type Target = Interpreted;

    /// The programs, for what only they give (the double-double value, dependencies).
    fn deref(&self) -> &Interpreted {
        &self.programs
    }
}
