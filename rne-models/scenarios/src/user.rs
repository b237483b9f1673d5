//! User scenarios: a TOML file naming a model, an initial state, an input (open-loop torque,
//! damping or PD control with gravity compensation and saturation), a duration and an
//! integrator, run through the same machinery as the thesis's experiments.
//!
//! ```toml
//! model = "planar-elbow"        # a built-in robot, or a .toml / .urdf spec (relative to this file)
//! duration = 10.0               # s
//! sample = 0.01                 # output spacing, s (default 0.01)
//! q0 = [0.0, 0.0]               # initial joint positions
//! qd0 = [0.0, 0.0]              # initial joint velocities (default 0)
//!
//! [controller]                  # optional: no input without it
//! torque = [0.0, 0.0]           # constant open-loop torque (default 0)
//! kp = [22.0, 45.0]             # PD: u = -Kp (q - q_ref) - Kd qd, needs q_ref, (6.32)
//! kd = [15.0, 8.0]              # derivative gain; alone it is damping u = -Kd qd, (6.30)
//! q_ref = [1.0, 0.5]
//! gravity = "remove"            # none (default) | remove (from the model, (6.33)) | compensate (add g(q) to u)
//! saturation = [39.4, 39.4]     # per-joint |u| limit, applied last
//!
//! [integrator]                  # optional: Dormand-Prince at rtol 1e-10, atol 1e-12
//! method = "dopri5"             # dopri5 | rk4 | gauss-legendre | implicit-midpoint
//! rtol = 1e-10                  # dopri5 only
//! atol = 1e-12                  # dopri5 only
//! step_to_outputs = false       # dopri5 only: end a step at every output time
//! # step = 1e-3                 # rk4, gauss-legendre, implicit-midpoint: the step (s), required
//! ```
//!
//! Unknown keys are errors naming the key; vectors must have one entry per joint.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::catalogue::{FileEngine, RunOptions};
use super::control::pd_findings;
use super::error::ScenarioError;
use super::figures::{energies, joint_angles, lyapunov, torques};
use super::outcome::{Finding, Outcome, Table};
use super::progress::WithProgress;
use rne_codegen_core::{GenerationOptions, Scene};
use rne_figures::time_series::Figure;
use rne_interpreted::{visit_jit, Interpreted};
use rne_jit::{JitError, JitModel};
use rne_models::{RobotSource, Visitor};
use rne_runtime::Dynamics;
use rne_sim::{
    output_times, simulate, ConstantTorque, Controller, Damping, Dopri5, GaussLegendre, Method, Pd,
    Record, Rk4, SimError, State, WithoutGravity,
};
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::RobotModel;

/// The largest number of output samples a scenario file may ask for.
const MAX_SAMPLES: f64 = 1e7;

/// The largest number of fixed steps a scenario file may ask for: Dormand–Prince's own cap
/// ([`Dopri5::max_steps`]), minutes of computing even for the smallest arm.
const MAX_FIXED_STEPS: f64 = 1e8;

/// How gravity is compensated (section 6.2.5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GravityMode {
    /// Not at all: the arm feels g(q).
    #[default]
    None,
    /// Removed from the model, M q̈ + C q̇ = u: the thesis's way, (6.33) and (6.53).
    Remove,
    /// Added to the input before saturation, u = u_PD + g(q): what motors must really supply.
    Compensate,
}

/// The `[controller]` table.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct ControllerSpec {
    torque: Option<Vec<f64>>,
    kp: Option<Vec<f64>>,
    kd: Option<Vec<f64>>,
    q_ref: Option<Vec<f64>>,
    #[serde(default)]
    gravity: GravityMode,
    saturation: Option<Vec<f64>>,
}

/// The `[integrator]` table.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "method", rename_all = "kebab-case", deny_unknown_fields)]
enum IntegratorSpec {
    Dopri5 {
        rtol: Option<f64>,
        atol: Option<f64>,
        #[serde(default)]
        step_to_outputs: bool,
    },
    Rk4 {
        step: f64,
    },
    GaussLegendre {
        step: f64,
    },
    ImplicitMidpoint {
        step: f64,
    },
}

/// The file's top level.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ScenarioFile {
    model: String,
    duration: f64,
    sample: Option<f64>,
    q0: Vec<f64>,
    qd0: Option<Vec<f64>>,
    #[serde(default)]
    controller: ControllerSpec,
    integrator: Option<IntegratorSpec>,
}

