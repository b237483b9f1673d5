//! The named scenarios: every experiment of the thesis's chapter 6, run on the generated
//! kernels, with its CSV tables, figures titled with the thesis's figure numbers, and its
//! measurements beside what the thesis reports.

use super::error::ScenarioError;
use super::outcome::Outcome;
use super::parameters::*;
use super::progress::WithProgress;
use rne_sim::{Integrator, Record, SimError};

use super::control::{elbow_pd_scenario, irb140_pd_scenario, lyapunov_scenario};
use super::floating_run::quadruped_in_space_scenario;
use super::free_runs::{
    damped_pendulum, double_pendulum, irb140_pendulum_scenario, open_loop_scenario, release_energy,
};
use super::friction_run::damped_by_friction_scenario;
/// How to run a scenario.
#[derive(Clone, Copy, Debug, Default)]
pub struct RunOptions {
    /// Show a progress bar per run on standard error (only when it is a terminal).
    pub progress: bool,
    /// What computes the dynamics of a scenario file's robot read from a file.
    pub engine: FileEngine,
}

/// What computes the dynamics of a robot read from a file (built-in robots run their compiled
/// modules).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FileEngine {
    /// The kernels compiled in memory (rne-jit); the interpreter, with a warning, on a
    /// processor the JIT does not support.
    #[default]
    Jit,
    /// The programs evaluated operation by operation.
    Interpreted,
}

/// Which experiment a scenario runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Experiment {
    OpenLoopFromZero,
    OpenLoopNearUpright,
    DoublePendulum,
    ReleaseEnergy,
    Damped,
    DampedByFriction,
    ElbowPd(usize),
    Irb140Pendulum,
    Irb140Pd(usize),
    Lyapunov,
    QuadrupedInSpace,
}

/// A named, built-in scenario: `rne simulate NAME`.
#[derive(Debug)]
pub struct Scenario {
    /// The name on the command line.
    pub name: &'static str,
    /// The thesis's figures or section it reproduces ("—" for a scenario beyond the thesis).
    pub figures: &'static str,
    /// One line about it.
    pub description: &'static str,
    experiment: Experiment,
}

/// Every built-in scenario, in the thesis's order, then those beyond the thesis.
pub static SCENARIOS: &[Scenario] = &[
    Scenario {
        name: "open-loop-from-zero",
        figures: "6.2",
        description: "planar elbow, open loop tau = g(pi, 0) from q = 0, 5 s",
        experiment: Experiment::OpenLoopFromZero,
    },
    Scenario {
        name: "open-loop-near-upright",
        figures: "6.3",
        description: "planar elbow, open loop tau = g(pi, 0) from q1 = pi - 0.01, 8 s",
        experiment: Experiment::OpenLoopNearUpright,
    },
    Scenario {
        name: "double-pendulum",
        figures: "6.4-6.7",
        description: "released from q = 0 and from q1 = 1e-6, 70 s, and their divergence",
        experiment: Experiment::DoublePendulum,
    },
    Scenario {
        name: "double-pendulum-energy",
        figures: "6.8",
        description: "kinetic, potential and total energy of the release; 1000 s symplectic",
        experiment: Experiment::ReleaseEnergy,
    },
    Scenario {
        name: "damped-pendulum",
        figures: "6.10",
        description: "damping Kd = (1.5, 1.5) from q = 0, 40 s, to (-pi/2, 0)",
        experiment: Experiment::Damped,
    },
    Scenario {
        name: "damped-pendulum-friction",
        figures: "6.10",
        description:
            "the damped run with Kd = 1.5 as viscous joint friction in the spec, against it",
        experiment: Experiment::DampedByFriction,
    },
    Scenario {
        name: "elbow-pd-1",
        figures: "6.12",
        description: "planar elbow PD, Kp = (22, 45), Kd = (15, 8), +-39.4 N m, set-point 1",
        experiment: Experiment::ElbowPd(0),
    },
    Scenario {
        name: "elbow-pd-2",
        figures: "6.13",
        description: "planar elbow PD, set-point 2",
        experiment: Experiment::ElbowPd(1),
    },
    Scenario {
        name: "elbow-pd-3",
        figures: "6.14",
        description: "planar elbow PD, set-point 3",
        experiment: Experiment::ElbowPd(2),
    },
    Scenario {
        name: "elbow-pd-4",
        figures: "6.15",
        description: "planar elbow PD, set-point 4",
        experiment: Experiment::ElbowPd(3),
    },
    Scenario {
        name: "irb140-pendulum",
        figures: "6.16-6.17",
        description: "IRB 140 joints 1-2 locked, link 3 released from q3 = 0, energy, 20 s",
        experiment: Experiment::Irb140Pendulum,
    },
    Scenario {
        name: "irb140-pd-1",
        figures: "6.19",
        description: "IRB 140 PD, Kp = (25, 18, 100), Kd = (27, 18, 20), set-point 1",
        experiment: Experiment::Irb140Pd(0),
    },
    Scenario {
        name: "irb140-pd-2",
        figures: "6.20",
        description: "IRB 140 PD, set-point 2",
        experiment: Experiment::Irb140Pd(1),
    },
    Scenario {
        name: "irb140-pd-3",
        figures: "6.21",
        description: "IRB 140 PD, set-point 3",
        experiment: Experiment::Irb140Pd(2),
    },
    Scenario {
        name: "lyapunov",
        figures: "section 6.4",
        description: "V = 1/2 qd' M qd + 1/2 e' Kp e along all seven PD runs",
        experiment: Experiment::Lyapunov,
    },
    Scenario {
        name: "quadruped-in-space",
        figures: "—",
        description: "floating quadruped in zero gravity swinging its legs, 10 s, Lie-group \
                      variational integrator: total momentum conserved",
        experiment: Experiment::QuadrupedInSpace,
    },
];

