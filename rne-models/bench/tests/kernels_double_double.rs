//! Accuracy of every generated `f64` kernel of every built-in robot against a ≈32-digit value
//! (issue 6): the kernel's own optimised program evaluated in double-double arithmetic, over
//! 10 000 seeded states with |q| ≤ π, |q̇| ≤ 10, |q̈| ≤ 10.
//!
//! The potential energy is one number that passes through zero as the arm turns (at q = 0 for
//! the planar elbow), where no relative error is meaningful; its error is taken relative to
//! the largest |U| over the sample instead (the other kernels' errors are normwise relative,
//! state by state).

use rne_codegen::{DoubleDouble, Kernel};
use rne_models::bench::implementation::Case;
use rne_models::bench::precision::{error, Error, ErrorSummary, Format};
use rne_models::bench::robots::Cases;
use rne_models::builtin::BUILTIN_ROBOTS;
use rne_models::kernels::Kernels;

const STATES: usize = 10_000;
/// Largest normwise relative error allowed anywhere.
const MAX_RELATIVE: f64 = 1e-13;
/// Largest median normwise relative error allowed per kernel.
const MEDIAN_RELATIVE: f64 = 2e-15;

/// The generated kernel's value, matrices row by row.
fn generated(kernels: &dyn Kernels, kernel: Kernel, cases: &Cases, k: usize) -> Vec<f64> {
    let state = cases.sample(Case::Full).state(k);
    let (q, qd, qdd, tau) = (state.q, state.qd, state.qdd, state.tau);
    let flat = |m: Vec<Vec<f64>>| m.concat();
    let value = match kernel {
        Kernel::InverseDynamics => kernels.inverse_dynamics(q, qd, qdd),
        Kernel::MassMatrix => kernels.mass_matrix(q).map(flat),
        Kernel::CoriolisMatrix => kernels.coriolis_matrix(q, qd).map(flat),
        Kernel::GravityTorques => kernels.gravity_torques(q),
        Kernel::BiasTorques => kernels.bias_torques(q, qd),
        Kernel::ForwardDynamics => kernels.forward_dynamics(q, qd, tau),
        Kernel::KineticEnergy => kernels.kinetic_energy(q, qd).map(|e| vec![e]),
        Kernel::PotentialEnergy => kernels.potential_energy(q).map(|e| vec![e]),
        other => panic!("`Kernels` has no method for {other}"),
    };
    value.expect("the sample has the robot's number of joints")
}

#[test]
fn every_generated_f64_kernel_is_within_1e_13_of_the_double_double_value() {
    let mut failures = Vec::new();
    for robot in BUILTIN_ROBOTS {
        let cases = Cases::new(robot, STATES).expect("built-in robots load");
        for kernel in Kernel::ALL {
            let exact: Vec<Vec<DoubleDouble>> = (0..STATES)
                .map(|k| cases.exact(Case::Full, kernel, k))
                .collect();
            let mut errors: Vec<Error> = exact
                .iter()
                .enumerate()
                .map(|(k, x)| error(&generated(robot.kernels, kernel, &cases, k), x, Format::F64))
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
