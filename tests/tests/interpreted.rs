//! The optimised programs, evaluated without compiling them, give bit-for-bit the results of
//! the compiled kernels: the emitted Rust performs the same operations in the same order.

mod common;

use common::state;
use common::SliceModel;
use rne_interpreted::Interpreted;
use rne_models::{RobotSource, BUILTIN_ROBOTS};
use rne_symbolic::spec::LoadOptions;

#[test]
fn interpreted_programs_equal_the_compiled_kernels_bit_for_bit() {
    for robot in BUILTIN_ROBOTS {
        let model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .unwrap();
        let programs = Interpreted::new(&model);
        SliceModel::programs(&programs, |interpreted| {
            common::with_generated(robot, |compiled| {
                let n = compiled.dof();
                let mut rng = common::rng(0x5eed_0005);
                for _ in 0..300 {
                    let (q, qd, qdd) = state(&mut rng, n);
                    let bits = |v: Vec<f64>| v.into_iter().map(f64::to_bits).collect::<Vec<_>>();
                    let same = |a: Vec<f64>, b: Vec<f64>, what: &str| {
                        assert_eq!(bits(a), bits(b), "{}: {what}", robot.name)
                    };
                    same(
                        interpreted.inverse_dynamics(&q, &qd, &qdd).unwrap(),
                        compiled.inverse_dynamics(&q, &qd, &qdd).unwrap(),
                        "tau",
                    );
                    same(
                        interpreted.mass_matrix(&q).unwrap().concat(),
                        compiled.mass_matrix(&q).unwrap().concat(),
                        "M",
                    );
                    same(
                        interpreted.coriolis_matrix(&q, &qd).unwrap().concat(),
                        compiled.coriolis_matrix(&q, &qd).unwrap().concat(),
                        "C",
                    );
                    same(
                        interpreted.gravity_torques(&q).unwrap(),
                        compiled.gravity_torques(&q).unwrap(),
                        "g",
                    );
                    same(
                        interpreted.bias_torques(&q, &qd).unwrap(),
                        compiled.bias_torques(&q, &qd).unwrap(),
                        "bias",
                    );
                    same(
                        interpreted.forward_dynamics(&q, &qd, &qdd).unwrap(),
                        compiled.forward_dynamics(&q, &qd, &qdd).unwrap(),
                        "qdd",
                    );
                    same(
                        vec![interpreted.kinetic_energy(&q, &qd).unwrap()],
                        vec![compiled.kinetic_energy(&q, &qd).unwrap()],
                        "T",
                    );
                    same(
                        vec![interpreted.potential_energy(&q).unwrap()],
                        vec![compiled.potential_energy(&q).unwrap()],
                        "V",
                    );
                }
            });
        });
    }
}
