//! `rne bench MODEL`: one robot, loaded at run time, timed kernel by kernel on every engine
//! that has its kernels — the JIT (rne-jit), the interpreter, the compiled module of a
//! built-in robot and, through the peer scripts, Pinocchio and Pinocchio + CppADCodeGen —
//! with each engine's largest error against the numeric reference and the time each side
//! takes to obtain its kernels (rne: generation and JIT; CppADCodeGen: taping, C source and
//! gcc).
//!
//! The engines of one kernel are timed together by the interleaved method of
//! [`crate::timing`], on the same seeded states, so their ratios hold within the run.

mod calls;
mod peers;

use rne_codegen::Kernel;
use rne_codegen_core::{GenerationOptions, Scene};
use rne_interpreted::agreement::{check_kernels, random_states, Engine as Agreement};
use rne_interpreted::{Interpreted, JointState};
use rne_jit::{JitModel, Tier};
use rne_models::BuiltinRobot;
use rne_symbolic::RobotModel;

use crate::error::BenchError;
use crate::timing::{time_interleaved, Plan, Timed};
use calls::WithCompiled;
pub use peers::{PeerFigures, PeerScripts};

/// The engines `rne bench MODEL` times.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Engine {
    /// The programs compiled in memory (rne-jit).
    Jit,
    /// The macro's compiled module (built-in robots only).
    Compiled,
    /// The programs evaluated operation by operation.
    Interpreted,
    /// Plain Pinocchio (peer script).
    Pinocchio,
    /// Pinocchio's CppADCodeGen code (peer script).
    CppAdCodeGen,
}

impl Engine {
    /// The engine's name in reports and JSON.
    pub fn label(self) -> &'static str {
        match self {
            Engine::Jit => "jit",
            Engine::Compiled => "compiled",
            Engine::Interpreted => "interpreted",
            Engine::Pinocchio => "pinocchio",
            Engine::CppAdCodeGen => "pinocchio+cppadcodegen",
        }
    }
}

/// The kernels `rne bench MODEL` times unless told otherwise: the dynamics and their
/// derivatives.
pub const DEFAULT_KERNELS: [Kernel; 10] = [
    Kernel::InverseDynamics,
    Kernel::MassMatrix,
    Kernel::CoriolisMatrix,
    Kernel::GravityTorques,
    Kernel::BiasTorques,
    Kernel::ForwardDynamics,
    Kernel::MassMatrixInverse,
    Kernel::KineticEnergy,
    Kernel::InverseDynamicsDerivatives,
    Kernel::ForwardDynamicsDerivatives,
];

/// What to time.
#[derive(Clone)]
pub struct RobotBenchSettings {
    /// The engines of rne to time (the peers' come from [`RobotBenchSettings::peers`]).
    pub engines: Vec<Engine>,
    /// The kernels to time; the JIT compiles every kernel of `options` either way.
    pub kernels: Vec<Kernel>,
    /// The scene the JIT and the interpreter are built with.
    pub scene: Scene,
    /// The generation options the JIT is built with (their `outputs` are the kernels whose
    /// time to obtain is reported).
    pub options: GenerationOptions,
    /// Seeded states: timing pool and error check.
    pub states: usize,
    /// The timing plan.
    pub plan: Plan,
    /// How hard the JIT works on the code.
    pub tier: Tier,
    /// The built-in robot, whose compiled module is then timed too.
    pub builtin: Option<&'static BuiltinRobot>,
    /// The peer scripts and the robot's URDF, when Pinocchio is timed too.
    pub peers: Option<PeerScripts>,
}

/// One kernel on one engine.
#[derive(Clone, Debug, PartialEq)]
pub struct KernelTiming {
    /// The kernel.
    pub kernel: Kernel,
    /// The engine.
    pub engine: Engine,
    /// Median ns per call.
    pub ns: f64,
    /// Interquartile range of ns per call (rne's engines; the peers report medians only).
    pub quartiles: Option<(f64, f64)>,
    /// Largest normwise relative error against the numeric reference over the states (rne's
    /// engines).
    pub max_rel_error: Option<f64>,
}

/// The time each side took to obtain its kernels, in seconds.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeToKernels {
    /// rne: symbolic recursion and optimisation of every kernel of the scene.
    pub generation_s: f64,
    /// rne: Cranelift's compilation of them.
    pub compile_s: f64,
    /// Their sum.
    pub rne_jit_s: f64,
    /// The number of kernels rne generated and compiled.
    pub rne_kernels: usize,
    /// Peak resident memory of the process after the JIT (Linux's VmHWM), in bytes.
    pub peak_memory_bytes: Option<u64>,
    /// Pinocchio + CppADCodeGen: taping, C source and gcc of its six functions.
    pub cppadcodegen_s: Option<f64>,
}

/// The report of `rne bench MODEL`.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotBench {
    /// The robot.
    pub robot: String,
    /// NQ and NV.
    pub nq: usize,
    /// NV.
    pub nv: usize,
    /// Whether the JIT fused multiply-adds (the processor has FMA and the options asked).
    pub fused: bool,
    /// The JIT's tier.
    pub tier: Tier,
    /// Time to obtain the kernels.
    pub time_to_kernels: TimeToKernels,
    /// Every kernel on every engine that has it.
    pub kernels: Vec<KernelTiming>,
}

