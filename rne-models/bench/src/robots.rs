//! Each built-in robot's implementations of the benchmarked kernels, and the models and
//! samples they are measured on.
//!
//! [`Cases`] holds, for one robot, the sampled states of every [`Case`] and the programs whose
//! double-double evaluation gives the exact values: the robot's own (also for the static scene,
//! at q̇ = 0, and for the `f32` kernels, at their rounded inputs), the robot without gravity and
//! the robot with its first joint locked. [`subjects`] lists the implementations of one kernel
//! as [`Calls`] of a [`Dynamics`]: the generated modules' `Model`s (statically dispatched and
//! inlined, as user code calls them), the interpreted programs and the reference (through its
//! allocation-free `*_into` methods) as [`RuntimeModel`]s.

use rne_codegen::{DoubleDouble, Dynamics, Kernel, OrderedReal};
use rne_codegen_core::Scene;
use rne_interpreted::{Interpreted, RuntimeModel, StateRef};
use rne_models::generated::{self, variants};
use rne_models::{BuiltinRobot, RobotSource};
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::RobotModel;

use crate::calls::{Calls, KernelCalls};
use crate::error::BenchError;
use crate::implementation::{Case, Implementation};
use crate::precision::exact;
use crate::sample::Sample;
use crate::timing::Timed;

/// Seed of every robot's sample.
pub const SEED: u64 = 0x5eed_be4c;

/// One robot's models and samples (see the module documentation).
pub struct Cases {
    /// The built-in robot.
    pub robot: &'static BuiltinRobot,
    /// Its model, with numeric parameters.
    pub model: RobotModel,
    /// The name of the joint locked in [`Case::Locked`] (the first).
    pub locked_joint: String,
    programs: [Interpreted; 3],
    samples: [Sample; 5],
}

impl Cases {
    /// Loads `robot`, builds its three programs and draws `len` states with [`SEED`].
    pub fn new(robot: &'static BuiltinRobot, len: usize) -> Result<Cases, BenchError> {
        let name = robot.name.to_owned();
        let model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .map_err(|cause| BenchError::Spec {
                robot: name.clone(),
                cause,
            })?;
        let locked_joint =
            model
                .joint_names()
                .first()
                .cloned()
                .ok_or_else(|| BenchError::Variants {
                    robot: name.clone(),
                    problem: "the robot has no joint to lock".into(),
                })?;
        let scene_model = |scene: Scene| {
            scene.apply(&model).map_err(|cause| BenchError::Codegen {
                robot: name.clone(),
                cause,
            })
        };
        let zero_gravity = scene_model(Scene {
            gravity: Some([0.0; 3]),
            ..Scene::default()
        })?;
        let locked = scene_model(Scene {
            lock: vec![(locked_joint.clone(), 0.0)],
            ..Scene::default()
        })?;
        let programs = [
            Interpreted::new(&model),
            Interpreted::new(&zero_gravity),
            Interpreted::new(&locked),
        ];
        // The programs are the generated kernels bit for bit, so g(q) is the generated one.
        let gravity = |q: &[f64]| {
            let state = StateRef {
                q,
                qd: &[],
                qdd: &[],
                tau: &[],
            };
            programs[0]
                .eval(Kernel::GravityTorques, state)
                .unwrap_or_default()
        };
        let sample = Sample::draw(model.dof(), len, SEED, gravity);
        let samples = [
            sample.clone(),
            sample.rounded_to_f32(),
            sample.clone(),
            sample.without_joint(0),
            sample.at_rest(),
        ];
        Ok(Cases {
            robot,
            model,
            locked_joint,
            programs,
            samples,
        })
    }

    /// The program whose double-double value is exact for `case`.
    pub fn program(&self, case: Case) -> &Interpreted {
        match case {
            Case::ZeroGravity => &self.programs[1],
            Case::Locked => &self.programs[2],
            Case::Full | Case::Single | Case::AtRest => &self.programs[0],
        }
    }

    /// The states of `case`.
    pub fn sample(&self, case: Case) -> &Sample {
        &self.samples[case.index()]
    }

    /// The exact value of `kernel` for `case` at state `k`.
    pub fn exact(&self, case: Case, kernel: Kernel, k: usize) -> Vec<DoubleDouble> {
        exact(self.program(case), kernel, self.sample(case).state(k))
    }

    /// The numeric reference of the robot.
    pub fn reference(&self) -> Result<Reference, BenchError> {
        Reference::try_new(&self.model.to_numeric()).map_err(|cause| BenchError::Reference {
            robot: self.robot.name.to_owned(),
            cause,
        })
    }
}

