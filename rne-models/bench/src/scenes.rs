//! Scene savings: what each scene setting of `derive_dynamics!` saves on a robot's inverse
//! dynamics, in operations (the emitted program's [`OpCount`]) and in time per call.
//!
//! The full inverse dynamics τ(q, q̇, q̈) is set beside the gravity torques g(q) (what a
//! gravity-compensation loop needs), the zero-gravity τ, τ with the first joint locked at 0
//! and the static-scene τ (q̇ = 0). Operation counts come from generating each scene's
//! `inverse_dynamics` (or `gravity_torques`) with [`generate`]; times from timing the
//! five generated functions together ([`time_interleaved`](super::timing::time_interleaved)).

use rne_codegen::Kernel;
use rne_codegen_core::{generate, GenerationOptions, Scene};
use rne_symbolic::OpCount;

use super::error::BenchError;
use super::implementation::Implementation;
use super::kernels::time;
use super::robots::{subjects, Cases};
use super::timing::{Plan, Timing};

/// A scene of the scene-savings table.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum SceneKernel {
    /// The full inverse dynamics.
    Full,
    /// The gravity torques alone.
    GravityOnly,
    /// The inverse dynamics without gravity.
    ZeroGravity,
    /// The inverse dynamics with the first joint locked.
    Locked,
    /// The inverse dynamics of a static scene.
    AtRest,
}

impl SceneKernel {
    /// Every scene, in table order.
    pub const ALL: [SceneKernel; 5] = [
        SceneKernel::Full,
        SceneKernel::GravityOnly,
        SceneKernel::ZeroGravity,
        SceneKernel::Locked,
        SceneKernel::AtRest,
    ];

    /// The name in the table.
    pub fn label(self) -> &'static str {
        match self {
            SceneKernel::Full => "full τ(q, q̇, q̈)",
            SceneKernel::GravityOnly => "gravity only g(q)",
            SceneKernel::ZeroGravity => "zero gravity",
            SceneKernel::Locked => "joint 1 locked",
            SceneKernel::AtRest => "static scene (q̇ = 0)",
        }
    }

    /// The generated kernel and the scene it is generated for; `locked_joint` names the joint
    /// to lock.
    fn generation(self, locked_joint: &str) -> (Kernel, Scene) {
        let kernel = match self {
            SceneKernel::GravityOnly => Kernel::GravityTorques,
            _ => Kernel::InverseDynamics,
        };
        let mut scene = Scene::default();
        match self {
            SceneKernel::ZeroGravity => scene.gravity = Some([0.0; 3]),
            SceneKernel::Locked => scene.lock = vec![(locked_joint.to_owned(), 0.0)],
            SceneKernel::AtRest => scene.at_rest = true,
            SceneKernel::Full | SceneKernel::GravityOnly => {}
        }
        (kernel, scene)
    }
}

/// One scene of one robot.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneRow {
    /// The scene.
    pub scene: SceneKernel,
    /// Operations per call.
    pub ops: OpCount,
    /// Time per call.
    pub timing: Timing,
    /// Time relative to the full inverse dynamics (median of per-round ratios).
    pub relative_time: f64,
}

/// The scene savings of one robot.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotScenes {
    /// The built-in robot's name.
    pub robot: &'static str,
    /// Its number of joints.
    pub dof: usize,
    /// One row per scene, in [`SceneKernel::ALL`] order.
    pub rows: Vec<SceneRow>,
}

/// Measures the scene savings of the robot of `cases`, timing on the first `pool` states.
pub fn measure(cases: &Cases, plan: &Plan, pool: usize) -> Result<RobotScenes, BenchError> {
    let robot = cases.robot.name;
    let mut ops = Vec::new();
    for scene in SceneKernel::ALL {
        let (kernel, settings) = scene.generation(&cases.locked_joint);
        let options = GenerationOptions {
            outputs: vec![kernel],
            ..GenerationOptions::default()
        };
        let module = generate(&cases.model, &settings, &options, robot).map_err(|cause| {
            BenchError::Codegen {
                robot: robot.to_owned(),
                cause,
            }
        })?;
        let count = module
            .kernels
            .iter()
            .find(|k| k.kernel == kernel)
            .map(|k| k.ops)
            .unwrap_or_default();
        ops.push(count);
    }
    let mut scenes = Vec::new();
    let mut candidates = Vec::new();
    for candidate in subjects(Kernel::InverseDynamics, cases, pool)? {
        let scene = match candidate.implementation {
            Implementation::Generated => SceneKernel::Full,
            Implementation::ZeroGravity => SceneKernel::ZeroGravity,
            Implementation::Locked => SceneKernel::Locked,
            Implementation::AtRest => SceneKernel::AtRest,
            _ => continue,
        };
        scenes.push(scene);
        candidates.push(candidate);
    }
    for candidate in subjects(Kernel::GravityTorques, cases, pool)? {
        scenes.push(SceneKernel::GravityOnly);
        candidates.push(candidate);
    }
    let timings = time(&mut candidates, plan);
    let full = scenes.iter().position(|&s| s == SceneKernel::Full);
    let mut rows = Vec::new();
    for (scene, ops) in SceneKernel::ALL.into_iter().zip(ops) {
        if let Some(i) = scenes.iter().position(|&s| s == scene) {
            rows.push(SceneRow {
                scene,
                ops,
                relative_time: full.map_or(f64::NAN, |f| timings[i].ratio_to(&timings[f])),
                timing: timings[i].clone(),
            });
        }
    }
    Ok(RobotScenes {
        robot,
        dof: cases.model.dof(),
        rows,
    })
}
