//! Each built-in robot's implementations of the benchmarked kernels, and the models and
//! samples they are measured on.
//!
//! [`Cases`] holds, for one robot, the sampled states of every [`Case`] and the programs whose
//! double-double evaluation gives the exact values: the robot's own (also for the static scene,
//! at q̇ = 0, and for the `f32` kernels, at their rounded inputs), the robot without gravity and
//! the robot with its first joint locked. [`subjects`] lists the implementations of one kernel
//! as [`Subject`]s: the generated functions are called directly (statically dispatched and
//! inlinable, as user code calls them), the interpreted programs through
//! [`Interpreted::eval_in`], the reference through its allocation-free `*_into` methods.

use rne_codegen::{DoubleDouble, Kernel, Scene};
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::RobotModel;

use super::error::BenchError;
use super::implementation::{Case, Implementation};
use super::precision::exact;
use super::sample::Sample;
use super::subject::{Input, Returning, Subject, Writing};
use super::timing::Timed;
use crate::builtin::{BuiltinRobot, RobotSource};
use crate::interpreted::Interpreted;
use rne_reference::Reference;

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
            .map_err(|source| BenchError::Spec {
                robot: name.clone(),
                source,
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
            scene.apply(&model).map_err(|source| BenchError::Codegen {
                robot: name.clone(),
                source,
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
        let kernels = robot.kernels;
        let sample = Sample::draw(kernels.dof(), len, SEED, |q| {
            kernels.gravity_torques(q).unwrap_or_default()
        });
        let samples = [
            sample.clone(),
            sample.rounded_to_f32(),
            sample.clone(),
            sample.without_joint(0),
            sample.at_rest(),
        ];
        let programs = [
            Interpreted::new(&model),
            Interpreted::new(&zero_gravity),
            Interpreted::new(&locked),
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
    fn reference(&self) -> Result<Reference, BenchError> {
        Reference::try_new(&self.model.to_numeric()).map_err(|source| BenchError::Reference {
            robot: self.robot.name.to_owned(),
            source,
        })
    }
}

/// An implementation with its subject.
pub struct Candidate<'a> {
    /// The implementation.
    pub implementation: Implementation,
    /// Its calls.
    pub subject: Box<dyn Subject + 'a>,
}

impl Timed for Candidate<'_> {
    fn run(&mut self, calls: u64) {
        self.subject.run(calls);
    }
}

/// Collects the candidates of one kernel.
struct Candidates<'a> {
    cases: &'a Cases,
    pool: usize,
    list: Vec<Candidate<'a>>,
}

impl<'a> Candidates<'a> {
    fn new(cases: &'a Cases, pool: usize) -> Candidates<'a> {
        Candidates {
            cases,
            pool,
            list: Vec::new(),
        }
    }

    /// The inputs of `implementation`, with scalar `T` and N joints.
    fn inputs<T: rne_codegen::Real, const N: usize>(
        &self,
        implementation: Implementation,
    ) -> Result<Vec<Input<T, N>>, BenchError> {
        self.cases
            .sample(implementation.case())
            .inputs::<T, N>()
            .map_err(|source| BenchError::Dimension {
                robot: self.cases.robot.name.to_owned(),
                source,
            })
    }

    /// Adds a kernel that returns its result.
    fn add<T, const N: usize, R, F>(
        &mut self,
        implementation: Implementation,
        kernel: F,
    ) -> Result<(), BenchError>
    where
        T: rne_codegen::Real + 'a,
        R: super::subject::Output,
        F: FnMut(&Input<T, N>) -> R + 'a,
    {
        let inputs = self.inputs::<T, N>(implementation)?;
        self.list.push(Candidate {
            implementation,
            subject: Box::new(Returning::new(inputs, self.pool, kernel)),
        });
        Ok(())
    }

    /// Adds the interpreted program of `kernel`.
    fn interpreted<const N: usize>(&mut self, kernel: Kernel) -> Result<(), BenchError> {
        let program = self.cases.program(Case::Full);
        self.add::<f64, N, _, _>(Implementation::Interpreted, move |s| {
            program.eval_in::<f64>(kernel, &s.q, &s.qd, &s.qdd, &s.tau)
        })
    }

    /// Adds the numeric reference's `kernel`, if it has one. An argument error (impossible:
    /// the arrays have the robot's length) would leave NaN in the result.
    fn reference<const N: usize>(&mut self, kernel: Kernel) -> Result<(), BenchError> {
        let inputs = self.inputs::<f64, N>(Implementation::Reference)?;
        let mut reference = self.cases.reference()?;
        let pool = self.pool;
        fn write(result: Result<(), rne_reference::ReferenceError>, out: &mut [f64]) {
            if result.is_err() {
                out.fill(f64::NAN);
            }
        }
        let subject: Box<dyn Subject + 'a> = match kernel {
            Kernel::InverseDynamics => Box::new(Writing::new(
                inputs,
                pool,
                N,
                move |s: &Input<f64, N>, out: &mut [f64]| {
                    write(
                        reference.inverse_dynamics_into(&s.q, &s.qd, &s.qdd, out),
                        out,
                    )
                },
            )),
            Kernel::MassMatrix => Box::new(Writing::new(
                inputs,
                pool,
                N * N,
                move |s: &Input<f64, N>, out: &mut [f64]| {
                    write(reference.mass_matrix_into(&s.q, out), out)
                },
            )),
            Kernel::BiasTorques => Box::new(Writing::new(
                inputs,
                pool,
                N,
                move |s: &Input<f64, N>, out: &mut [f64]| {
                    write(reference.bias_torques_into(&s.q, &s.qd, out), out)
                },
            )),
            Kernel::ForwardDynamics => Box::new(Writing::new(
                inputs,
                pool,
                N,
                move |s: &Input<f64, N>, out: &mut [f64]| {
                    write(
                        reference.forward_dynamics_into(&s.q, &s.qd, &s.tau, out),
                        out,
                    )
                },
            )),
            Kernel::GravityTorques => Box::new(Writing::new(
                inputs,
                pool,
                N,
                move |s: &Input<f64, N>, out: &mut [f64]| {
                    write(reference.gravity_torques_into(&s.q, out), out)
                },
            )),
            // C(q, q̇), the energies and any later kernel have no reference implementation.
            _ => return Ok(()),
        };
        self.list.push(Candidate {
            implementation: Implementation::Reference,
            subject,
        });
        Ok(())
    }
}

/// The kernels of the kernel benchmark.
pub const BENCHED: [Kernel; 4] = [
    Kernel::InverseDynamics,
    Kernel::MassMatrix,
    Kernel::BiasTorques,
    Kernel::ForwardDynamics,
];

/// Defines, for one robot, the function listing its candidates for a kernel: its generated
/// module, then the variants of [`super::variants`], the interpreted programs and the
/// reference. Gravity and velocities do not enter M, so the mass matrix has no zero-gravity or
/// static-scene variant. `gravity_torques` lists the generated function alone (for the scene
/// savings).
macro_rules! robot_candidates {
    ($function:ident, $module:ident $(, $runtime:ident)?) => {
        fn $function(
            kernel: Kernel,
            cases: &Cases,
            pool: usize,
        ) -> Result<Vec<Candidate<'_>>, BenchError> {
            use super::variants::$module as v;
            use crate::generated::$module as g;
            use Implementation::*;
            const N: usize = g::NDOF;
            const L: usize = v::locked::NDOF;
            let mut c = Candidates::new(cases, pool);
            if g::JOINTS.get(1..) != Some(&v::locked::JOINTS[..])
                || cases.locked_joint != g::JOINTS[0]
            {
                return Err(BenchError::Variants {
                    robot: cases.robot.name.to_owned(),
                    problem: format!(
                        "the locked variant's joints {:?} are not the robot's {:?} without `{}`",
                        v::locked::JOINTS, g::JOINTS, cases.locked_joint
                    ),
                });
            }
            match kernel {
                Kernel::InverseDynamics => {
                    c.add::<f64, N, _, _>(Generated, |s| g::inverse_dynamics(&s.q, &s.qd, &s.qdd))?;
                    c.add::<f32, N, _, _>(Single, |s| v::single::inverse_dynamics(&s.q, &s.qd, &s.qdd))?;
                    $(
                        let p = v::$runtime::Params::default();
                        c.add::<f64, N, _, _>(RuntimeParameters, move |s| {
                            v::$runtime::inverse_dynamics(&p, &s.q, &s.qd, &s.qdd)
                        })?;
                    )?
                    c.add::<f64, N, _, _>(ZeroGravity, |s| {
                        v::zero_gravity::inverse_dynamics(&s.q, &s.qd, &s.qdd)
                    })?;
                    c.add::<f64, L, _, _>(Locked, |s| v::locked::inverse_dynamics(&s.q, &s.qd, &s.qdd))?;
                    c.add::<f64, N, _, _>(AtRest, |s| v::at_rest::inverse_dynamics(&s.q, &s.qd, &s.qdd))?;
                }
                Kernel::MassMatrix => {
                    c.add::<f64, N, _, _>(Generated, |s| g::mass_matrix(&s.q))?;
                    c.add::<f32, N, _, _>(Single, |s| v::single::mass_matrix(&s.q))?;
                    $(
                        let p = v::$runtime::Params::default();
                        c.add::<f64, N, _, _>(RuntimeParameters, move |s| v::$runtime::mass_matrix(&p, &s.q))?;
                    )?
                    c.add::<f64, L, _, _>(Locked, |s| v::locked::mass_matrix(&s.q))?;
                }
                Kernel::BiasTorques => {
                    c.add::<f64, N, _, _>(Generated, |s| g::bias_torques(&s.q, &s.qd))?;
                    c.add::<f32, N, _, _>(Single, |s| v::single::bias_torques(&s.q, &s.qd))?;
                    $(
                        let p = v::$runtime::Params::default();
                        c.add::<f64, N, _, _>(RuntimeParameters, move |s| {
                            v::$runtime::bias_torques(&p, &s.q, &s.qd)
                        })?;
                    )?
                    c.add::<f64, N, _, _>(ZeroGravity, |s| v::zero_gravity::bias_torques(&s.q, &s.qd))?;
                    c.add::<f64, L, _, _>(Locked, |s| v::locked::bias_torques(&s.q, &s.qd))?;
                    c.add::<f64, N, _, _>(AtRest, |s| v::at_rest::bias_torques(&s.q, &s.qd))?;
                }
                Kernel::ForwardDynamics => {
                    c.add::<f64, N, _, _>(Generated, |s| g::forward_dynamics(&s.q, &s.qd, &s.tau))?;
                    c.add::<f32, N, _, _>(Single, |s| v::single::forward_dynamics(&s.q, &s.qd, &s.tau))?;
                    $(
                        let p = v::$runtime::Params::default();
                        c.add::<f64, N, _, _>(RuntimeParameters, move |s| {
                            v::$runtime::forward_dynamics(&p, &s.q, &s.qd, &s.tau)
                        })?;
                    )?
                    c.add::<f64, N, _, _>(ZeroGravity, |s| {
                        v::zero_gravity::forward_dynamics(&s.q, &s.qd, &s.tau)
                    })?;
                    c.add::<f64, L, _, _>(Locked, |s| v::locked::forward_dynamics(&s.q, &s.qd, &s.tau))?;
                    c.add::<f64, N, _, _>(AtRest, |s| v::at_rest::forward_dynamics(&s.q, &s.qd, &s.tau))?;
                }
                Kernel::GravityTorques => {
                    c.add::<f64, N, _, _>(Generated, |s| g::gravity_torques(&s.q))?;
                    return Ok(c.list);
                }
                // C(q, q̇), the energies and any later kernel have no variants.
                _ => return Ok(c.list),
            }
            c.interpreted::<N>(kernel)?;
            c.reference::<N>(kernel)?;
            Ok(c.list)
        }
    };
}