/// An implementation with its calls.
pub struct Candidate<'a> {
    /// The implementation.
    pub implementation: Implementation,
    /// Its calls.
    pub calls: Box<dyn KernelCalls + 'a>,
}

impl Timed for Candidate<'_> {
    fn run(&mut self, calls: u64) {
        self.calls.run(calls);
    }
}

/// The kernels of the kernel benchmark.
pub const BENCHED: [Kernel; 4] = [
    Kernel::InverseDynamics,
    Kernel::MassMatrix,
    Kernel::BiasTorques,
    Kernel::ForwardDynamics,
];

/// One robot's generated modules that the benchmark compares (see
/// [`rne_models::generated::variants`]): the default module, `f32`, zero gravity, the first
/// joint locked (L = N − 1 joints), the static scene and, for robots with named parameters,
/// runtime parameters.
pub struct Modules<G, S, Z, K, R, P> {
    /// The default module.
    pub generated: G,
    /// `scalar: f32`.
    pub single: S,
    /// `gravity: [0.0, 0.0, 0.0]`.
    pub zero_gravity: Z,
    /// The first joint locked at 0.
    pub locked: K,
    /// `at_rest: true`.
    pub at_rest: R,
    /// `parameters: runtime` with the spec's values, if the spec has named parameters.
    pub runtime: Option<P>,
}

/// Collects the candidates of one kernel.
struct Candidates<'a> {
    cases: &'a Cases,
    kernel: Kernel,
    pool: usize,
    list: Vec<Candidate<'a>>,
}

impl<'a> Candidates<'a> {
    /// Adds `model`'s kernel as `implementation`, if the model has the kernel.
    fn add<D, const N: usize>(
        &mut self,
        implementation: Implementation,
        model: D,
    ) -> Result<(), BenchError>
    where
        D: Dynamics<N, N> + 'a,
        D::Scalar: OrderedReal,
    {
        if !model.has(self.kernel) {
            return Ok(());
        }
        let inputs = self
            .cases
            .sample(implementation.case())
            .inputs::<D::Scalar, N>()
            .map_err(|cause| BenchError::Evaluation {
                robot: self.cases.robot.name.to_owned(),
                cause,
            })?;
        self.list.push(Candidate {
            implementation,
            calls: Box::new(Calls::new(model, self.kernel, inputs, self.pool)),
        });
        Ok(())
    }
}

/// Which implementations [`candidates`] makes.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Which {
    /// Every implementation of the kernel.
    All,
    /// The default generated module's alone.
    Generated,
}

/// The candidates of `kernel` for the robot of `cases` with its generated `modules`, in
/// [`Implementation::ALL`] order: for a kernel of [`BENCHED`] every implementation that has
/// it (gravity and velocities do not enter M, so the mass matrix has no zero-gravity or
/// static-scene variant), then the interpreted programs and the reference, or with
/// [`Which::Generated`] the generated function alone; for the gravity torques the generated
/// function alone (for the scene savings); nothing for the others.
pub fn candidates<'a, const N: usize, const L: usize, G, S, Z, K, R, P>(
    kernel: Kernel,
    cases: &'a Cases,
    pool: usize,
    modules: Modules<G, S, Z, K, R, P>,
    which: Which,
) -> Result<Vec<Candidate<'a>>, BenchError>
where
    G: Dynamics<N, N, Scalar = f64> + 'a,
    S: Dynamics<N, N, Scalar = f32> + 'a,
    Z: Dynamics<N, N, Scalar = f64> + 'a,
    K: Dynamics<L, L, Scalar = f64> + 'a,
    R: Dynamics<N, N, Scalar = f64> + 'a,
    P: Dynamics<N, N, Scalar = f64> + 'a,
{
    let robot = cases.robot.name.to_owned();
    if G::JOINTS.get(1..) != Some(K::JOINTS) || G::JOINTS.first() != Some(&&*cases.locked_joint) {
        return Err(BenchError::Variants {
            robot,
            problem: format!(
                "the locked variant's joints {:?} are not the robot's {:?} without `{}`",
                K::JOINTS,
                G::JOINTS,
                cases.locked_joint
            ),
        });
    }
    let mut c = Candidates {
        cases,
        kernel,
        pool,
        list: Vec::new(),
    };
    let benched = BENCHED.contains(&kernel);
    if kernel == Kernel::GravityTorques || (benched && which == Which::Generated) {
        c.add(Implementation::Generated, modules.generated)?;
        return Ok(c.list);
    }
    if !benched {
        return Ok(c.list);
    }
    c.add(Implementation::Generated, modules.generated)?;
    c.add(Implementation::Single, modules.single)?;
    if let Some(runtime) = modules.runtime {
        c.add(Implementation::RuntimeParameters, runtime)?;
    }
    c.add(Implementation::ZeroGravity, modules.zero_gravity)?;
    c.add(Implementation::Locked, modules.locked)?;
    c.add(Implementation::AtRest, modules.at_rest)?;
    let interpreted = RuntimeModel::<N>::interpreted(cases.program(Case::Full));
    let reference = cases.reference().and_then(|r| {
        RuntimeModel::<N>::reference(r).map_err(|cause| BenchError::Evaluation {
            robot: robot.clone(),
            cause,
        })
    });
    c.add(
        Implementation::Interpreted,
        interpreted.map_err(|cause| BenchError::Evaluation {
            robot: robot.clone(),
            cause,
        })?,
    )?;
    c.add(Implementation::Reference, reference?)?;
    Ok(c.list)
}

