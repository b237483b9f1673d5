//! The premise of the stress suite and of every accuracy figure measured on expression
//! graphs: a built-in robot's compiled `f64` kernels return bit for bit what the `f64`
//! evaluation of its graph (`Interpreted`) returns, for every output of all eight kernels, at
//! states from |q| ≤ π to |q| ~ 1e9 (past the fast argument reduction of `sin_cos`).

use rne_codegen::Kernel;
use rne_models::builtin::{RobotSource, BUILTIN_ROBOTS};
use rne_models::stress::cases::compiled::check;
use rne_models::stress::states::{generator, uniform};
use rne_models::stress::{JointState, Probe};
use rne_symbolic::spec::LoadOptions;

/// Bound: zero differing bits, every built-in robot, 40 seeded states each (320 kernel calls
/// per robot and evaluation path).
#[test]
fn compiled_kernels_equal_graph_evaluation_bitwise() {
    for robot in BUILTIN_ROBOTS {
        let c = check(robot, 40).unwrap_or_else(|e| panic!("{e}"));
        assert!(c.values >= 40 * 8, "{}: {} values", c.robot, c.values);
        assert_eq!(
            c.mismatch_count, 0,
            "{}: compiled and graph differ: {:#?}",
            c.robot, c.mismatches
        );
    }
}

/// The probe that every stress case measures with evaluates the same programs, whatever
/// subset of kernels it is built with and in whatever order: its `f64` values equal the
/// compiled kernels' bit for bit (20 states per robot, |q| ≤ 1e3).
#[test]
fn probe_programs_equal_compiled_kernels_bitwise() {
    let kernels = [
        Kernel::ForwardDynamics,
        Kernel::KineticEnergy,
        Kernel::InverseDynamics,
    ];
    for robot in BUILTIN_ROBOTS {
        let model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .unwrap();
        let probe = Probe::new(&model, &kernels);
        let n = probe.dof();
        let mut rng = generator(5);
        for _ in 0..20 {
            let state = JointState {
                q: uniform(&mut rng, n, 1e3),
                qd: uniform(&mut rng, n, 10.0),
                qdd: uniform(&mut rng, n, 10.0),
                tau: uniform(&mut rng, n, 100.0),
            };
            let k = robot.kernels;
            let compiled = [
                k.forward_dynamics(&state.q, &state.qd, &state.tau).unwrap(),
                vec![k.kinetic_energy(&state.q, &state.qd).unwrap()],
                k.inverse_dynamics(&state.q, &state.qd, &state.qdd).unwrap(),
            ];
            for (kernel, expected) in kernels.iter().zip(&compiled) {
                let probed = probe.eval_f64(*kernel, &state).unwrap();
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&probed),
                    bits(expected),
                    "{} {}",
                    robot.name,
                    kernel.name()
                );
            }
        }
    }
}
