//! One built-in robot in `rne verify`: every kernel generated and compiled in memory (the JIT,
//! the programs the macro emits), the JIT's kernels and the compiled module's against the
//! numeric reference at the same seeded states, each against its own tolerance.

use std::time::Duration;

use rne_codegen::Kernel;
use rne_codegen_core::{GenerationOptions, Scene};
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
    let options = GenerationOptions {
        outputs: Kernel::ALL.to_vec(),
        ..GenerationOptions::default()
    };
    let jit = JitModel::compile(&model, &Scene::default(), &options, robot.file)?;
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

#[cfg(test)]
mod tests {
    use super::*;
    use rne_interpreted::agreement::Engine;
    use rne_interpreted::{Error, StateRef};

    /// The JIT's kernels with one of them off by a relative `by` in every entry: a broken
    /// kernel.
    struct Perturbed<'a> {
        jit: &'a JitModel,
        kernel: Kernel,
        by: f64,
    }

    impl Engine for Perturbed<'_> {
        fn has(&self, kernel: Kernel) -> bool {
            Engine::has(self.jit, kernel)
        }

        fn evaluate(&self, kernel: Kernel, state: StateRef<'_>) -> Result<Vec<f64>, Error> {
            let mut values = Engine::evaluate(self.jit, kernel, state)?;
            if kernel == self.kernel {
                values.iter_mut().for_each(|v| *v *= 1.0 + self.by);
            }
            Ok(values)
        }

        fn base_parameters(&self, standard: &[f64]) -> Result<Vec<f64>, Error> {
            Engine::base_parameters(self.jit, standard)
        }

        fn frames(&self) -> Vec<String> {
            Engine::frames(self.jit)
        }
    }

    /// The rows of the planar elbow's kernels with `kernel` perturbed by `by`.
    fn rows_with(kernel: Kernel, by: f64) -> Vec<KernelRow> {
        let robot = rne_models::builtin("planar-elbow").unwrap();
        let model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .unwrap();
        let options = GenerationOptions {
            outputs: Kernel::ALL.to_vec(),
            ..GenerationOptions::default()
        };
        let jit = JitModel::compile(&model, &Scene::default(), &options, robot.file).unwrap();
        let states = random_states(jit.nq(), jit.nv(), 50, 7);
        let engine = Perturbed {
            jit: &jit,
            kernel,
            by,
        };
        let model = &jit.programs().model;
        let errors = check_kernels(model, false, &engine, &Kernel::ALL, &states).unwrap();
        rows(&errors, &[], |_| 0, None)
    }

    #[test]
    fn a_kernel_off_by_a_little_more_than_its_tolerance_fails_and_only_it() {
        for kernel in [
            Kernel::InverseDynamics,
            Kernel::FrameJacobians,
            Kernel::BaseRegressor,
        ] {
            let by = 10.0 * tolerance::of(kernel);
            let rows = rows_with(kernel, by);
            assert_eq!(rows.len(), Kernel::ALL.len());
            // The base regressor and base parameters are checked together, as Y_b π_b.
            let base = [Kernel::BaseRegressor, Kernel::BaseParameters];
            let shares = |k| k == kernel || (base.contains(&k) && base.contains(&kernel));
            for row in &rows {
                assert_eq!(
                    row.passes(),
                    !shares(row.kernel),
                    "{kernel} perturbed: {row:?}"
                );
            }
        }
    }

    #[test]
    fn a_kernel_within_its_tolerance_passes() {
        let rows = rows_with(Kernel::MassMatrixInverse, 1e-15);
        assert!(rows.iter().all(KernelRow::passes), "{rows:?}");
    }

    #[test]
    fn a_missing_or_nan_error_fails() {
        let agreement = |kernel, max_error| KernelAgreement { kernel, max_error };
        let jit = vec![agreement(Kernel::MassMatrix, f64::NAN)];
        let compiled = vec![agreement(Kernel::InverseDynamics, 0.0)];
        let rows = rows(&jit, &compiled, |_| 1, Some(1.0));
        let row = |k| rows.iter().find(|r| r.kernel == k).unwrap();
        assert!(!row(Kernel::MassMatrix).passes(), "NaN error");
        assert!(
            !row(Kernel::InverseDynamics).passes(),
            "no JIT kernel, though the compiled one agrees"
        );
        assert_eq!(row(Kernel::InverseDynamics).compiled, Some(0.0));
        assert!(
            rows.iter().all(|r| r.tolerance == 1.0),
            "--tolerance for all"
        );
    }
}
