//! Every generated kernel of every built-in robot against the independent numeric reference
//! (spatial RNEA, CRBA, ABA), over 10 000 seeded random states, in f64.

mod common;

use common::{flat, mat_vec, rel_err, state, Worst};
use rne_models::{RobotSource, BUILTIN_ROBOTS};
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;

const SAMPLES: usize = 10_000;
const TOLERANCE: f64 = 1e-13;

#[test]
fn generated_kernels_agree_with_the_numeric_reference_on_every_builtin_robot() {
    for robot in BUILTIN_ROBOTS {
        let model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .unwrap();
        let mut reference = Reference::new(&model.to_numeric());
        // C(q, q̇) q̇ of the reference is its bias without gravity (not bias − g, which
        // cancels digits when the velocities are small).
        let mut weightless = model.to_numeric();
        weightless.gravity = [0.0; 3];
        let mut weightless = Reference::new(&weightless);
        common::with_generated(robot, |kernels| {
            let n = kernels.dof();
            assert_eq!(
                kernels.joints(),
                model.joint_names(),
                "{}: joint order",
                robot.name
            );
            let mut rng = common::rng(0x5eed_0001);
            let mut worst: [(&str, Worst); 8] = [
                ("tau", Worst::default()),
                ("M", Worst::default()),
                ("g", Worst::default()),
                ("bias", Worst::default()),
                ("C qd", Worst::default()),
                ("qdd", Worst::default()),
                ("kinetic", Worst::default()),
                ("potential", Worst::default()),
            ];
            for k in 0..SAMPLES {
                let (q, qd, qdd) = state(&mut rng, n);
                let tau_ref: Vec<f64> = reference
                    .inverse_dynamics(&q, &qd, &qdd)
                    .unwrap()
                    .data
                    .into();
                let tau = kernels.inverse_dynamics(&q, &qd, &qdd).unwrap();
                worst[0].1.record(rel_err(&tau, &tau_ref), k);

                let m_ref: Vec<f64> = reference.mass_matrix(&q).unwrap().transpose().data.into();
                worst[1]
                    .1
                    .record(rel_err(&flat(&kernels.mass_matrix(&q).unwrap()), &m_ref), k);

                let g_ref: Vec<f64> = reference.gravity_torques(&q).unwrap().data.into();
                worst[2]
                    .1
                    .record(rel_err(&kernels.gravity_torques(&q).unwrap(), &g_ref), k);

                let bias_ref: Vec<f64> = reference.bias_torques(&q, &qd).unwrap().data.into();
                worst[3].1.record(
                    rel_err(&kernels.bias_torques(&q, &qd).unwrap(), &bias_ref),
                    k,
                );

                let c_qd = mat_vec(&kernels.coriolis_matrix(&q, &qd).unwrap(), &qd);
                let c_qd_ref: Vec<f64> = weightless.bias_torques(&q, &qd).unwrap().data.into();
                worst[4].1.record(rel_err(&c_qd, &c_qd_ref), k);

                // Forward dynamics from random torques of the size of the gravity torques: torques
                // made as τ(q̈) would cancel most of their digits against the bias when q̈ is
                // small, which measures that cancellation rather than the solve.
                let scale = g_ref.iter().fold(10.0, |m: f64, g| m.max(g.abs()));
                let tau_in = common::uniform(&mut rng, n, scale);
                let qdd_ref: Vec<f64> = reference
                    .forward_dynamics(&q, &qd, &tau_in)
                    .unwrap()
                    .data
                    .into();
                worst[5].1.record(
                    rel_err(
                        &kernels.forward_dynamics(&q, &qd, &tau_in).unwrap(),
                        &qdd_ref,
                    ),
                    k,
                );

                let t_ref = reference.kinetic_energy(&q, &qd).unwrap();
                worst[6].1.record(
                    rel_err(&[kernels.kinetic_energy(&q, &qd).unwrap()], &[t_ref]),
                    k,
                );
                // V crosses zero (its zero is the base origin), so its error is taken relative to
                // the size of the gravity torques, which share its units (N·m = J).
                let v_ref = reference.potential_energy(&q).unwrap();
                let v_scale = g_ref.iter().fold(v_ref.abs(), |m, g| m.max(g.abs()));
                let v = kernels.potential_energy(&q).unwrap();
                worst[7].1.record((v - v_ref).abs() / v_scale, k);
            }
            for (name, w) in &worst {
                assert!(
                    w.error <= TOLERANCE,
                    "{}: {name} relative error {:e} at sample {} exceeds {TOLERANCE:e}",
                    robot.name,
                    w.error,
                    w.sample
                );
            }
        });
    }
}