/// A scenario read from a TOML file and checked; see the module documentation for the format.
#[derive(Clone, Debug)]
pub struct UserScenario {
    path: PathBuf,
    name: String,
    file: ScenarioFile,
    method: Method,
}

impl UserScenario {
    /// Reads and checks the scenario file at `path` (the model is read by [`UserScenario::run`]).
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|e| ScenarioError::File {
            path: path.to_path_buf(),
            message: format!("cannot read: {e}"),
        })?;
        Self::parse(&text, path)
    }

    /// Parses and checks scenario text; `path` names it in errors and anchors a relative model
    /// path.
    pub fn parse(text: &str, path: &Path) -> Result<Self, ScenarioError> {
        let error = |message: String| ScenarioError::File {
            path: path.to_path_buf(),
            message,
        };
        let file: ScenarioFile = toml::from_str(text).map_err(|e| error(e.to_string()))?;
        let method = check(&file).map_err(error)?;
        let name = path.file_stem().map_or_else(
            || "scenario".to_owned(),
            |s| s.to_string_lossy().into_owned(),
        );
        Ok(Self {
            path: path.to_path_buf(),
            name,
            file,
            method,
        })
    }

    /// The scenario's name: its file name without extension.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Reads the model and runs the scenario: the built-in robots on their generated kernels,
    /// other spec files on their optimised programs.
    pub fn run(&self, options: &RunOptions) -> Result<Outcome, ScenarioError> {
        let source = match RobotSource::resolve(&self.file.model) {
            RobotSource::File(file) if file.is_relative() => {
                let base = self.path.parent().unwrap_or(Path::new(""));
                RobotSource::File(base.join(file))
            }
            source => source,
        };
        let model = source
            .load(&LoadOptions::default())
            .map_err(|cause| ScenarioError::Model {
                path: self.path.clone(),
                cause,
            })?;
        let run = Run {
            scenario: self,
            options,
            names: model.joint_names(),
        };
        match &source {
            RobotSource::Builtin(robot) => robot.visit(run),
            RobotSource::File(_) => {
                model
                    .check_mass_matrix_invertible()
                    .map_err(|e| self.error(format!("model `{}`: {e}", self.file.model)))?;
                self.on_file_model(&model, run, options.engine)
                    .map_err(|error| match error {
                        rne_interpreted::Error::TooManyJoints { dof, max } => self.error(format!(
                            "model `{}` has {dof} joints; scenario files support 1 to {max}",
                            self.file.model
                        )),
                        cause => ScenarioError::Evaluation {
                            path: self.path.clone(),
                            cause,
                        },
                    })?
            }
        }
    }

    /// Runs `run` on `model`'s kernels compiled in memory, or on its programs interpreted.
    fn on_file_model(
        &self,
        model: &RobotModel,
        run: Run<'_>,
        engine: FileEngine,
    ) -> Result<Result<Outcome, ScenarioError>, rne_interpreted::Error> {
        if engine == FileEngine::Jit {
            let (scene, options) = (Scene::default(), GenerationOptions::default());
            match JitModel::compile(model, &scene, &options, &self.file.model) {
                Ok(jit) => return visit_jit(&jit, run),
                Err(JitError::UnsupportedHost(why)) => {
                    eprintln!("warning: {why}; the interpreter computes instead");
                }
                Err(e) => return Err(e.into()),
            }
        }
        Interpreted::new(model).visit(run)
    }

    fn error(&self, message: String) -> ScenarioError {
        ScenarioError::File {
            path: self.path.clone(),
            message,
        }
    }

    /// The vector under `key` as N values, `default` when absent.
    fn joints<const N: usize>(
        &self,
        key: &str,
        values: Option<&Vec<f64>>,
        default: f64,
        names: &[String],
    ) -> Result<[f64; N], ScenarioError> {
        match values {
            None => Ok([default; N]),
            Some(v) => v.as_slice().try_into().map_err(|_| {
                self.error(format!(
                    "`{key}` has {} values; model `{}` has {N} joints ({})",
                    v.len(),
                    self.file.model,
                    names.join(", ")
                ))
            }),
        }
    }

    /// The run for a model with N joints whose names are `names`.
    fn run_with<const N: usize, D: Dynamics<N, N, Scalar = f64>>(
        &self,
        model: D,
        names: &[String],
        options: &RunOptions,
    ) -> Result<Outcome, ScenarioError> {
        let c = &self.file.controller;
        let q0 = self.joints::<N>("q0", Some(&self.file.q0), 0.0, names)?;
        let qd0 = self.joints::<N>("qd0", self.file.qd0.as_ref(), 0.0, names)?;
        let torque = self.joints::<N>("controller.torque", c.torque.as_ref(), 0.0, names)?;
        let kp = self.joints::<N>("controller.kp", c.kp.as_ref(), 0.0, names)?;
        let kd = self.joints::<N>("controller.kd", c.kd.as_ref(), 0.0, names)?;
        let q_ref = self.joints::<N>("controller.q_ref", c.q_ref.as_ref(), 0.0, names)?;
        let u_max = self.joints::<N>(
            "controller.saturation",
            c.saturation.as_ref(),
            f64::INFINITY,
            names,
        )?;
        let feedback = match (&c.kp, &c.kd) {
            (Some(_), _) => Feedback::Pd(Pd::new(kp, kd, q_ref)),
            (None, Some(_)) => Feedback::Damping(Damping::new(kd)),
            (None, None) => Feedback::None,
        };
        let law = ConstantTorque(torque).plus(feedback);
        let x0 = State::new(q0, qd0);
        let record = match c.gravity {
            GravityMode::None => self.simulate(&model, &law.saturated(u_max), &x0, options),
            GravityMode::Remove => {
                self.simulate(&WithoutGravity(&model), &law.saturated(u_max), &x0, options)
            }
            GravityMode::Compensate => {
                let compensated = law.with_gravity_compensation(&model).saturated(u_max);
                self.simulate(&model, &compensated, &x0, options)
            }
        }?;

        let mut findings = vec![Finding::new(
            "energy drift max |E − E(0)| of the simulated model",
            format!("{:.2e} J", record.energy_drift()),
            "—",
        )];
        let mut panels = vec![joint_angles(&record, c.kp.as_ref().map(|_| &q_ref))];
        panels.push(torques(&record, c.saturation.as_ref().map(|_| &u_max)));
        panels.push(energies(&record));
        if c.kp.is_some() {
            findings.extend(pd_findings(&record, &q_ref, &u_max, "—"));
            panels.push(lyapunov(&[("V (6.57)".to_owned(), &record)]));
        }
        Ok(Outcome {
            scenario: self.name.clone(),
            tables: vec![Table::of(format!("{}.csv", self.name), &record)],
            figures: vec![Figure {
                file: self.name.clone(),
                title: format!(
                    "{} — {} ({})",
                    self.name,
                    self.file.model,
                    method_name(&self.method)
                ),
                panels,
            }],
            findings,
        })
    }
    /// Simulates `model` under `controller` from `x0` over the scenario's duration.
    fn simulate<const N: usize, D, C>(
        &self,
        model: &D,
        controller: &C,
        x0: &State<N>,
        options: &RunOptions,
    ) -> Result<Record<N>, ScenarioError>
    where
        D: Dynamics<N, N, Scalar = f64>,
        C: Controller<N>,
    {
        let sample = self.file.sample.unwrap_or(0.01);
        let times = output_times(0.0, self.file.duration, sample);
        let integrator = WithProgress::new(&self.method, &self.name, options.progress);
        Ok(simulate(model, controller, &integrator, x0, &times)
            .map_err(SimError::in_run(&self.name))?)
    }
}

