//! Scene specialisation: a module generated with locked joints, zero gravity, at rest or with
//! runtime parameters equals the full module evaluated accordingly, and costs fewer
//! operations; the deprecated spelling `velocities: zero` is still `at_rest: true`.

mod common;

use common::{rel_err, rel_err_floor, state};
use rne_codegen::Kernel;
use rne_codegen_core::{generate, GenerationOptions, ParameterMode, Scene};
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};

rne_codegen::derive_dynamics! {
    /// Every kernel of the IRB 140's first three joints.
    mod full {
        robot: "fixtures/robots/irb140-3dof.toml",
    }
}

rne_codegen::derive_dynamics! {
    /// Without gravity.
    mod weightless {
        robot: "fixtures/robots/irb140-3dof.toml",
        gravity: [0.0, 0.0, 0.0],
    }
}

rne_codegen::derive_dynamics! {
    /// Joints 1 and 2 locked, as in the thesis's section 6.3.3.
    mod wrist_pendulum {
        robot: "fixtures/robots/irb140-3dof.toml",
        lock: { q1: 0.3, q2: -0.5 },
    }
}

rne_codegen::derive_dynamics! {
    /// A static scene: the joints move slowly enough that q̇ = 0.
    mod at_rest {
        robot: "fixtures/robots/irb140-3dof.toml",
        at_rest: true,
    }
}

rne_codegen::derive_dynamics! {
    /// The same under the deprecated spelling, still accepted (its warning allowed here).
    #[allow(deprecated)]
    mod velocities_zero {
        robot: "fixtures/robots/irb140-3dof.toml",
        velocities: zero,
    }
}

rne_codegen::derive_dynamics! {
    /// `at_rest: false`, the default, spelled out.
    mod moving {
        robot: "fixtures/robots/irb140-3dof.toml",
        outputs: [inverse_dynamics],
        at_rest: false,
    }
}

rne_codegen::derive_dynamics! {
    /// Parameters read at run time.
    mod tunable {
        robot: "fixtures/robots/irb140-3dof.toml",
        outputs: [inverse_dynamics, mass_matrix, forward_dynamics],
        parameters: runtime,
    }
}

const SPEC: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/fixtures/robots/irb140-3dof.toml"
);

#[test]
fn zero_gravity_module_equals_the_full_module_without_its_gravity_torques() {
    let mut rng = common::rng(11);
    for _ in 0..1000 {
        let (q, qd, qdd) = state(&mut rng, 3);
        let (q, qd, qdd) = (
            q.try_into().unwrap(),
            qd.try_into().unwrap(),
            qdd.try_into().unwrap(),
        );
        let expected: Vec<f64> = full::inverse_dynamics(&q, &qd, &qdd)
            .iter()
            .zip(full::gravity_torques(&q))
            .map(|(t, g)| t - g)
            .collect();
        assert!(rel_err(&weightless::inverse_dynamics(&q, &qd, &qdd), &expected) < 1e-13);
        assert_eq!(
            weightless::gravity_torques(&q),
            [0.0; 3],
            "no gravity term survives"
        );
        assert_eq!(weightless::potential_energy(&q), 0.0);
        assert_eq!(
            weightless::mass_matrix(&q),
            full::mass_matrix(&q),
            "M does not depend on gravity"
        );
    }
}

#[test]
fn locked_module_equals_the_full_module_at_the_locked_values() {
    assert_eq!(wrist_pendulum::NDOF, 1);
    assert_eq!(wrist_pendulum::JOINTS, ["q3"]);
    let mut rng = common::rng(12);
    for _ in 0..1000 {
        let (q, qd, qdd) = state(&mut rng, 1);
        let (q3, qd3, qdd3) = ([q[0]], [qd[0]], [qdd[0]]);
        let q_full = [0.3, -0.5, q[0]];
        let qd_full = [0.0, 0.0, qd[0]];
        let qdd_full = [0.0, 0.0, qdd[0]];
        let tau = full::inverse_dynamics(&q_full, &qd_full, &qdd_full);
        // τ3 can vanish; its error is taken relative to the joint's torque scale M33 + |g3|.
        let scale = full::mass_matrix(&q_full)[2][2] + full::gravity_torques(&q_full)[2].abs();
        let locked = wrist_pendulum::inverse_dynamics(&q3, &qd3, &qdd3);
        assert!(rel_err_floor(&locked, &[tau[2]], scale) < 1e-13);
        let m = full::mass_matrix(&q_full);
        assert!(rel_err(&wrist_pendulum::mass_matrix(&q3)[0], &[m[2][2]]) < 1e-13);
        let g = full::gravity_torques(&q_full);
        assert!(rel_err(&wrist_pendulum::gravity_torques(&q3), &[g[2]]) < 1e-13);
        let t = full::kinetic_energy(&q_full, &qd_full);
        assert!(rel_err(&[wrist_pendulum::kinetic_energy(&q3, &qd3)], &[t]) < 1e-13);
        // With q1, q2 held, q̈3 = (τ3 − b3) / M33.
        let tau3 = [tau[2]];
        let qdd_back = wrist_pendulum::forward_dynamics(&q3, &qd3, &tau3);
        assert!(rel_err(&qdd_back, &qdd3) < 1e-11);
    }
}

