//! Case 8: NaN and infinite inputs.
//!
//! The generated kernels are straight-line code: no loop, branch or index depends on a value
//! (the only branch, in `sin_cos`, sends non-finite and huge arguments to the standard
//! library), so they cannot hang or panic on any input. IEEE 754 arithmetic then fixes what
//! they return: NaN propagates through every operation (`NaN · 0 = NaN`), and an infinity
//! becomes NaN through `sin`/`cos`, `∞ − ∞` or `0 · ∞`, or stays infinite. The case checks,
//! on every kernel of every built-in robot and for each input entry set in turn to NaN, +∞
//! and −∞ at an otherwise finite state, that
//! - every output that depends on that entry in the emitted program is NaN (for a NaN
//!   input) or not finite (for an infinite one);
//! - every other output is bit for bit the value at the finite state: a bad entry does not
//!   leak into outputs that do not depend on it (M(q) does not read q̇; for the planar elbow
//!   it does not read q₁ either);
//! - no call panics.
//!
//! It also runs the integrators from a non-finite state: they stop with an error instead of
//! looping.

use std::panic::{catch_unwind, AssertUnwindSafe};

use rne_codegen::Kernel;
use rne_codegen_core::Input;
use rne_symbolic::Symbol;

use super::builtin_model;
use crate::error::StressError;
use crate::report::CaseReport;
use crate::states::{generator, uniform};
use crate::Settings;
use rne_figures::Table;
use rne_interpreted::Interpreted;
use rne_interpreted::{evaluate, StateRef};
use rne_models::generated::planar_elbow::Model as PlanarElbow;
use rne_models::{BuiltinRobot, Visitor, BUILTIN_ROBOTS};
use rne_runtime::Dynamics;
use rne_sim::{simulate, Dopri5, GaussLegendre, Integrator, Rk4, SimError, State, ZeroInput};

/// The case's name.
pub const SLUG: &str = "non-finite";

/// The values put into one input entry.
pub const BAD_VALUES: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

/// Seed of the finite states.
const SEED: u64 = 0x5eed_0008;

/// The outcome for one robot.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NonFiniteCheck {
    /// The robot.
    pub robot: String,
    /// Kernel calls made (kernel × input entry × bad value × state).
    pub calls: usize,
    /// Outputs that depend on the bad entry, all of which must be non-finite.
    pub dependent: usize,
    /// Outputs that do not depend on it, all of which must be unchanged.
    pub independent: usize,
    /// The first few outputs that broke the rule.
    pub violations: Vec<String>,
    /// How many outputs broke it.
    pub violation_count: usize,
    /// Calls that panicked.
    pub panics: usize,
}

/// Calls `kernel` of `model` with the state arrays `[q, q̇, q̈, τ]`; matrices flattened
/// row-major.
fn call<const NQ: usize, const NV: usize, D: Dynamics<NQ, NV, Scalar = f64>>(
    model: &D,
    kernel: Kernel,
    arrays: &[Vec<f64>; 4],
) -> Result<Vec<f64>, rne_interpreted::Error> {
    let [q, qd, qdd, tau] = arrays;
    evaluate(model, kernel, StateRef { q, qd, qdd, tau })
}

/// The array of `input` in `[q, q̇, q̈, τ]`, and the symbol of its entry `j`.
fn slot(input: Input, j: usize) -> (usize, Symbol) {
    // Joint indices of built-in robots are far below u16::MAX.
    let j16 = u16::try_from(j).unwrap_or(u16::MAX);
    match input {
        Input::Q => (0, Symbol::Position(j16)),
        Input::Qd => (1, Symbol::Velocity(j16)),
        Input::Qdd => (2, Symbol::Acceleration(j16)),
        Input::Tau => (3, Symbol::Force(j16)),
        other => unreachable!("no dynamics kernel takes `{}`", other.name()),
    }
}