/// A scenario's run on the model the visit brings.
struct Run<'a> {
    scenario: &'a UserScenario,
    options: &'a RunOptions,
    names: Vec<String>,
}

impl Visitor for Run<'_> {
    type Output = Result<Outcome, ScenarioError>;

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) -> Self::Output {
        self.scenario
            .run_with::<N, D>(model, &self.names, self.options)
    }
}

/// The feedback part of a scenario's input.
#[derive(Clone, Copy, Debug)]
enum Feedback<const N: usize> {
    None,
    Damping(Damping<N>),
    Pd(Pd<N>),
}

impl<const N: usize> Controller<N> for Feedback<N> {
    fn torque(&self, t: f64, q: &[f64; N], qd: &[f64; N]) -> [f64; N] {
        match self {
            Self::None => [0.0; N],
            Self::Damping(d) => d.torque(t, q, qd),
            Self::Pd(pd) => pd.torque(t, q, qd),
        }
    }

    fn spring_energy(&self, q: &[f64; N]) -> Option<f64> {
        match self {
            Self::Pd(pd) => pd.spring_energy(q),
            _ => None,
        }
    }
}

/// How the integrator is described in titles.
fn method_name(method: &Method) -> String {
    match method {
        Method::Dopri5(d) => format!("Dormand–Prince, rtol {:e}, atol {:e}", d.rtol, d.atol),
        Method::Rk4(r) => format!("RK4, h = {} s", r.h),
        Method::GaussLegendre(g) => {
            format!("Gauss–Legendre ({:?} stages), h = {} s", g.stages, g.h)
        }
    }
}

