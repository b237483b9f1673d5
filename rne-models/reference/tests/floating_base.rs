//! Physics of a free-flyer root: free fall, momentum conservation, the equations of motion's
//! consistency (RNEA ∘ ABA, CRBA, energy), and Pinocchio's conventions for q and v.

mod common;

use common::{floating, floating_three_body, free_body, rel_err, rng, rotation_of, state, G};
use nalgebra::{DVector, Matrix3, Vector3};
use rne_reference::Reference;
use rne_symbolic::NumericModel;

/// Gravity of a model as a vector.
fn gravity(model: &NumericModel) -> Vector3<f64> {
    Vector3::from(model.gravity)
}

#[test]
fn a_free_body_at_rest_falls_with_body_frame_acceleration_r_transpose_g_in_every_orientation() {
    let model = free_body();
    let mut reference = Reference::new(&model);
    let mut rng = rng(1);
    for _ in 0..200 {
        let (q, _, _) = state(&mut rng, &model);
        let qdd = reference
            .forward_dynamics(&q, &[0.0; 6], &[0.0; 6])
            .unwrap();
        let expected = rotation_of(&q).transpose() * gravity(&model);
        let expected = [expected.x, expected.y, expected.z, 0.0, 0.0, 0.0];
        assert!(
            rel_err(qdd.as_slice(), &expected, 1.0) < 1e-14,
            "{qdd} vs {expected:?}"
        );
    }
}

#[test]
fn a_free_body_with_any_twist_has_its_centre_of_mass_accelerating_at_g() {
    let model = free_body();
    let com = Vector3::from(model.links[0].com);
    let mut reference = Reference::new(&model);
    let mut rng = rng(2);
    for _ in 0..200 {
        let (q, v, _) = state(&mut rng, &model);
        let a = reference.forward_dynamics(&q, &v, &[0.0; 6]).unwrap();
        let (v_lin, w) = (
            Vector3::new(v[0], v[1], v[2]),
            Vector3::new(v[3], v[4], v[5]),
        );
        let (a_lin, alpha) = (
            Vector3::new(a[0], a[1], a[2]),
            Vector3::new(a[3], a[4], a[5]),
        );
        // Classical acceleration of the body point c, body axes (v̇ the body-frame derivative).
        let com_acceleration =
            a_lin + w.cross(&v_lin) + alpha.cross(&com) + w.cross(&w.cross(&com));
        let world = rotation_of(&q) * com_acceleration;
        assert!((world - gravity(&model)).norm() < 1e-12 * G, "{world}");
    }
}

#[test]
fn inverse_dynamics_inverts_forward_dynamics_and_mass_matrix_is_symmetric_positive_definite() {
    let mut rng = rng(3);
    for model in [
        free_body(),
        floating_three_body(),
        floating(&common::fixture("ur5.urdf")),
    ] {
        let mut reference = Reference::new(&model);
        for _ in 0..50 {
            let (q, v, tau) = state(&mut rng, &model);
            let qdd = reference.forward_dynamics(&q, &v, &tau).unwrap();
            let back = reference.inverse_dynamics(&q, &v, qdd.as_slice()).unwrap();
            assert!(
                rel_err(back.as_slice(), &tau, 1.0) < 1e-10,
                "{}: {back} vs {tau:?}",
                model.name
            );
            let m = reference.mass_matrix(&q).unwrap();
            assert_eq!(m, m.transpose(), "{}", model.name);
            assert!(
                m.clone().cholesky().is_some(),
                "{}: M not positive definite",
                model.name
            );
            // The q̈ column of the RNEA is M: τ(q̈) − τ(0) = M q̈.
            let bias = reference.bias_torques(&q, &v).unwrap();
            let expected = &m * &qdd + &bias;
            assert!(
                rel_err(back.as_slice(), expected.as_slice(), 1.0) < 1e-10,
                "{}",
                model.name
            );
        }
    }
}

#[test]
fn kinetic_energy_is_half_v_transpose_m_v_and_potential_energy_follows_the_base_height() {
    let model = floating_three_body();
    let total_mass: f64 = model.links.iter().map(|l| l.mass).sum();
    let mut reference = Reference::new(&model);
    let mut rng = rng(4);
    for _ in 0..50 {
        let (q, v, _) = state(&mut rng, &model);
        let m = reference.mass_matrix(&q).unwrap();
        let v_vector = DVector::from_column_slice(&v);
        let expected = 0.5 * v_vector.dot(&(&m * &v_vector));
        let kinetic = reference.kinetic_energy(&q, &v).unwrap();
        assert!((kinetic - expected).abs() < 1e-12 * expected.max(1.0));
        // Raising the whole robot by h adds m g h.
        let potential = reference.potential_energy(&q).unwrap();
        let mut raised = q.clone();
        raised[2] += 0.7;
        let higher = reference.potential_energy(&raised).unwrap();
        assert!((higher - potential - total_mass * G * 0.7).abs() < 1e-12 * total_mass * G);
    }
}

#[test]
fn gravity_torques_are_the_weight_and_its_moment_in_the_base_frame() {
    // For a single body, g(q) = −[m Rᵀg; c × m Rᵀg]: the force that holds it up.
    let model = free_body();
    let (mass, com) = (model.links[0].mass, Vector3::from(model.links[0].com));
    let mut reference = Reference::new(&model);
    let mut rng = rng(5);
    for _ in 0..50 {
        let (q, _, _) = state(&mut rng, &model);
        let weight = rotation_of(&q).transpose() * gravity(&model) * mass;
        let moment = com.cross(&weight);
        let expected = [
            -weight.x, -weight.y, -weight.z, -moment.x, -moment.y, -moment.z,
        ];
        let g = reference.gravity_torques(&q).unwrap();
        assert!(rel_err(g.as_slice(), &expected, 1.0) < 1e-14, "{g}");
    }
}