/// The built-in scenario called `name`.
pub fn find(name: &str) -> Option<&'static Scenario> {
    SCENARIOS.iter().find(|s| s.name == name)
}

impl Scenario {
    /// Runs the scenario: its simulations, figures and measurements.
    pub fn run(&self, options: &RunOptions) -> Result<Outcome, ScenarioError> {
        match self.experiment {
            Experiment::OpenLoopFromZero => open_loop_scenario(self.name, "6.2", 0.0, options),
            Experiment::OpenLoopNearUpright => {
                open_loop_scenario(self.name, "6.3", NEAR_UPRIGHT_Q1, options)
            }
            Experiment::DoublePendulum => double_pendulum(self.name, options),
            Experiment::ReleaseEnergy => release_energy(self.name, options),
            Experiment::Damped => damped_pendulum(self.name, options),
            Experiment::DampedByFriction => damped_by_friction_scenario(self.name, options),
            Experiment::ElbowPd(k) => elbow_pd_scenario(self.name, k, options),
            Experiment::Irb140Pendulum => irb140_pendulum_scenario(self.name, options),
            Experiment::Irb140Pd(k) => irb140_pd_scenario(self.name, k, options),
            Experiment::Lyapunov => lyapunov_scenario(self.name, options),
            Experiment::QuadrupedInSpace => quadruped_in_space_scenario(self.name),
        }
    }
}

/// Runs one simulation with a progress bar labelled `label`.
pub(crate) fn run_with<const N: usize, I: Integrator<N>>(
    options: &RunOptions,
    label: &str,
    integrator: &I,
    run: impl FnOnce(&WithProgress<'_, I>) -> Result<Record<N>, SimError>,
) -> Result<Record<N>, ScenarioError> {
    Ok(run(&WithProgress::new(integrator, label, options.progress))
        .map_err(SimError::in_run(label))?)
}

/// `(a, b, …)` with three decimals.
pub(crate) fn vector(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| format!("{x:.3}")).collect();
    format!("({})", items.join(", "))
}

/// `q1 a, q2 b, …` with each value formatted by `f`.
pub(crate) fn per_joint<T: Copy>(values: &[T], f: impl Fn(T) -> String) -> String {
    let items: Vec<String> = values
        .iter()
        .enumerate()
        .map(|(i, &v)| format!("q{} {}", i + 1, f(v)))
        .collect();
    items.join(", ")
}

/// A time in seconds, or what its absence means.
pub(crate) fn seconds(t: Option<f64>, absent: &str) -> String {
    t.map_or_else(|| absent.to_owned(), |t| format!("{t:.2} s"))
}
