//! Every kernel the generator can emit, for one robot on one base, against the numeric
//! reference: each built on its own (so that a failure is the kernel's own), evaluated as the
//! interpreted program the macro emits, and compared by
//! [`rne_interpreted::agreement::check_kernels`]. Pinocchio has no values for most of them;
//! the reference, which shares no code with the symbolic path, has them all.

use std::panic::{catch_unwind, AssertUnwindSafe};

use rne_codegen::Kernel;
use rne_interpreted::agreement::{check_kernels, random_states};
use rne_interpreted::Interpreted;
use rne_symbolic::RobotModel;

/// What became of one kernel.
#[derive(Clone, Debug, PartialEq)]
pub enum KernelOutcome {
    /// Generated and compared: its largest relative error.
    Compared(f64),
    /// Undefined for this robot (forward dynamics of a joint that moves no mass): why.
    Undefined(String),
    /// Generation or evaluation failed: how. Never expected; a bug to report.
    Failed(String),
}

/// One kernel's outcome.
#[derive(Clone, Debug, PartialEq)]
pub struct KernelCheck {
    /// The kernel.
    pub kernel: Kernel,
    /// What became of it.
    pub outcome: KernelOutcome,
}

/// Every kernel of [`Kernel::ALL`] for `model` (its base and mimic mode set), at `states`
/// seeded random states.
pub fn check_every_kernel(model: &RobotModel, states: usize, seed: u64) -> Vec<KernelCheck> {
    let layout = model.state_layout();
    let states = random_states(layout.nq(), layout.nv(), states, seed);
    let invertible = model.check_mass_matrix_invertible();
    Kernel::ALL
        .iter()
        .map(|&kernel| {
            let outcome = match &invertible {
                Err(joint) if kernel.inverts_mass_matrix() => {
                    KernelOutcome::Undefined(joint.to_string())
                }
                _ => check_one(model, kernel, &states),
            };
            KernelCheck { kernel, outcome }
        })
        .collect()
}

fn check_one(
    model: &RobotModel,
    kernel: Kernel,
    states: &[rne_interpreted::JointState],
) -> KernelOutcome {
    // The base regressor is checked through the base parameters and the other way round.
    let base = [Kernel::BaseRegressor, Kernel::BaseParameters];
    let kernels: &[Kernel] = if base.contains(&kernel) {
        &base
    } else {
        &[kernel]
    };
    let built = catch_unwind(AssertUnwindSafe(|| {
        Interpreted::with_kernels(model, kernels)
    }));
    let interpreted = match built {
        Ok(interpreted) => interpreted,
        Err(panic) => return KernelOutcome::Failed(format!("generation: {}", message(&*panic))),
    };
    match check_kernels(model, false, &interpreted, &[kernel], states) {
        Ok(agreement) => KernelOutcome::Compared(agreement.first().map_or(0.0, |a| a.max_error)),
        Err(e) => KernelOutcome::Failed(format!("evaluation: {e}")),
    }
}

/// A panic's message.
fn message(panic: &(dyn std::any::Any + Send)) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_owned())
}

/// The kernels of one robot and base in short.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct KernelSummary<'a> {
    /// The largest error of a compared kernel, and that kernel.
    pub worst: Option<(f64, Kernel)>,
    /// Every kernel that failed, and how.
    pub failed: Vec<(Kernel, &'a str)>,
}

/// The worst compared kernel and every kernel that failed.
pub fn summary(checks: &[KernelCheck]) -> KernelSummary<'_> {
    let mut summary = KernelSummary::default();
    for check in checks {
        match &check.outcome {
            KernelOutcome::Compared(e) => {
                let e = if e.is_nan() { f64::INFINITY } else { *e };
                if summary.worst.map_or(true, |(w, _)| e > w) {
                    summary.worst = Some((e, check.kernel));
                }
            }
            KernelOutcome::Failed(why) => summary.failed.push((check.kernel, why.as_str())),
            KernelOutcome::Undefined(_) => {}
        }
    }
    summary
}
