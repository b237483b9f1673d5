//! Every built-in robot three ways: its generated kernels, its symbolic dynamics evaluated on
//! the expression graph, and the independent numeric reference agree to 1e-12 (relative) on
//! seeded states, for τ, M, g, the bias, forward dynamics and both energies. (The workspace's
//! `generated_vs_reference` test takes 10 000 states and C too; this one also brings in the
//! symbolic path and the robots' own properties.)

mod robots_common;

use rne_codegen::Dynamics;
use rne_models::{builtin, RobotSource, Visitor, BUILTIN_ROBOTS};
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::RobotModel;
use robots_common::{assert_close, kernels, reference, rng, state, uniform, Dof, Symbolic};

const STATES: usize = 200;
const TOLERANCE: f64 = 1e-12;

/// The three evaluations of one built-in robot, on its generated `Model`.
struct Agree<'a> {
    name: &'a str,
    model: &'a RobotModel,
}

impl Visitor for Agree<'_> {
    type Output = ();

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, generated: D) {
        let (name, model) = (self.name, self.model);
        assert_eq!(D::JOINTS, model.joint_names(), "{name}");
        assert_eq!(N, model.dof(), "{name}");
        let symbolic = Symbolic::new(model);
        let mut numeric = Reference::new(&model.to_numeric());
        let mut rng = rng(0x0b07_5001);
        for _ in 0..STATES {
            let (q, qd, qdd) = state(&mut rng, N);
            let g = numeric.gravity_torques(&q).unwrap();
            let tau = uniform(&mut rng, N, g.amax().max(10.0));
            let expected = reference(&mut numeric, &q, &qd, &qdd, &tau);
            let from_kernels = kernels(&generated, &q, &qd, &qdd, &tau);
            let from_graph = symbolic.eval(&q, &qd, &qdd, &tau);
            assert_close(
                name,
                "kernels vs reference",
                from_kernels.errors(&expected),
                TOLERANCE,
                &q,
            );
            assert_close(
                name,
                "symbolic vs reference",
                from_graph.errors(&expected),
                TOLERANCE,
                &q,
            );
        }
    }
}

#[test]
fn kernels_symbolic_dynamics_and_reference_agree_on_every_builtin_robot() {
    for robot in BUILTIN_ROBOTS {
        let model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        robot.visit(Agree {
            name: robot.name,
            model: &model,
        });
    }
}

#[test]
fn the_new_robots_are_registered() {
    for (name, file, dof) in [
        ("puma560", "robots/puma560.toml", 6),
        ("ur5", "robots/ur5.urdf", 6),
        ("panda", "robots/panda.urdf", 9),
        ("panda-arm", "robots/panda-arm.urdf", 7),
        ("irb140", "robots/irb140.toml", 6),
    ] {
        let robot = builtin(name).unwrap_or_else(|| panic!("{name} is not built in"));
        assert_eq!(robot.file, file);
        assert_eq!(robot.visit(Dof), dof, "{name}");
    }
}

#[test]
fn the_panda_fingers_share_no_inertia() {
    // Both fingers hang off the hand: M couples them with nothing in common, M[7][8] = 0
    // exactly (the generated LDLᵀ keeps the zero).
    assert!(builtin("panda").is_some());
    let mut rng = rng(0x0b07_5002);
    for _ in 0..100 {
        let q: [f64; 9] = uniform(&mut rng, 9, 3.0).try_into().unwrap();
        let m = rne_models::generated::panda::mass_matrix(&q);
        assert_eq!(m[7][8], 0.0);
        assert_eq!(m[8][7], 0.0);
        // Each finger carries its own 0.015 kg along its axis.
        assert!(
            (m[7][7] - 0.015).abs() < 1e-15 && (m[8][8] - 0.015).abs() < 1e-15,
            "{m:?}"
        );
    }
}