#[test]
fn static_scene_module_equals_the_full_module_at_zero_velocity() {
    let mut rng = common::rng(14);
    for _ in 0..1000 {
        let (q, qd, qdd) = state(&mut rng, 3);
        let (q, qd, qdd): ([f64; 3], [f64; 3], [f64; 3]) = (
            q.try_into().unwrap(),
            qd.try_into().unwrap(),
            qdd.try_into().unwrap(),
        );
        let rest = [0.0; 3];
        // The velocities passed are ignored.
        let tau = full::inverse_dynamics(&q, &rest, &qdd);
        assert!(rel_err(&at_rest::inverse_dynamics(&q, &qd, &qdd), &tau) < 1e-14);
        let g = full::gravity_torques(&q);
        assert!(rel_err(&at_rest::bias_torques(&q, &qd), &g) < 1e-14);
        assert_eq!(at_rest::coriolis_matrix(&q, &qd), [[0.0; 3]; 3]);
        assert_eq!(at_rest::kinetic_energy(&q, &qd), 0.0);
        assert!(
            rel_err(
                &at_rest::forward_dynamics(&q, &qd, &qdd),
                &full::forward_dynamics(&q, &rest, &qdd)
            ) < 1e-13
        );
    }
}

/// `velocities: zero` is the old spelling of `at_rest: true`: the same functions, bit for bit;
/// `at_rest: false` is the full module's inverse dynamics, bit for bit.
#[test]
fn the_deprecated_spelling_velocities_zero_is_at_rest_true() {
    let mut rng = common::rng(15);
    for _ in 0..100 {
        let (q, qd, qdd) = state(&mut rng, 3);
        let (q, qd, qdd): ([f64; 3], [f64; 3], [f64; 3]) = (
            q.try_into().unwrap(),
            qd.try_into().unwrap(),
            qdd.try_into().unwrap(),
        );
        assert_eq!(
            velocities_zero::inverse_dynamics(&q, &qd, &qdd),
            at_rest::inverse_dynamics(&q, &qd, &qdd)
        );
        assert_eq!(
            velocities_zero::bias_torques(&q, &qd),
            at_rest::bias_torques(&q, &qd)
        );
        assert_eq!(
            velocities_zero::forward_dynamics(&q, &qd, &qdd),
            at_rest::forward_dynamics(&q, &qd, &qdd)
        );
        assert_eq!(
            moving::inverse_dynamics(&q, &qd, &qdd),
            full::inverse_dynamics(&q, &qd, &qdd)
        );
    }
}

#[test]
fn runtime_parameters_default_to_the_spec_and_follow_edits() {
    let p = tunable::Params::default();
    assert_eq!(p.m3, 22.0);
    let mut rng = common::rng(13);
    for _ in 0..200 {
        let (q, qd, qdd) = state(&mut rng, 3);
        let (q, qd, qdd) = (
            q.try_into().unwrap(),
            qd.try_into().unwrap(),
            qdd.try_into().unwrap(),
        );
        let constant = full::inverse_dynamics(&q, &qd, &qdd);
        assert!(rel_err(&tunable::inverse_dynamics(&p, &q, &qd, &qdd), &constant) < 1e-13);
    }
    // Doubling m3 at run time equals editing the spec's m3 (checked with the reference).
    let heavier = tunable::Params {
        m3: 44.0,
        ..tunable::Params::default()
    };
    let mut model = read_robot(
        Description::file(SPEC.as_ref()),
        &LoadOptions {
            symbolic_parameters: true,
            ..LoadOptions::default()
        },
    )
    .unwrap();
    model
        .parameters
        .iter_mut()
        .find(|p| p.name == "m3")
        .unwrap()
        .value = 44.0;
    let mut reference = rne_reference::Reference::new(&model.to_numeric());
    let (q, qd, qdd) = ([0.1, 0.7, -1.2], [0.5, -0.3, 2.0], [1.0, 0.2, -0.4]);
    let expected: Vec<f64> = reference
        .inverse_dynamics(&q, &qd, &qdd)
        .unwrap()
        .data
        .into();
    assert!(
        rel_err(
            &tunable::inverse_dynamics(&heavier, &q, &qd, &qdd),
            &expected
        ) < 1e-13
    );
}

#[test]
fn specialised_scenes_cost_fewer_operations() {
    let model = read_robot(Description::file(SPEC.as_ref()), &LoadOptions::default()).unwrap();
    let in_scene =
        |scene: Scene| generate(&model, &scene, &GenerationOptions::default(), "irb140").unwrap();
    let full = in_scene(Scene::default());
    let weightless = in_scene(Scene {
        gravity: Some([0.0; 3]),
        ..Scene::default()
    });
    let locked = in_scene(Scene {
        lock: vec![("q1".into(), 0.3), ("q2".into(), -0.5)],
        ..Scene::default()
    });
    let at_rest = in_scene(Scene {
        at_rest: true,
        ..Scene::default()
    });
    for (variant, name) in [
        (&weightless, "zero gravity"),
        (&locked, "locked q1, q2"),
        (&at_rest, "at rest"),
    ] {
        for (k, (special, general)) in variant.kernels.iter().zip(&full.kernels).enumerate() {
            assert_eq!(special.kernel, general.kernel);
            assert!(
                special.ops.total() <= general.ops.total(),
                "{name}: {} costs {} > {}",
                special.kernel,
                special.ops,
                general.ops
            );
            if special.kernel == Kernel::InverseDynamics {
                assert!(
                    special.ops.total() < general.ops.total(),
                    "{name}: inverse dynamics not cheaper ({k})"
                );
            }
        }
    }
    let with_options = |options: GenerationOptions| {
        generate(&model, &Scene::default(), &options, "irb140").unwrap()
    };
    let only_id = with_options(GenerationOptions {
        outputs: vec![Kernel::InverseDynamics],
        ..GenerationOptions::default()
    });
    assert_eq!(
        only_id.kernels.len(),
        1,
        "only what the scene asks for is generated"
    );
    let runtime = with_options(GenerationOptions {
        parameters: ParameterMode::Runtime,
        ..GenerationOptions::default()
    });
    assert_eq!(runtime.kernels.len(), full.kernels.len());
}
