//! `rne stress`: the numerical stability of the generated `f64` kernels at the edges of their
//! use — extreme mass ratios and link lengths, huge joint angles and velocities, nearly
//! singular mass matrices, long chaotic runs, robots of up to 12 joints, and NaN or infinite
//! inputs — measured against a ≥ 30-digit reference.
//!
//! # Method
//!
//! Every case evaluates a robot's kernels at seeded random states twice (see [`sweep`]): in
//! `f64` through the optimised programs that code generation emits, which is bit for bit what
//! the generated kernel computes (the [`cases::compiled`] check confirms it on every built-in
//! robot), and in [`DoubleDouble`](rne_symbolic::DoubleDouble) (about 32 digits) through the
//! model's expression graph before optimisation, with the same `f64` constants and inputs. The
//! double-double value is the exact value of the `f64` model to about 10⁻³¹, so the difference
//! is the error of the generated kernel alone. Errors are normwise relative, ‖c − e‖∞ / ‖e‖∞,
//! and in ulps of the largest component (see [`rne_figures::measure`]); each table gives the largest and the
//! median over the states.
//!
//! The cases, one module each under [`cases`], return typed measurements (used by the tests
//! in `tests/stress_*.rs`, each with a stated bound) and a [`CaseReport`]: tables,
//! figures, and where accuracy is lost and why. [`run`] runs them all into a
//! [`StressReport`], which `rne stress` writes as markdown with SVG and PNG figures.

#![deny(missing_docs)]

pub mod cases;
mod chain;
mod error;
pub mod measure;
mod probe;
mod random_robot;
mod report;
pub mod states;
pub mod sweep;

pub use chain::{Chain, ChainLink, JointType};
pub use error::StressError;
pub use probe::{Engine, Probe};
pub use random_robot::random_robot;
pub use report::{CaseReport, StressReport};
pub use sweep::Sweep;

/// How thorough a run is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Effort {
    /// Small samples and short runs, seconds in a debug build: what the tests use.
    Quick,
    /// The report's samples and the 1000 s chaotic runs; use a release build.
    Full,
}

impl Effort {
    /// `full` for a full run, `quick` for a quick one.
    pub fn pick<T>(self, full: T, quick: T) -> T {
        match self {
            Effort::Full => full,
            Effort::Quick => quick,
        }
    }
}

/// How a stress run is made: how thorough, and what computes the kernels' `f64` values (the
/// cases of the non-finite inputs, of the compiled kernels and of the chaotic runs use the
/// interpreter, the compiled modules and the compiled elbow whatever the engine: compiled code
/// rejects non-finite states before they reach it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Settings {
    /// Sample sizes and run lengths.
    pub effort: Effort,
    /// The programs interpreted, or compiled in memory (the same bits).
    pub engine: Engine,
}

/// The method paragraph at the head of the report.
pub const METHOD: &str = "\
Each case evaluates a robot's kernels at seeded random states twice, with the same `f64` \
constants and inputs: in `f64` through the optimised straight-line programs that code \
generation emits, operation by operation in the emitted order (bit for bit what the compiled \
kernel computes, checked below on every built-in robot), and in double-double (about 32 \
significant digits) through the model's expression graph before optimisation. The \
double-double value is the exact value of the `f64` model to about 1e-31, so the difference is \
the error of the generated kernel alone — the rounding of its operations and of the constants \
the optimiser folds — not an error of the model or of its inputs. Errors are normwise relative, ‖c − e‖∞ / ‖e‖∞ (a matrix taken as the \
vector of its entries), given as the largest and the median over the states, and in ulps of \
the largest component (0.5 ulp is a correctly rounded result). ε = 2⁻⁵² ≈ 2.2e-16.";

/// One stress case of the report.
pub struct Case {
    /// Short name: `mass-ratio`, `conditioning`, …
    pub slug: &'static str,
    /// Runs the case.
    pub run: fn(Settings) -> Result<CaseReport, StressError>,
}

/// Every case, in the order of the report.
pub const CASES: [Case; 9] = [
    Case {
        slug: cases::compiled::SLUG,
        run: cases::compiled::report,
    },
    Case {
        slug: cases::mass_ratio::SLUG,
        run: cases::mass_ratio::report,
    },
    Case {
        slug: cases::link_length::SLUG,
        run: cases::link_length::report,
    },
    Case {
        slug: cases::joint_angle::SLUG,
        run: cases::joint_angle::report,
    },
    Case {
        slug: cases::velocity::SLUG,
        run: cases::velocity::report,
    },
    Case {
        slug: cases::conditioning::SLUG,
        run: cases::conditioning::report,
    },
    Case {
        slug: cases::chaos::SLUG,
        run: cases::chaos::report,
    },
    Case {
        slug: cases::joint_count::SLUG,
        run: cases::joint_count::report,
    },
    Case {
        slug: cases::non_finite::SLUG,
        run: cases::non_finite::report,
    },
];

/// Runs every case, calling `progress` with each case's name before it starts.
pub fn run(
    settings: Settings,
    mut progress: impl FnMut(&str),
) -> Result<StressReport, StressError> {
    let mut report = StressReport {
        effort: settings.effort,
        cases: Vec::with_capacity(CASES.len()),
    };
    for case in &CASES {
        progress(case.slug);
        report.cases.push((case.run)(settings)?);
    }
    Ok(report)
}