/// Benchmarks `model` (from `source`) by `settings`; `progress` hears each step.
pub fn bench_robot(
    model: &RobotModel,
    source: &str,
    settings: &RobotBenchSettings,
    progress: &mut dyn FnMut(&str),
) -> Result<RobotBench, BenchError> {
    let failed = |e: rne_jit::JitError| BenchError::Variants {
        robot: source.to_owned(),
        problem: e.to_string(),
    };
    progress("generating and compiling the kernels (JIT)");
    let jit = JitModel::compile_at(
        model,
        &settings.scene,
        &settings.options,
        source,
        settings.tier,
    )
    .map_err(failed)?;
    let peak_memory_bytes = peak_memory();
    let timings = jit.timings();
    let states = random_states(jit.nq(), jit.nv(), settings.states, 0xbe4c);
    let interpreted = settings
        .engines
        .contains(&Engine::Interpreted)
        .then(|| Interpreted::with_kernels(&jit.programs().model, &settings.kernels));
    let bench = Bench {
        source,
        settings,
        jit: &jit,
        interpreted: interpreted.as_ref(),
        states: &states,
    };
    let mut kernels = Vec::new();
    for &kernel in &settings.kernels {
        if !jit.has(kernel) {
            continue;
        }
        progress(&format!("timing {kernel}"));
        kernels.extend(bench.time_kernel(kernel)?);
    }
    let mut time_to_kernels = TimeToKernels {
        generation_s: timings.generation.as_secs_f64(),
        compile_s: timings.compilation.as_secs_f64(),
        rne_jit_s: (timings.generation + timings.compilation).as_secs_f64(),
        rne_kernels: jit.kernels().len(),
        peak_memory_bytes,
        cppadcodegen_s: None,
    };
    if let Some(peers) = &settings.peers {
        progress("timing Pinocchio and generating its CppADCodeGen code (minutes)");
        let figures = peers.run(source)?;
        time_to_kernels.cppadcodegen_s = figures.cppadcodegen_s();
        kernels.extend(figures.timings(&settings.kernels));
    }
    Ok(RobotBench {
        robot: jit.robot().to_owned(),
        nq: jit.nq(),
        nv: jit.nv(),
        fused: jit.fused(),
        tier: settings.tier,
        time_to_kernels,
        kernels,
    })
}

/// What the timing of every kernel shares: the robot's engines and the seeded states.
struct Bench<'a> {
    source: &'a str,
    settings: &'a RobotBenchSettings,
    jit: &'a JitModel,
    interpreted: Option<&'a Interpreted>,
    states: &'a [JointState],
}

impl Bench<'_> {
    /// The largest error of `engine`'s `kernel` against the reference over the states.
    fn error(&self, engine: &dyn Agreement, kernel: Kernel) -> Result<f64, rne_interpreted::Error> {
        let agreement = check_kernels(
            &self.jit.programs().model,
            self.settings.scene.friction,
            engine,
            &[kernel],
            self.states,
        )?;
        Ok(agreement.first().map_or(f64::NAN, |a| a.max_error))
    }

    /// An engine's failure to evaluate a kernel, as the bench reports it.
    fn evaluation(&self, cause: rne_interpreted::Error) -> BenchError {
        BenchError::Evaluation {
            robot: self.source.to_owned(),
            cause,
        }
    }

    /// `kernel` timed on every engine of the settings that has it, in the same rounds, each
    /// with its largest error.
    fn time_kernel(&self, kernel: Kernel) -> Result<Vec<KernelTiming>, BenchError> {
        let settings = self.settings;
        let states = self.states;
        let mut engines = Vec::new();
        let mut subjects: Vec<Box<dyn Timed + '_>> = Vec::new();
        let mut errors = Vec::new();
        if settings.engines.contains(&Engine::Jit) {
            engines.push(Engine::Jit);
            subjects.push(calls::jit(self.jit, kernel, states));
            errors.push(
                self.error(self.jit, kernel)
                    .map_err(|e| self.evaluation(e))?,
            );
        }
        if let Some(programs) = self.interpreted.filter(|i| i.has(kernel)) {
            engines.push(Engine::Interpreted);
            subjects.push(calls::interpreted(programs, kernel, states));
            errors.push(
                self.error(programs, kernel)
                    .map_err(|e| self.evaluation(e))?,
            );
        }
        let mut times = match settings.builtin {
            Some(robot) if settings.engines.contains(&Engine::Compiled) => {
                // The default module has the dynamics; the URDF robots' `control` module the
                // derivatives and M⁻¹.
                let run = robot.visit_having(
                    kernel,
                    WithCompiled {
                        kernel,
                        others: &mut subjects,
                        states,
                        plan: &settings.plan,
                        error: &|engine| self.error(engine, kernel),
                    },
                );
                let mut times = run.others;
                if let Some((time, e)) = run.compiled {
                    engines.push(Engine::Compiled);
                    errors.push(e.map_err(|e| self.evaluation(e))?);
                    times.push(time);
                }
                times
            }
            _ => {
                let mut timed: Vec<&mut dyn Timed> = subjects
                    .iter_mut()
                    .map(|c| &mut **c as &mut dyn Timed)
                    .collect();
                time_interleaved(&mut timed, &settings.plan)
            }
        };
        let timings = engines.into_iter().zip(times.drain(..)).zip(errors);
        Ok(timings
            .map(|((engine, time), error)| KernelTiming {
                kernel,
                engine,
                ns: time.median(),
                quartiles: Some(time.quartiles()),
                max_rel_error: Some(error),
            })
            .collect())
    }
}

/// The process's peak resident memory (VmHWM of /proc/self/status), where Linux reports it.
fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}