/// The [`Modules`] of the built-in robot whose modules are called `$module`, with runtime
/// parameters if `runtime` follows.
macro_rules! modules {
    ($module:ident) => {
        modules!(@ $module, None::<generated::$module::Model>)
    };
    ($module:ident, runtime) => {
        modules!(@ $module, Some(variants::$module::runtime::Model::default()))
    };
    (@ $module:ident, $runtime:expr) => {
        Modules {
            generated: generated::$module::Model,
            single: variants::$module::single::Model,
            zero_gravity: variants::$module::zero_gravity::Model,
            locked: variants::$module::locked::Model,
            at_rest: variants::$module::at_rest::Model,
            runtime: $runtime,
        }
    };
}

/// The implementations of `kernel` for the robot of `cases` ([`candidates`]), each timed on
/// the first `pool` states of its sample.
pub fn subjects(
    kernel: Kernel,
    cases: &Cases,
    pool: usize,
) -> Result<Vec<Candidate<'_>>, BenchError> {
    subjects_of(kernel, cases, pool, Which::All)
}

/// The default generated module's `kernel` for the robot of `cases`, timed on the first
/// `pool` states, if the kernel is one of [`BENCHED`] or the gravity torques.
pub fn generated_subject(
    kernel: Kernel,
    cases: &Cases,
    pool: usize,
) -> Result<Option<Candidate<'_>>, BenchError> {
    Ok(subjects_of(kernel, cases, pool, Which::Generated)?
        .into_iter()
        .next())
}

/// [`subjects`] or [`generated_subject`], as `which` says.
fn subjects_of(
    kernel: Kernel,
    cases: &Cases,
    pool: usize,
    which: Which,
) -> Result<Vec<Candidate<'_>>, BenchError> {
    use generated::{irb140, irb140_3dof, panda, panda_arm, planar_elbow, puma560, ur5};
    use variants as v;
    match cases.robot.name {
        "planar-elbow" => {
            candidates::<{ planar_elbow::NV }, { v::planar_elbow::locked::NV }, _, _, _, _, _, _>(
                kernel,
                cases,
                pool,
                modules!(planar_elbow, runtime),
                which,
            )
        }
        "irb140-3dof" => {
            candidates::<{ irb140_3dof::NV }, { v::irb140_3dof::locked::NV }, _, _, _, _, _, _>(
                kernel,
                cases,
                pool,
                modules!(irb140_3dof, runtime),
                which,
            )
        }
        "puma560" => candidates::<{ puma560::NV }, { v::puma560::locked::NV }, _, _, _, _, _, _>(
            kernel,
            cases,
            pool,
            modules!(puma560),
            which,
        ),
        "ur5" => candidates::<{ ur5::NV }, { v::ur5::locked::NV }, _, _, _, _, _, _>(
            kernel,
            cases,
            pool,
            modules!(ur5),
            which,
        ),
        "panda" => candidates::<{ panda::NV }, { v::panda::locked::NV }, _, _, _, _, _, _>(
            kernel,
            cases,
            pool,
            modules!(panda),
            which,
        ),
        "panda-arm" => {
            candidates::<{ panda_arm::NV }, { v::panda_arm::locked::NV }, _, _, _, _, _, _>(
                kernel,
                cases,
                pool,
                modules!(panda_arm),
                which,
            )
        }
        "irb140" => candidates::<{ irb140::NV }, { v::irb140::locked::NV }, _, _, _, _, _, _>(
            kernel,
            cases,
            pool,
            modules!(irb140, runtime),
            which,
        ),
        other => Err(BenchError::Variants {
            robot: other.to_owned(),
            problem: "no generated variants: add the robot to rne_models::generated::variants \
                      and to bench/src/robots.rs"
                .into(),
        }),
    }
}
