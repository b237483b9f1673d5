//! One built-in robot in `rne verify`: every kernel generated and compiled in memory (the JIT,
//! the programs the macro emits), the JIT's kernels and the compiled module's against the
//! numeric reference at the same seeded states, each against its own tolerance.

use std::time::Duration;

use rne_codegen::{Kernel, Scene};
use rne_interpreted::agreement::{check_kernels, random_states, KernelAgreement};
use rne_jit::JitModel;
use rne_models::{BuiltinRobot, RobotSource};
use rne_symbolic::spec::LoadOptions;

use super::compiled::CompiledErrors;
use super::tolerance;
use crate::CliError;

/// One kernel of one robot: its size and its largest errors against the reference.
#[derive(Clone, Debug, PartialEq)]
pub struct KernelRow {
    /// The kernel.
    pub kernel: Kernel,
    /// Operations of its optimised program.
    pub operations: usize,
    /// Largest error of the JIT's kernel (NaN when the JIT has none: a failure).
    pub jit: f64,
    /// Largest error of the built-in compiled module's kernel, when the module has it.
    pub compiled: Option<f64>,
    /// The largest error accepted.
    pub tolerance: f64,
}

impl KernelRow {
    /// Whether every error is within the tolerance (NaN is not).
    pub fn passes(&self) -> bool {
        self.jit <= self.tolerance && self.compiled.map_or(true, |e| e <= self.tolerance)
    }
}

/// What `rne verify` found for one robot.
#[derive(Clone, Debug)]
pub struct RobotCheck {
    /// Number of joint variables.
    pub ndof: usize,
    /// From the robot model to the optimised programs of every kernel.
    pub generation: Duration,
    /// The programs to machine code (Cranelift).
    pub compilation: Duration,
    /// Every kernel of [`Kernel::ALL`], in that order.
    pub rows: Vec<KernelRow>,
}

/// Checks every kernel of `robot` at `samples` states seeded with `seed`, each against its own
/// tolerance, or against `tolerance` when given.
pub fn check(
    robot: &'static BuiltinRobot,
    samples: usize,
    seed: u64,
    tolerance: Option<f64>,
) -> Result<RobotCheck, CliError> {
    let model = RobotSource::Builtin(robot).load(&LoadOptions::default())?;
    let scene = Scene {
        outputs: Kernel::ALL.to_vec(),
        ..Scene::default()
    };
    let jit = JitModel::compile(&model, &scene, robot.file)?;
    let programs = jit.programs();
    let states = random_states(jit.nq(), jit.nv(), samples, seed);
    let jit_errors = check_kernels(&programs.model, false, &jit, &Kernel::ALL, &states)?;
    let compiled_errors = robot.visit(CompiledErrors {
        model: &programs.model,
        states: &states,
    })?;
    let operations = |kernel| {
        programs
            .kernels
            .iter()
            .find(|k| k.kernel == kernel)
            .map_or(0, |k| k.report.ops.total())
    };
    Ok(RobotCheck {
        ndof: programs.ndof,
        generation: jit.timings().generation,
        compilation: jit.timings().compilation,
        rows: rows(&jit_errors, &compiled_errors, operations, tolerance),
    })
}

/// One row per kernel of [`Kernel::ALL`]: its errors from `jit` and `compiled` (a kernel
/// missing from `jit` gets NaN, and fails), its operations, and its tolerance (`tolerance`
/// for every kernel when given).
pub fn rows(
    jit: &[KernelAgreement],
    compiled: &[KernelAgreement],
    operations: impl Fn(Kernel) -> usize,
    tolerance: Option<f64>,
) -> Vec<KernelRow> {
    let error = |agreements: &[KernelAgreement], kernel| {
        agreements
            .iter()
            .find(|a| a.kernel == kernel)
            .map(|a| a.max_error)
    };
    Kernel::ALL
        .iter()
        .map(|&kernel| KernelRow {
            kernel,
            operations: operations(kernel),
            jit: error(jit, kernel).unwrap_or(f64::NAN),
            compiled: error(compiled, kernel),
            tolerance: tolerance.unwrap_or_else(|| tolerance::of(kernel)),
        })
        .collect()
}
