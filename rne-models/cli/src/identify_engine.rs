//! What `rne identify` evaluates regressors and torques with (`--engine`): the generated
//! regressor and inverse-dynamics kernels compiled in memory (the default), or the
//! independent numeric reference. The base parameters are found from the reference either
//! way ([`rne_identify::BaseSet::find`]); the engine evaluates the regressor of every sample,
//! every candidate excitation and the simulated torques, with the reference's columns.

use clap::ValueEnum;
use nalgebra::DMatrix;
use rne_codegen::Kernel;
use rne_codegen_core::{GenerationOptions, Scene};
use rne_identify::{IdentifyError, Regressors};
use rne_jit::{JitError, JitModel, State};
use rne_reference::Reference;
use rne_symbolic::model::Friction;
use rne_symbolic::RobotModel;

use super::CliError;

/// The engines of `rne identify`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum IdentifyEngine {
    /// The generated kernels compiled in memory (Cranelift); the numeric reference where this
    /// processor has no JIT backend, with a warning.
    #[default]
    Jit,
    /// The independent numeric reference (spatial-vector recursions, no generated code).
    Numeric,
}

/// The generated `regressor` and `inverse_dynamics` of a robot, compiled in memory.
pub struct JitRegressors {
    model: JitModel,
}

impl JitRegressors {
    /// Compiles the two kernels of `model` (friction included, as the reference of
    /// `rne identify` has it) and checks that the regressor has the reference's columns.
    pub fn compile(
        model: &RobotModel,
        scene: Scene,
        source: &str,
        reference: &Reference,
    ) -> Result<JitRegressors, CliError> {
        let scene = Scene {
            friction: true,
            ..scene
        };
        let options = GenerationOptions {
            outputs: vec![Kernel::InverseDynamics, Kernel::Regressor],
            ..GenerationOptions::default()
        };
        let model = JitModel::compile(model, &scene, &options, source)?;
        let columns = model.output_len(Kernel::Regressor).unwrap_or(0) / model.nv().max(1);
        if columns != reference.parameter_count() {
            return Err(CliError::Argument(format!(
                "{source}: the generated regressor has {columns} columns and the reference's \
                 {}; use --engine numeric",
                reference.parameter_count()
            )));
        }
        Ok(JitRegressors { model })
    }

    fn evaluate(
        &self,
        kernel: Kernel,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<Vec<f64>, IdentifyError> {
        let state = State {
            q,
            qd,
            qdd,
            tau: &[],
        };
        self.model
            .evaluate_vec(kernel, state)
            .map_err(|e: JitError| IdentifyError::Engine(Box::new(e)))
    }
}

impl Regressors for JitRegressors {
    fn nq(&self) -> usize {
        self.model.nq()
    }

    fn nv(&self) -> usize {
        self.model.nv()
    }

    fn regressor(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<DMatrix<f64>, IdentifyError> {
        let y = self.evaluate(Kernel::Regressor, q, qd, qdd)?;
        let nv = self.model.nv();
        Ok(DMatrix::from_row_slice(nv, y.len() / nv.max(1), &y))
    }

    fn inverse_dynamics(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<Vec<f64>, IdentifyError> {
        self.evaluate(Kernel::InverseDynamics, q, qd, qdd)
    }
}

/// Gives every moving joint of `model` friction (zero coefficients) where `friction` and it
/// has none, and armature (zero) where `armature` and it has none: the symbolic model the
/// reference of `rne identify --friction --armature` is built from.
pub fn add_joint_parameters(model: &mut RobotModel, friction: bool, armature: bool) {
    let RobotModel { graph, links, .. } = model;
    for link in links.iter_mut().filter(|l| l.joint.is_some()) {
        if friction && link.friction.is_none() {
            let zero = graph.zero();
            link.friction = Some(Friction {
                viscous: zero,
                coulomb: zero,
                offset: zero,
            });
        }
        if armature && link.armature.is_none() {
            link.armature = Some(graph.zero());
        }
    }
}
