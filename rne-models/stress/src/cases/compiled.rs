//! The method's premise: a built-in robot's compiled `f64` kernels return, bit for bit, what
//! the evaluation of its optimised programs returns ([`Interpreted`], the same programs the
//! probe of every case evaluates), over states at every scale the other cases use — so
//! measuring the programs measures the compiled kernels, also for stress robots that are not
//! compiled into `rne`.
//!
//! The emitted code performs the program's operations in the program's order: nothing is
//! re-associated, Rust does not contract `a * b + c` into a fused multiply–add, and `sin`/`cos`
//! go through the same `Real::sin_cos` as the program's `f64` evaluation.

use rand_chacha::ChaCha8Rng;

use super::{builtin_model, symbol};
use crate::error::StressError;
use crate::report::CaseReport;
use crate::states::{generator, uniform};
use crate::Settings;
use rne_codegen::Kernel;
use rne_figures::Table;
use rne_interpreted::{evaluate, Interpreted, JointState};
use rne_models::{BuiltinRobot, Visitor, BUILTIN_ROBOTS};
use rne_runtime::Dynamics;

/// The case's name.
pub const SLUG: &str = "compiled";

/// Seed of the states.
const SEED: u64 = 0x5eed_0000;

/// The outcome of comparing one robot's compiled kernels with its programs.
#[derive(Clone, Debug, PartialEq)]
pub struct BitwiseCheck {
    /// The robot.
    pub robot: &'static str,
    /// Its joints.
    pub joints: usize,
    /// States compared.
    pub states: usize,
    /// Output values compared (every output of every kernel at every state).
    pub values: usize,
    /// The first few values that differ: kernel, output index, compiled, program, state scale.
    pub mismatches: Vec<String>,
    /// How many values differ in all.
    pub mismatch_count: usize,
}

/// The scales of the states, cycled through: (|q|, |q̇|, |q̈|, |τ|) bounds. The second and
/// third exercise the fast argument reduction of `sin_cos` up to 10⁶, the last its fallback
/// to the standard library beyond 1.6·10⁶.
pub const SCALES: [(f64, f64, f64, f64); 4] = [
    (std::f64::consts::PI, 10.0, 10.0, 100.0),
    (1e3, 1e2, 1e2, 1e3),
    (1e6, 1e3, 1e3, 1e4),
    (1e9, 1.0, 1.0, 1.0),
];

/// Compares `robot`'s compiled kernels with its programs, value by value, at `states` seeded
/// states cycling through [`SCALES`].
pub fn check(robot: &BuiltinRobot, states: usize) -> Result<BitwiseCheck, StressError> {
    let programs = Interpreted::new(&builtin_model(robot.name)?);
    robot.visit(Bitwise {
        robot: robot.name,
        programs: &programs,
        states,
    })
}

/// The comparison of one robot, run on its generated `Model`.
struct Bitwise<'a> {
    robot: &'static str,
    programs: &'a Interpreted,
    states: usize,
}

impl Visitor for Bitwise<'_> {
    type Output = Result<BitwiseCheck, StressError>;

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) -> Self::Output {
        let mut rng: ChaCha8Rng = generator(SEED);
        let mut result = BitwiseCheck {
            robot: self.robot,
            joints: N,
            states: self.states,
            values: 0,
            mismatches: Vec::new(),
            mismatch_count: 0,
        };
        for s in 0..self.states {
            let (qb, qdb, qddb, taub) = SCALES[s % SCALES.len()];
            let state = JointState {
                q: uniform(&mut rng, N, qb),
                qd: uniform(&mut rng, N, qdb),
                qdd: uniform(&mut rng, N, qddb),
                tau: uniform(&mut rng, N, taub),
            };
            for kernel in Kernel::DYNAMICS {
                let compiled = evaluate(&model, kernel, state.as_ref()).map_err(|cause| {
                    StressError::Evaluation {
                        robot: self.robot.to_owned(),
                        cause,
                    }
                })?;
                let program = self
                    .programs
                    .eval(kernel, state.as_ref())
                    .unwrap_or_default();
                for (i, (x, y)) in compiled.iter().zip(&program).enumerate() {
                    result.values += 1;
                    if x.to_bits() != y.to_bits() {
                        result.mismatch_count += 1;
                        if result.mismatches.len() < 5 {
                            result.mismatches.push(format!(
                                "{} output {i}: compiled {x:e}, program {y:e} (|q| ≤ {qb:e})",
                                kernel.name()
                            ));
                        }
                    }
                }
            }
        }
        Ok(result)
    }
}

/// The report section: one row per built-in robot.
pub fn report(settings: Settings) -> Result<CaseReport, StressError> {
    let effort = settings.effort;
    let states = effort.pick(2000, 20);
    let mut table = Table::new(
        format!(
            "Compiled kernels against the `f64` evaluation of their programs, {states} seeded \
             states per robot, every output of all eight kernels."
        ),
        &["robot", "joints", "values compared", "bitwise identical"],
    );
    let mut failures = Vec::new();
    for robot in BUILTIN_ROBOTS {
        let c = check(robot, states)?;
        table.push(vec![
            c.robot.to_string(),
            c.joints.to_string(),
            c.values.to_string(),
            if c.mismatch_count == 0 {
                "all".to_string()
            } else {
                format!("{} differ", c.mismatch_count)
            },
        ]);
        failures.extend(c.mismatches.iter().map(|m| format!("{}: {m}", c.robot)));
    }
    let findings = if failures.is_empty() {
        format!(
            "Every compiled value ({}) equals the program's `f64` value bit for bit, so the \
             errors measured on programs in the cases below are the errors of the generated \
             kernels, also for the stress robots that are not compiled into `rne`.",
            Kernel::DYNAMICS.map(symbol).join(", ")
        )
    } else {
        format!(
            "**The compiled kernels differ from their programs**, so the measurements below \
             are those of the programs only. First differences:\n\n- {}",
            failures.join("\n- ")
        )
    };
    Ok(CaseReport {
        slug: SLUG,
        title: "0. Premise: compiled kernels = program evaluation, bit for bit".into(),
        setup: "Each built-in robot's generated kernels (compiled into `rne`) and its optimised \
             programs evaluated in `f64` (`Interpreted`) at the same seeded states, cycling \
             through |q| ≤ π, 1e3, 1e6 and 1e9 rad (the last beyond the fast argument \
             reduction of `sin_cos`), |q̇|, |q̈| up to 1e3 and |τ| up to 1e4. Values are \
             compared by their bits."
            .into(),
        tables: vec![table],
        plots: Vec::new(),
        findings,
    })
}
