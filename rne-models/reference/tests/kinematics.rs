//! Frame placements, Jacobians and `J̇ q̇`: each against finite differences of the quantity it
//! is the derivative of, in the tangent space of the configuration.

mod common;

use common::{
    coupled, fixture, floating, floating_three_body, rel_err, rng, rotation_of, state,
    with_fixed_payload, Mimic, FIXTURES,
};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3, Vector6};
use rne_reference::Reference;
use rne_symbolic::NumericModel;

const H: f64 = 1e-6;

fn models() -> Vec<NumericModel> {
    let mut models: Vec<NumericModel> = FIXTURES.iter().map(|f| fixture(f)).collect();
    models.push(floating_three_body());
    models.push(floating(&fixture("panda-arm.urdf")));
    let mimic = Mimic {
        follower: 1,
        leader: 3,
        multiplier: 0.8,
        offset: -0.3,
    };
    models.push(coupled(&floating(&fixture("ur5.urdf")), mimic).0);
    models.push(with_fixed_payload(&floating_three_body()));
    models
}

/// The angular velocity ω (world axes) that rotates `minus` into `plus` in time `2h`:
/// `R₊ R₋ᵀ ≈ 1 + 2h ω×`.
fn angular_rate(plus: &Matrix3<f64>, minus: &Matrix3<f64>) -> Vector3<f64> {
    let d = plus * minus.transpose();
    Vector3::new(
        d[(2, 1)] - d[(1, 2)],
        d[(0, 2)] - d[(2, 0)],
        d[(1, 0)] - d[(0, 1)],
    ) / (4.0 * H)
}

#[test]
fn placements_of_a_floating_base_are_its_position_and_quaternion_and_fixed_links_ride_along() {
    let model = floating(&fixture("ur5.urdf"));
    let mut reference = Reference::new(&model);
    let (q, _, _) = state(&mut rng(31), &model);
    let frames = reference.frame_placements(&q).unwrap();
    assert_eq!(frames.len(), model.links.len());
    assert!((frames[0].0 - rotation_of(&q)).norm() < 1e-15);
    assert_eq!(frames[0].1, Vector3::new(q[0], q[1], q[2]));
    // A link behind a fixed joint keeps its constant offset from its parent.
    for (i, link) in model.links.iter().enumerate().skip(1) {
        if link.joint.is_none() {
            let p = link.parent.unwrap();
            let expected = frames[p].1 + frames[p].0 * Vector3::from(link.translation);
            assert!((frames[i].1 - expected).norm() < 1e-14, "{}", link.name);
        }
    }
}

#[test]
fn frame_jacobians_are_the_derivatives_of_the_placements() {
    let mut rng = rng(32);
    for model in models() {
        let mut reference = Reference::new(&model);
        for _ in 0..5 {
            let (q, _, _) = state(&mut rng, &model);
            let jacobians = reference.frame_jacobians(&q).unwrap();
            let n = model.nv();
            for j in 0..n {
                let mut step = vec![0.0; n];
                step[j] = H;
                let plus = reference.integrate(&q, &step).unwrap();
                step[j] = -H;
                let minus = reference.integrate(&q, &step).unwrap();
                let (frames_plus, frames_minus) = (
                    reference.frame_placements(plus.as_slice()).unwrap(),
                    reference.frame_placements(minus.as_slice()).unwrap(),
                );
                for (f, jacobian) in jacobians.iter().enumerate() {
                    let ((r_plus, p_plus), (r_minus, p_minus)) =
                        (&frames_plus[f], &frames_minus[f]);
                    let velocity = (p_plus - p_minus) / (2.0 * H);
                    let omega = angular_rate(r_plus, r_minus);
                    let expected = [
                        velocity.x, velocity.y, velocity.z, omega.x, omega.y, omega.z,
                    ];
                    let column: Vec<f64> = jacobian.column(j).iter().copied().collect();
                    assert!(
                        rel_err(&column, &expected, 1.0) < 1e-8,
                        "{} frame {f} column {j}: {column:?} vs {expected:?}",
                        model.name
                    );
                }
            }
        }
    }
}

#[test]
fn jacobian_dot_qd_is_the_time_derivative_of_the_jacobian_along_the_motion_times_qd() {
    let mut rng = rng(33);
    for model in models() {
        let mut reference = Reference::new(&model);
        for _ in 0..5 {
            let (q, v, _) = state(&mut rng, &model);
            let actual = reference.frame_jacobian_dot_qd(&q, &v).unwrap();
            let step: Vec<f64> = v.iter().map(|x| x * H).collect();
            let back: Vec<f64> = v.iter().map(|x| -x * H).collect();
            let plus = reference.integrate(&q, &step).unwrap();
            let minus = reference.integrate(&q, &back).unwrap();
            let (j_plus, j_minus) = (
                reference.frame_jacobians(plus.as_slice()).unwrap(),
                reference.frame_jacobians(minus.as_slice()).unwrap(),
            );
            let v_vector = DVector::from_column_slice(&v);
            for (f, jdqd) in actual.iter().enumerate() {
                let derivative: DMatrix<f64> = (&j_plus[f] - &j_minus[f]) / (2.0 * H);
                let expected = derivative * &v_vector;
                assert!(
                    rel_err(jdqd.as_slice(), expected.as_slice(), 1.0) < 1e-7,
                    "{} frame {f}: {jdqd} vs {expected}",
                    model.name
                );
            }
        }
    }
}

#[test]
fn task_acceleration_is_j_qdd_plus_jdot_qd_as_the_second_difference_of_the_placement() {
    // Along q(t) = q ⊕ (v t + ½ a t²) (joint space; the base's body-frame velocity is constant
    // plus a t), the frame origin's acceleration is J a + J̇ v.
    let model = fixture("ur5.urdf");
    let mut reference = Reference::new(&model);
    let (q, v, a) = state(&mut rng(34), &model);
    let h = 1e-4;
    let at = |t: f64| -> Vec<f64> {
        q.iter()
            .zip(&v)
            .zip(&a)
            .map(|((q, v), a)| q + v * t + 0.5 * a * t * t)
            .collect()
    };
    let origin = |reference: &mut Reference, q: &[f64], f: usize| {
        reference.frame_placements(q).unwrap()[f].1
    };
    let jacobians = reference.frame_jacobians(&q).unwrap();
    let jdqd = reference.frame_jacobian_dot_qd(&q, &v).unwrap();
    for f in 0..model.links.len() {
        let second = (origin(&mut reference, &at(h), f) - 2.0 * origin(&mut reference, &q, f)
            + origin(&mut reference, &at(-h), f))
            / (h * h);
        let predicted: Vector6<f64> =
            Vector6::from_column_slice((&jacobians[f] * DVector::from_column_slice(&a)).as_slice())
                + jdqd[f];
        let linear = Vector3::new(predicted[0], predicted[1], predicted[2]);
        assert!(
            (second - linear).norm() < 1e-5 * linear.norm().max(1.0),
            "frame {f}"
        );
    }
}