robot_candidates!(planar_elbow, planar_elbow, runtime);
robot_candidates!(irb140_3dof, irb140_3dof, runtime);
robot_candidates!(puma560, puma560);
robot_candidates!(ur5, ur5);
robot_candidates!(panda, panda);
robot_candidates!(panda_arm, panda_arm);
robot_candidates!(irb140, irb140, runtime);

/// The implementations of `kernel` for the robot of `cases`, each timed on the first `pool`
/// states of its sample: those of [`BENCHED`] kernels, the generated `gravity_torques` alone,
/// nothing for the other kernels.
pub fn subjects(
    kernel: Kernel,
    cases: &Cases,
    pool: usize,
) -> Result<Vec<Candidate<'_>>, BenchError> {
    match cases.robot.name {
        "planar-elbow" => planar_elbow(kernel, cases, pool),
        "irb140-3dof" => irb140_3dof(kernel, cases, pool),
        "puma560" => puma560(kernel, cases, pool),
        "ur5" => ur5(kernel, cases, pool),
        "panda" => panda(kernel, cases, pool),
        "panda-arm" => panda_arm(kernel, cases, pool),
        "irb140" => irb140(kernel, cases, pool),
        other => Err(BenchError::Variants {
            robot: other.to_owned(),
            problem: "no generated variants: add the robot to bench/variants.rs and \
                      bench/robots.rs"
                .into(),
        }),
    }
}