/// `[linear momentum; angular momentum about the world origin]` in world axes: the base rows of
/// `M v` are the robot's total momentum in the base frame about the base origin.
fn world_momentum(reference: &mut Reference, q: &[f64], v: &[f64]) -> [f64; 6] {
    let m = reference.mass_matrix(q).unwrap();
    let h = m * DVector::from_column_slice(v);
    let r = rotation_of(q);
    let linear = r * Vector3::new(h[0], h[1], h[2]);
    let angular =
        r * Vector3::new(h[3], h[4], h[5]) + Vector3::new(q[0], q[1], q[2]).cross(&linear);
    [
        linear.x, linear.y, linear.z, angular.x, angular.y, angular.z,
    ]
}

/// dq/dt for a floating base: ṗ = R v_lin, quaternion rate ½ quat ⊗ [ω; 0], joints q̇ = v.
fn configuration_rate(q: &[f64], v: &[f64]) -> Vec<f64> {
    let r = rotation_of(q);
    let p_dot = r * Vector3::new(v[0], v[1], v[2]);
    let (w, qv, qs) = (
        Vector3::new(v[3], v[4], v[5]),
        Vector3::new(q[3], q[4], q[5]),
        q[6],
    );
    let quat_v = (w * qs + qv.cross(&w)) * 0.5;
    let quat_s = -0.5 * qv.dot(&w);
    let mut rate = vec![
        p_dot.x, p_dot.y, p_dot.z, quat_v.x, quat_v.y, quat_v.z, quat_s,
    ];
    rate.extend_from_slice(&v[6..]);
    rate
}

#[test]
fn total_momentum_is_conserved_over_ten_seconds_of_zero_gravity_joint_motion() {
    let mut model = floating_three_body();
    model.gravity = [0.0; 3];
    let mut reference = Reference::new(&model);
    let mut q = vec![0.1, -0.2, 0.3, 0.0, 0.0, 0.0, 1.0, 0.3, 0.05, -0.4];
    let mut v = vec![0.2, -0.1, 0.05, 0.3, -0.2, 0.4, 0.5, -0.2, 1.0];
    // Joint torques that drive the joints back and forth: internal forces only.
    let torque = |t: f64| {
        let mut tau = vec![0.0; 9];
        tau[6] = 0.8 * (2.0 * t).sin();
        tau[7] = -0.5 * (3.0 * t).cos();
        tau[8] = 0.2 * (5.0 * t).sin();
        tau
    };
    let initial = world_momentum(&mut reference, &q, &v);
    let mut derivative = |q: &[f64], v: &[f64], t: f64| {
        let a = reference.forward_dynamics(q, v, &torque(t)).unwrap();
        (configuration_rate(q, v), a.as_slice().to_vec())
    };
    let dt = 1e-3;
    let axpy = |x: &[f64], k: &[f64], h: f64| -> Vec<f64> {
        x.iter().zip(k).map(|(x, k)| x + h * k).collect()
    };
    for step in 0..10_000 {
        let t = step as f64 * dt;
        let (k1q, k1v) = derivative(&q, &v, t);
        let (k2q, k2v) = derivative(
            &axpy(&q, &k1q, dt / 2.0),
            &axpy(&v, &k1v, dt / 2.0),
            t + dt / 2.0,
        );
        let (k3q, k3v) = derivative(
            &axpy(&q, &k2q, dt / 2.0),
            &axpy(&v, &k2v, dt / 2.0),
            t + dt / 2.0,
        );
        let (k4q, k4v) = derivative(&axpy(&q, &k3q, dt), &axpy(&v, &k3v, dt), t + dt);
        for i in 0..q.len() {
            q[i] += dt / 6.0 * (k1q[i] + 2.0 * k2q[i] + 2.0 * k3q[i] + k4q[i]);
        }
        for i in 0..v.len() {
            v[i] += dt / 6.0 * (k1v[i] + 2.0 * k2v[i] + 2.0 * k3v[i] + k4v[i]);
        }
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
    }
    let last = world_momentum(&mut reference, &q, &v);
    // RK4's truncation error at this step leaves ~2e-9; momentum exchanged with the base through
    // a wrong term would show as a drift of order one.
    assert!(
        rel_err(&last, &initial, 1.0) < 1e-7,
        "{last:?} vs {initial:?}"
    );
    // The joints did move: the test is not of a rigid body.
    assert!((q[7] - 0.3).abs() > 0.01 || (q[8] - 0.05).abs() > 0.01);
}

#[test]
fn the_base_rows_of_the_mass_matrix_are_the_composite_inertia_of_the_whole_robot() {
    // At a joint configuration, the 6×6 base block of M is the robot's spatial inertia about the
    // base origin: its mass block is the total mass.
    let model = floating_three_body();
    let total_mass: f64 = model.links.iter().map(|l| l.mass).sum();
    let mut reference = Reference::new(&model);
    let (q, _, _) = state(&mut rng(6), &model);
    let m = reference.mass_matrix(&q).unwrap();
    let mass_block = m.view((0, 0), (3, 3)).into_owned();
    assert!((mass_block - Matrix3::identity() * total_mass).norm() < 1e-13);
}