#[test]
fn forward_dynamics_inverts_inverse_dynamics() {
    for robot in BUILTIN_ROBOTS {
        common::with_generated(robot, |kernels| {
            let n = kernels.dof();
            let mut rng = common::rng(0x5eed_0002);
            for k in 0..SAMPLES {
                let (q, qd, qdd) = state(&mut rng, n);
                let tau = kernels.inverse_dynamics(&q, &qd, &qdd).unwrap();
                let back = kernels.forward_dynamics(&q, &qd, &tau).unwrap();
                let error = rel_err(&back, &qdd);
                assert!(
                    error <= 1e-11,
                    "{}: fd(id(qdd)) != qdd, error {error:e} at sample {k}",
                    robot.name
                );
            }
        });
    }
}

#[test]
fn christoffel_matrix_is_symmetric_in_velocity_and_makes_mdot_minus_2c_skew() {
    for robot in BUILTIN_ROBOTS {
        let model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .unwrap();
        let mut reference = Reference::new(&model.to_numeric());
        common::with_generated(robot, |kernels| {
            let n = kernels.dof();
            let mut rng = common::rng(0x5eed_0003);
            for _ in 0..200 {
                let (q, x, y) = state(&mut rng, n);
                // C(q, x) y = C(q, y) x: the Christoffel symbols are symmetric in their last indices.
                let cxy = mat_vec(&kernels.coriolis_matrix(&q, &x).unwrap(), &y);
                let cyx = mat_vec(&kernels.coriolis_matrix(&q, &y).unwrap(), &x);
                assert!(
                    rel_err(&cxy, &cyx) < 1e-12,
                    "{}: C(q,x)y != C(q,y)x",
                    robot.name
                );
                // Ṁ = C + Cᵀ, with Ṁ from the reference CRBA by a central difference along q̇ = x.
                let h = 1e-6;
                let shifted =
                    |s: f64| -> Vec<f64> { q.iter().zip(&x).map(|(q, v)| q + s * v).collect() };
                let m_plus = reference.mass_matrix(&shifted(h)).unwrap();
                let m_minus = reference.mass_matrix(&shifted(-h)).unwrap();
                let mdot = (m_plus - m_minus) / (2.0 * h);
                let c = kernels.coriolis_matrix(&q, &x).unwrap();
                let scale = mdot.amax().max(1.0);
                for i in 0..n {
                    for j in 0..n {
                        let skew_defect = mdot[(i, j)] - c[i][j] - c[j][i];
                        assert!(
                            skew_defect.abs() < 1e-7 * scale,
                            "{}: Mdot - 2C not skew at ({i},{j})",
                            robot.name
                        );
                    }
                }
            }
        });
    }
}

#[test]
fn expression_graphs_with_symbolic_parameters_agree_with_the_reference_on_the_thesis_robots() {
    use common::SliceModel;
    use rne_interpreted::Interpreted;
    for name in ["planar-elbow", "irb140-3dof"] {
        let robot = rne_models::builtin(name).unwrap();
        let symbolic = RobotSource::Builtin(robot)
            .load(&LoadOptions {
                symbolic_parameters: true,
                ..LoadOptions::default()
            })
            .unwrap();
        assert!(!symbolic.parameters.is_empty());
        let programs = Interpreted::new(&symbolic);
        SliceModel::programs(&programs, |graph| {
            let mut reference = Reference::new(&symbolic.to_numeric());
            let mut weightless = symbolic.to_numeric();
            weightless.gravity = [0.0; 3];
            let mut weightless = Reference::new(&weightless);
            let n = graph.dof();
            let mut rng = common::rng(0x5eed_0004);
            for k in 0..1000 {
                let (q, qd, qdd) = state(&mut rng, n);
                let tau_ref: Vec<f64> = reference
                    .inverse_dynamics(&q, &qd, &qdd)
                    .unwrap()
                    .data
                    .into();
                assert!(
                    rel_err(&graph.inverse_dynamics(&q, &qd, &qdd).unwrap(), &tau_ref) <= 1e-12,
                    "{name} tau {k}"
                );
                let m_ref: Vec<f64> = reference.mass_matrix(&q).unwrap().transpose().data.into();
                assert!(
                    rel_err(&flat(&graph.mass_matrix(&q).unwrap()), &m_ref) <= 1e-12,
                    "{name} M {k}"
                );
                let g_ref: Vec<f64> = reference.gravity_torques(&q).unwrap().data.into();
                assert!(
                    rel_err(&graph.gravity_torques(&q).unwrap(), &g_ref) <= 1e-12,
                    "{name} g {k}"
                );
                let c_qd = mat_vec(&graph.coriolis_matrix(&q, &qd).unwrap(), &qd);
                let c_qd_ref: Vec<f64> = weightless.bias_torques(&q, &qd).unwrap().data.into();
                assert!(rel_err(&c_qd, &c_qd_ref) <= 1e-12, "{name} C qd {k}");
            }
        });
    }
}
