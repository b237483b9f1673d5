//! The stress cases, one per module: each measures, returns typed results for the tests, and
//! writes its section of the report.

pub mod chaos;
pub mod compiled;
pub mod conditioning;
pub mod joint_angle;
pub mod joint_count;
pub mod link_length;
pub mod mass_ratio;
pub mod non_finite;
pub mod velocity;

use rand_chacha::ChaCha8Rng;
use rne_codegen::Kernel;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::RobotModel;

use crate::chain::Chain;
use crate::error::StressError;
use crate::measure::ErrorsByKernel;
use crate::states::uniform;
use crate::sweep::{torque_for, Sweep};
use rne_figures::{sci, ulps, Table};
use rne_interpreted::JointState;

use crate::probe::Probe;
use rne_models::{builtin, RobotSource};

/// The model of the built-in robot `name`.
pub fn builtin_model(name: &str) -> Result<RobotModel, StressError> {
    let robot = builtin(name).ok_or_else(|| StressError::MissingRobot(name.to_owned()))?;
    RobotSource::Builtin(robot)
        .load(&LoadOptions::default())
        .map_err(|cause| StressError::Robot {
            robot: name.to_owned(),
            cause,
        })
}

/// The model of a stress robot.
pub fn chain_model(chain: &Chain) -> Result<RobotModel, StressError> {
    chain.model().map_err(|cause| StressError::Robot {
        robot: chain.name.clone(),
        cause,
    })
}

/// The symbol of a kernel's output in the tables.
pub fn symbol(kernel: Kernel) -> &'static str {
    match kernel {
        Kernel::InverseDynamics => "τ",
        Kernel::MassMatrix => "M",
        Kernel::CoriolisMatrix => "C",
        Kernel::GravityTorques => "g",
        Kernel::BiasTorques => "bias",
        Kernel::ForwardDynamics => "q̈",
        Kernel::KineticEnergy => "T",
        Kernel::PotentialEnergy => "V",
        other => other.name(),
    }
}

/// `samples` seeded states with |q| ≤ `q`, |q̇| ≤ `qd`, |q̈| ≤ `qdd`, and τ = τ(q, q̇, q̈) as
/// the `f64` inverse-dynamics kernel computes it: forward dynamics is then asked for
/// accelerations of the size of `qdd`, whatever the masses and lengths of the robot (random
/// torques would make a light link's acceleration swamp every other one).
pub fn driven_states(
    probe: &Probe,
    rng: &mut ChaCha8Rng,
    samples: usize,
    (q, qd, qdd): (f64, f64, f64),
) -> Vec<JointState> {
    let n = probe.dof();
    (0..samples)
        .map(|_| {
            let mut state = JointState {
                q: uniform(rng, n, q),
                qd: uniform(rng, n, qd),
                qdd: uniform(rng, n, qdd),
                tau: Vec::new(),
            };
            state.tau = torque_for(probe, &state).unwrap_or_default();
            state
        })
        .collect()
}

/// Column headings `τ max / median`, … for `kernels`.
pub fn kernel_headings(kernels: &[Kernel]) -> Vec<String> {
    kernels
        .iter()
        .map(|&k| format!("{} max / median", symbol(k)))
        .collect()
}

/// The cells `1.2e-16 / 3.4e-17`, … of `kernels` in `errors`.
pub fn kernel_cells(errors: &ErrorsByKernel, kernels: &[Kernel]) -> Vec<String> {
    kernels
        .iter()
        .map(|&k| format!("{} / {}", sci(errors.max(k)), sci(errors.median(k))))
        .collect()
}

/// A table whose first columns are `first` and then one column per kernel.
pub fn kernel_table(caption: String, first: &[&str], kernels: &[Kernel]) -> Table {
    let mut table = Table::new(caption, first);
    table.header.extend(kernel_headings(kernels));
    table
}

/// The largest of `values` (NaN if any is NaN, 0 if there are none).
pub fn largest(values: impl IntoIterator<Item = f64>) -> f64 {
    values.into_iter().fold(0.0, |m: f64, x| {
        if x.is_nan() || m.is_nan() {
            f64::NAN
        } else {
            m.max(x)
        }
    })
}

/// The headings of [`sweep_cells`].
pub const SWEEP_HEADINGS: [&str; 5] = [
    "cond(M) median",
    "scaled cond max",
    "κ median",
    "q̈ error / (ε κ κₛ) max",
    "τ max ulps",
];

/// The conditioning of a sweep's states and the largest τ error in ulps: cond(M), the
/// scaled condition number κₛ, the cancellation κ of forward dynamics' right-hand side, and
/// forward dynamics' error over ε·max(κ, 1)·κₛ.
pub fn sweep_cells(sweep: &Sweep) -> Vec<String> {
    vec![
        sci(sweep.condition.median),
        sci(sweep.scaled_condition.max),
        sci(sweep.cancellation.median),
        format!("{:.2}", sweep.fd_over_estimate.max),
        ulps(sweep.errors.max_ulps(Kernel::InverseDynamics)),
    ]
}

/// A table whose columns are `first`, [`SWEEP_HEADINGS`] and one per kernel.
pub fn sweep_table(caption: String, first: &str, kernels: &[Kernel]) -> Table {
    let mut headings = vec![first];
    headings.extend(SWEEP_HEADINGS);
    kernel_table(caption, &headings, kernels)
}

/// A row of a [`sweep_table`].
pub fn sweep_row(first: String, sweep: &Sweep, kernels: &[Kernel]) -> Vec<String> {
    let mut row = vec![first];
    row.extend(sweep_cells(sweep));
    row.extend(kernel_cells(&sweep.errors, kernels));
    row
}
