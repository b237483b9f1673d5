//! Accuracy of every generated `f64` kernel of every built-in robot against a ≈32-digit value
//! (issue 6): the kernel's own optimised program evaluated in double-double arithmetic, over
//! 10 000 seeded states with |q| ≤ π, |q̇| ≤ 10, |q̈| ≤ 10.
//!
//! The potential energy is one number that passes through zero as the arm turns (at q = 0 for
//! the planar elbow), where no relative error is meaningful; its error is taken relative to
//! the largest |U| over the sample instead (the other kernels' errors are normwise relative,
//! state by state).

use rne_bench::implementation::Case;
use rne_bench::precision::ErrorSummary;
use rne_bench::robots::Cases;
use rne_codegen::{DoubleDouble, Dynamics, Kernel};
use rne_figures::{Deviation, Format};
use rne_interpreted::evaluate;
use rne_models::{Visitor, BUILTIN_ROBOTS};

const STATES: usize = 10_000;
/// Largest normwise relative error allowed anywhere.
const MAX_RELATIVE: f64 = 1e-13;
/// Largest median normwise relative error allowed per kernel.
const MEDIAN_RELATIVE: f64 = 2e-15;

/// The generated kernel's values over the sample of `cases`, matrices row by row.
struct Generated<'a> {
    kernel: Kernel,
    cases: &'a Cases,
}

impl Visitor for Generated<'_> {
    type Output = Vec<Vec<f64>>;

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) -> Self::Output {
        (0..STATES)
            .map(|k| {
                let state = self.cases.sample(Case::Full).state(k);
                evaluate(&model, self.kernel, state).expect("every kernel at the robot's size")
            })
            .collect()
    }
}

#[test]
fn every_generated_f64_kernel_is_within_1e_13_of_the_double_double_value() {
    let mut failures = Vec::new();
    for robot in BUILTIN_ROBOTS {
        let cases = Cases::new(robot, STATES).expect("built-in robots load");
        for kernel in Kernel::DYNAMICS {
            let exact: Vec<Vec<DoubleDouble>> = (0..STATES)
                .map(|k| cases.exact(Case::Full, kernel, k))
                .collect();
            let values = robot.visit(Generated {
                kernel,
                cases: &cases,
            });
            let mut errors: Vec<Deviation> = values
                .iter()
                .zip(&exact)
                .map(|(value, x)| Deviation::between(value, x, Format::F64))
                .collect();
            if kernel == Kernel::PotentialEnergy {
                let range = exact.iter().fold(0.0f64, |m, x| m.max(x[0].to_f64().abs()));
                for (e, x) in errors.iter_mut().zip(&exact) {
                    let absolute = if x[0].to_f64() == 0.0 {
                        e.relative
                    } else {
                        e.relative * x[0].to_f64().abs()
                    };
                    e.relative = absolute / range;
                }
            }
            let summary = ErrorSummary::of(&errors);
            assert_eq!(summary.states, STATES);
            if !(summary.max_relative <= MAX_RELATIVE && summary.median_relative <= MEDIAN_RELATIVE)
            {
                failures.push(format!(
                    "{} {}: max {:.2e}, median {:.2e}",
                    robot.name,
                    kernel.name(),
                    summary.max_relative,
                    summary.median_relative
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