/// Checks everything that does not need the model, and builds the integrator.
fn check(file: &ScenarioFile) -> Result<Method, String> {
    check_times(file)?;
    check_start_and_controller(file)?;
    integrator(file)
}

/// `Ok` when every entry of `v`, the value of `key`, is finite.
fn finite(key: &str, v: &[f64]) -> Result<(), String> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(format!("`{key}` must be finite"))
    }
}

/// `Ok` when `x`, the value of `key`, is positive and finite.
fn positive(key: &str, x: f64) -> Result<(), String> {
    if x > 0.0 && x.is_finite() {
        Ok(())
    } else {
        Err(format!("`{key}` must be positive and finite, got {x}"))
    }
}

/// The duration and the sample interval: positive, and not asking for more than
/// [`MAX_SAMPLES`] samples.
fn check_times(file: &ScenarioFile) -> Result<(), String> {
    positive("duration", file.duration)?;
    let sample = file.sample.unwrap_or(0.01);
    positive("sample", sample)?;
    if file.duration / sample > MAX_SAMPLES {
        return Err(format!(
            "`duration` / `sample` asks for more than {MAX_SAMPLES:e} samples"
        ));
    }
    Ok(())
}

/// The initial state and the controller's numbers: finite, gains non-negative, saturation
/// limits positive, and `kp` and `q_ref` given together.
fn check_start_and_controller(file: &ScenarioFile) -> Result<(), String> {
    finite("q0", &file.q0)?;
    finite("qd0", file.qd0.as_deref().unwrap_or(&[]))?;
    let c = &file.controller;
    finite("controller.torque", c.torque.as_deref().unwrap_or(&[]))?;
    finite("controller.q_ref", c.q_ref.as_deref().unwrap_or(&[]))?;
    for (key, gains) in [("controller.kp", &c.kp), ("controller.kd", &c.kd)] {
        if gains
            .iter()
            .flatten()
            .any(|g| !(g.is_finite() && *g >= 0.0))
        {
            return Err(format!("`{key}` must be finite and non-negative"));
        }
    }
    if let Some(limits) = &c.saturation {
        if limits.iter().any(|u| u.is_nan() || *u <= 0.0) {
            return Err("`controller.saturation` entries must be positive".into());
        }
    }
    match (&c.kp, &c.q_ref) {
        (Some(_), None) => Err("`controller.kp` needs `controller.q_ref`".into()),
        (None, Some(_)) => Err("`controller.q_ref` needs `controller.kp`".into()),
        _ => Ok(()),
    }
}

/// The integrator `file` asks for (Dormand–Prince at rtol 1e-10, atol 1e-12 unless given),
/// its tolerances or step checked.
fn integrator(file: &ScenarioFile) -> Result<Method, String> {
    let fixed_step = |step: f64| {
        positive("integrator.step", step)?;
        if file.duration / step > MAX_FIXED_STEPS {
            return Err(format!(
                "`duration` / `integrator.step` asks for more than {MAX_FIXED_STEPS:e} steps"
            ));
        }
        Ok(())
    };
    let method = match file.integrator.clone().unwrap_or(IntegratorSpec::Dopri5 {
        rtol: None,
        atol: None,
        step_to_outputs: false,
    }) {
        IntegratorSpec::Dopri5 {
            rtol,
            atol,
            step_to_outputs,
        } => {
            let (rtol, atol) = (rtol.unwrap_or(1e-10), atol.unwrap_or(1e-12));
            if !(rtol >= 0.0 && atol >= 0.0 && rtol + atol > 0.0 && (rtol + atol).is_finite()) {
                return Err("`integrator.rtol` and `integrator.atol` must be non-negative, finite and not both zero".into());
            }
            Method::Dopri5(Dopri5 {
                step_to_outputs,
                ..Dopri5::new(rtol, atol)
            })
        }
        IntegratorSpec::Rk4 { step } => {
            fixed_step(step)?;
            Method::Rk4(Rk4::new(step))
        }
        IntegratorSpec::GaussLegendre { step } => {
            fixed_step(step)?;
            Method::GaussLegendre(GaussLegendre::new(step))
        }
        IntegratorSpec::ImplicitMidpoint { step } => {
            fixed_step(step)?;
            Method::GaussLegendre(GaussLegendre::midpoint(step))
        }
    };
    Ok(method)
}