/// Checks every kernel of `model` (a robot whose programs `probe` holds) at `states` seeded
/// finite states, each input entry set in turn to each of [`BAD_VALUES`].
pub fn check<const N: usize, D: Dynamics<N, N, Scalar = f64>>(
    name: &str,
    model: &D,
    probe: &Interpreted,
    states: usize,
) -> Result<NonFiniteCheck, StressError> {
    let n = probe.dof();
    let mut rng = generator(SEED);
    let mut result = NonFiniteCheck {
        robot: name.to_owned(),
        ..NonFiniteCheck::default()
    };
    let dimension = |cause| StressError::Evaluation {
        robot: name.to_owned(),
        cause,
    };
    for _ in 0..states {
        let finite = [0; 4].map(|_| uniform(&mut rng, n, 2.0));
        for kernel in Kernel::DYNAMICS {
            let dependencies = probe.dependencies(kernel).unwrap_or_default();
            let baseline = call(model, kernel, &finite).map_err(dimension)?;
            for &input in kernel.inputs() {
                for j in 0..n {
                    let (array, symbol) = slot(input, j);
                    for bad in BAD_VALUES {
                        let mut arrays = finite.clone();
                        arrays[array][j] = bad;
                        result.calls += 1;
                        let Ok(outputs) =
                            catch_unwind(AssertUnwindSafe(|| call(model, kernel, &arrays)))
                        else {
                            result.panics += 1;
                            continue;
                        };
                        let outputs = outputs.map_err(dimension)?;
                        for (i, (&out, &base)) in outputs.iter().zip(&baseline).enumerate() {
                            let depends = dependencies.get(i).is_some_and(|d| d.contains(&symbol));
                            let ok = if depends {
                                result.dependent += 1;
                                if bad.is_nan() {
                                    out.is_nan()
                                } else {
                                    !out.is_finite()
                                }
                            } else {
                                result.independent += 1;
                                out.to_bits() == base.to_bits()
                            };
                            if !ok {
                                result.violation_count += 1;
                                if result.violations.len() < 5 {
                                    result.violations.push(format!(
                                        "{name} {} output {i} with {}[{j}] = {bad}: {out} (finite input: {base}, depends: {depends})",
                                        kernel.name(),
                                        input.name()
                                    ));
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    Ok(result)
}

/// Runs [`check`] on a built-in robot's compiled kernels.
pub fn check_builtin(robot: &BuiltinRobot, states: usize) -> Result<NonFiniteCheck, StressError> {
    let probe = Interpreted::new(&builtin_model(robot.name)?);
    robot.visit(Builtin {
        name: robot.name,
        probe: &probe,
        states,
    })
}

/// [`check`] on a built-in robot's generated `Model`.
struct Builtin<'a> {
    name: &'a str,
    probe: &'a Interpreted,
    states: usize,
}

impl Visitor for Builtin<'_> {
    type Output = Result<NonFiniteCheck, StressError>;

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) -> Self::Output {
        check(self.name, &model, self.probe, self.states)
    }
}

/// What an integrator does from a non-finite initial state of the planar elbow.
pub fn integrate_from_nan<I: Integrator<2>>(integrator: &I) -> Result<(), SimError> {
    simulate(
        &PlanarElbow,
        &ZeroInput,
        integrator,
        &State::new([f64::NAN, 0.0], [0.0, f64::INFINITY]),
        &[0.0, 1.0],
    )
    .map(|_| ())
}

/// What each integrator does when started from a non-finite state.
fn integrator_table() -> Table {
    let mut table = Table::new(
        "The planar elbow integrated from q = (NaN, 0), q̇ = (0, ∞) over 1 s.",
        &["integrator", "outcome"],
    );
    let outcome = |r: Result<(), SimError>| match r {
        Ok(()) => "returned a record (no error)".to_string(),
        Err(e) => format!("error: {e}"),
    };
    table.push(vec![
        "RK4, h = 1e-3".into(),
        outcome(integrate_from_nan(&Rk4::new(1e-3))),
    ]);
    table.push(vec![
        "Dormand–Prince, rtol 1e-10".into(),
        outcome(integrate_from_nan(&Dopri5::new(1e-10, 1e-12))),
    ]);
    table.push(vec![
        "Gauss–Legendre 4, h = 1e-3".into(),
        outcome(integrate_from_nan(&GaussLegendre::new(1e-3))),
    ]);
    table
}

/// The report section.
pub fn report(settings: Settings) -> Result<CaseReport, StressError> {
    let effort = settings.effort;
    let states = effort.pick(20, 1);
    let mut table = Table::new(
        format!(
            "Every kernel of every built-in robot (compiled), each input entry set to NaN, +∞ \
             and −∞ in turn at {states} finite states."
        ),
        &[
            "robot",
            "calls",
            "dependent outputs non-finite",
            "independent outputs unchanged",
            "violations",
            "panics",
        ],
    );
    let mut violations = Vec::new();
    let mut totals = (0, 0, 0);
    for robot in BUILTIN_ROBOTS {
        let c = check_builtin(robot, states)?;
        table.push(vec![
            c.robot.clone(),
            c.calls.to_string(),
            c.dependent.to_string(),
            c.independent.to_string(),
            c.violation_count.to_string(),
            c.panics.to_string(),
        ]);
        totals.0 += c.calls;
        totals.1 += c.violation_count;
        totals.2 += c.panics;
        violations.extend(c.violations);
    }
    let integrators = integrator_table();
    let findings = if totals.1 == 0 && totals.2 == 0 {
        format!(
            "**NaN in gives NaN out, ±∞ in gives NaN or ±∞ out, exactly where the output \
             depends on the bad entry; nothing panics or hangs.** Over {} kernel calls, \
             every output whose program reads the bad entry was NaN (NaN \
             input) or non-finite (infinite input), and every output that does not read it \
             kept its finite value bit for bit. An infinite q becomes NaN through sin/cos; \
             an infinite q̇, q̈ or τ gives ±∞ where it is only scaled and added, and NaN \
             where ∞ − ∞ or 0 · ∞ occurs (in C q̇, in the elimination of forward dynamics). \
             Callers should check `is_finite` on what they feed in, or on what comes out: a \
             kernel never reports bad input any other way. The integrators stop with an \
             error at the first non-finite state (table 2).",
            totals.0
        )
    } else {
        format!(
            "**{} outputs broke the rule and {} calls panicked.** First cases:\n\n- {}",
            totals.1,
            totals.2,
            violations.join("\n- ")
        )
    };
    Ok(CaseReport {
        slug: SLUG,
        title: "8. NaN and infinite inputs".into(),
        setup: "For each built-in robot, each of the eight compiled kernels, each entry of \
                each input array (q, q̇, q̈, τ as the kernel takes them) and each of NaN, +∞, \
                −∞: the kernel is called at a random finite state (|x| ≤ 2) with that one \
                entry replaced, inside `catch_unwind`. Each output is classified by whether \
                its emitted program reads that entry."
            .into(),
        tables: vec![table, integrators],
        plots: Vec::new(),
        findings,
    })
}
