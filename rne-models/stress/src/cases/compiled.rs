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
use crate::builtin::{BuiltinRobot, BUILTIN_ROBOTS};
use crate::interpreted::Interpreted;
use crate::kernels::{DimensionError, Kernels};
use crate::stress::error::StressError;
use crate::stress::report::CaseReport;
use crate::stress::states::{generator, uniform};
use crate::stress::table::Table;
use crate::stress::Effort;
use rne_codegen::Kernel;

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

/// Every kernel's outputs at one state, flattened, in the order of `Kernel::ALL`.
fn outputs(
    k: &dyn Kernels,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    tau: &[f64],
) -> Result<Vec<(Kernel, Vec<f64>)>, DimensionError> {
    Ok(vec![
        (Kernel::InverseDynamics, k.inverse_dynamics(q, qd, qdd)?),
        (Kernel::MassMatrix, k.mass_matrix(q)?.concat()),
        (Kernel::CoriolisMatrix, k.coriolis_matrix(q, qd)?.concat()),
        (Kernel::GravityTorques, k.gravity_torques(q)?),
        (Kernel::BiasTorques, k.bias_torques(q, qd)?),
        (Kernel::ForwardDynamics, k.forward_dynamics(q, qd, tau)?),
        (Kernel::KineticEnergy, vec![k.kinetic_energy(q, qd)?]),
        (Kernel::PotentialEnergy, vec![k.potential_energy(q)?]),
    ])
}

/// Compares `robot`'s compiled kernels with its programs, value by value, at `states` seeded
/// states cycling through [`SCALES`].
pub fn check(robot: &BuiltinRobot, states: usize) -> Result<BitwiseCheck, StressError> {
    let graph = Interpreted::new(&builtin_model(robot.name)?);
    let n = graph.dof();
    let mut rng: ChaCha8Rng = generator(SEED);
    let mut result = BitwiseCheck {
        robot: robot.name,
        joints: n,
        states,
        values: 0,
        mismatches: Vec::new(),
        mismatch_count: 0,
    };
    let dimension = |source| StressError::Dimension {
        robot: robot.name.to_owned(),
        source,
    };
    for s in 0..states {
        let (qb, qdb, qddb, taub) = SCALES[s % SCALES.len()];
        let (q, qd) = (uniform(&mut rng, n, qb), uniform(&mut rng, n, qdb));
        let (qdd, tau) = (uniform(&mut rng, n, qddb), uniform(&mut rng, n, taub));
        let compiled = outputs(robot.kernels, &q, &qd, &qdd, &tau).map_err(dimension)?;
        let evaluated = outputs(&graph, &q, &qd, &qdd, &tau).map_err(dimension)?;
        for ((kernel, a), (_, b)) in compiled.iter().zip(&evaluated) {
            for (i, (x, y)) in a.iter().zip(b).enumerate() {
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

/// The report section: one row per built-in robot.
pub fn report(effort: Effort) -> Result<CaseReport, StressError> {
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
            Kernel::ALL.map(symbol).join(", ")
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
