//! `rne bench`: run time against error, for the kernels and for the integrators (docs/design.md
//! §5).
//!
//! The studies, each written as markdown tables (and work-precision charts) by [`Report`]:
//! - **Kernels** ([`kernels`]): for every built-in robot and for inverse dynamics, mass
//!   matrix, bias torques and forward dynamics, every implementation rne offers
//!   ([`Implementation`]: generated `f64`, `f32`, runtime parameters, the scene variants of
//!   [`rne_models::generated::variants`], the interpreted programs, the numeric reference), timed per call and measured
//!   for error against the double-double value of the same model ([`precision`]);
//! - **Control kernels** ([`control`]): the derivatives, M⁻¹, frame Jacobians, J̇q̇ and
//!   regressor of the URDF robots, timed and measured for error likewise, which the comparison
//!   with Pinocchio ([`pinocchio`]) sets beside its algorithms and generated code, timing
//!   rne's side again right after each run of Pinocchio's scripts ([`beside`]);
//! - **Scene savings** ([`scenes`]): operations and time of the inverse dynamics against the
//!   gravity torques and the zero-gravity, locked-joint and static-scene variants;
//! - **Integrators** ([`integrators`]): time to solution against final-state error and energy
//!   drift for RK4, Dormand–Prince and Gauss–Legendre on the double pendulum and the IRB 140
//!   joint-3 pendulum.
//!
//! Times come from the interleaved-batch harness of [`timing`]; on a shared machine the
//! absolute times move with the load, the ratios measured within one run much less.

#![deny(missing_docs)]

pub mod beside;
pub mod calls;
pub mod control;
pub mod error;
pub mod implementation;
pub mod integrators;
pub mod kernels;
pub mod pinocchio;
pub mod precision;
pub mod report;
pub mod robot;
pub mod robots;
pub mod sample;
pub mod scenes;
pub mod timing;

use std::time::{Duration, Instant};

pub use error::BenchError;
pub use implementation::{Case, Implementation};
pub use pinocchio::{PinocchioScript, PinocchioTimes};
pub use report::Report;

use integrators::Settings;
use rne_models::BUILTIN_ROBOTS;
use timing::Plan;

/// How much to measure.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Effort {
    /// A check in seconds: few states, short batches, short runs.
    Quick,
    /// The report: 10 000 states per robot, 101 rounds of 200 µs batches.
    Full,
}

impl Effort {
    /// States per robot for the errors.
    pub fn samples(self) -> usize {
        match self {
            Effort::Quick => 48,
            Effort::Full => 10_000,
        }
    }

    /// States cycled through while timing.
    pub fn pool(self) -> usize {
        match self {
            Effort::Quick => 16,
            Effort::Full => 256,
        }
    }

    /// Timing of the kernels.
    pub fn kernel_plan(self) -> Plan {
        match self {
            Effort::Quick => Plan {
                batch: Duration::from_micros(20),
                rounds: 5,
            },
            Effort::Full => Plan {
                batch: Duration::from_micros(200),
                rounds: 101,
            },
        }
    }

    /// Timing of the integrations (a batch is at least one whole integration).
    pub fn integrator_plan(self) -> Plan {
        match self {
            Effort::Quick => Plan {
                batch: Duration::ZERO,
                rounds: 2,
            },
            Effort::Full => Plan {
                batch: Duration::from_millis(2),
                rounds: 15,
            },
        }
    }

    /// The double-pendulum settings.
    pub fn double_pendulum(self) -> Settings {
        match self {
            Effort::Quick => Settings {
                duration: 0.5,
                rk4: vec![1e-2, 2e-3],
                dopri5: vec![1e-4, 1e-8],
                gauss_legendre: vec![1e-2],
            },
            Effort::Full => Settings {
                duration: 5.0,
                rk4: vec![1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4],
                dopri5: vec![1e-4, 1e-6, 1e-8, 1e-10, 1e-12],
                gauss_legendre: vec![1e-2, 5e-3, 2e-3, 1e-3],
            },
        }
    }

    /// The IRB 140 joint-3 pendulum settings.
    pub fn irb140_pendulum(self) -> Settings {
        match self {
            Effort::Quick => Settings {
                duration: 1.0,
                ..self.double_pendulum()
            },
            Effort::Full => Settings {
                duration: 20.0,
                ..self.double_pendulum()
            },
        }
    }
}

/// Runs the studies with `effort`, and the comparison with Pinocchio when `pinocchio`
/// names its script (URDF copies go to `scratch`), calling `progress` with the name of each
/// step as it starts.
pub fn run(
    effort: Effort,
    pinocchio: Option<(&PinocchioScript, &std::path::Path)>,
    mut progress: impl FnMut(&str),
) -> Result<Report, BenchError> {
    let start = Instant::now();
    let (plan, pool) = (effort.kernel_plan(), effort.pool());
    let mut kernel_results = Vec::new();
    let mut control_results = Vec::new();
    let mut scene_results = Vec::new();
    let mut pinocchio_results = Vec::new();
    for robot in BUILTIN_ROBOTS {
        let compared = pinocchio.filter(|_| pinocchio::COMPARED.contains(&robot.name));
        let mut pinocchio_runs = beside::PairedTimes::default();
        progress(&format!("{}: models and samples", robot.name));
        let cases = robots::Cases::new(robot, effort.samples())?;
        // The scripts, then rne's compared kernels right after them (`beside`).
        let run_pinocchio = |runs: &mut beside::PairedTimes| -> Result<(), BenchError> {
            if let Some((script, scratch)) = compared {
                let figures = script.run_once(robot, scratch, runs.runs())?;
                runs.push(figures, beside::time_compared(&cases, &plan, pool)?);
            }
            Ok(())
        };
        let control_programs = control::has_control(robot.name).then(|| control::programs(&cases));
        run_pinocchio(&mut pinocchio_runs)?;
        progress(&format!("{}: kernels", robot.name));
        kernel_results.push(kernels::measure(&cases, &plan, pool)?);
        if let Some(programs) = &control_programs {
            progress(&format!("{}: control kernels", robot.name));
            control_results.push(control::measure(&cases, programs, &plan, pool)?);
        }
        run_pinocchio(&mut pinocchio_runs)?;
        progress(&format!("{}: scenes", robot.name));
        scene_results.push(scenes::measure(&cases, &plan, pool)?);
        run_pinocchio(&mut pinocchio_runs)?;
        if let Some((script, _)) = compared {
            pinocchio_results.push(script.times(robot.name, pinocchio_runs));
        }
    }
    let plan = effort.integrator_plan();
    progress("integrators: double pendulum");
    let double = integrators::double_pendulum(&effort.double_pendulum(), &plan)?;
    progress("integrators: IRB 140 joint-3 pendulum");
    let irb = integrators::irb140_pendulum(&effort.irb140_pendulum(), &plan)?;
    Ok(Report {
        effort,
        kernels: kernel_results,
        control: control_results,
        scenes: scene_results,
        integrators: vec![double, irb],
        pinocchio: pinocchio_results,
        elapsed: start.elapsed(),
    })
}
