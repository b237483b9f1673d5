//! The premise of the stress suite and of every accuracy figure measured on expression
//! graphs: a built-in robot's compiled `f64` kernels return bit for bit what the `f64`
//! evaluation of its graph (`Interpreted`) returns, for every output of all eight kernels, at
//! states from |q| ≤ π to |q| ~ 1e9 (past the fast argument reduction of `sin_cos`).

use rne_codegen::Kernel;
use rne_interpreted::{evaluate, Interpreted, JointState};
use rne_models::{RobotSource, Visitor, BUILTIN_ROBOTS};
use rne_runtime::Dynamics;
use rne_stress::cases::compiled::check;
use rne_stress::states::{generator, uniform};
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

/// Programs built for a subset of kernels, in any order, as every stress case builds them:
/// their `f64` values equal the compiled kernels' bit for bit (20 states per robot,
/// |q| ≤ 1e3).
#[test]
fn programs_of_some_kernels_equal_compiled_kernels_bitwise() {
    /// Compares one robot's generated `Model` with `programs`.
    struct Compare<'a> {
        name: &'a str,
        programs: &'a Interpreted,
    }
    impl Visitor for Compare<'_> {
        type Output = ();
        fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) {
            let mut rng = generator(5);
            for _ in 0..20 {
                let state = JointState {
                    q: uniform(&mut rng, N, 1e3),
                    qd: uniform(&mut rng, N, 10.0),
                    qdd: uniform(&mut rng, N, 10.0),
                    tau: uniform(&mut rng, N, 100.0),
                };
                for kernel in self.programs.kernels() {
                    let compiled = evaluate(&model, kernel, state.as_ref()).unwrap();
                    let programmed = self.programs.eval(kernel, state.as_ref()).unwrap();
                    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&programmed), bits(&compiled), "{} {kernel}", self.name);
                }
            }
        }
    }
    let kernels = [
        Kernel::ForwardDynamics,
        Kernel::KineticEnergy,
        Kernel::InverseDynamics,
    ];
    for robot in BUILTIN_ROBOTS {
        let model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .unwrap();
        let programs = Interpreted::with_kernels(&model, &kernels);
        robot.visit(Compare {
            name: robot.name,
            programs: &programs,
        });
    }
}
