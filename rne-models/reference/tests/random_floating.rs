//! The equations-of-motion identities on random trees put on a floating base and, when they
//! have two joints or more, with one joint coupled to another (proptest).

mod common;
mod random_robots;

use common::{coupled, floating, rel_err, with_friction_and_armature, Mimic};
use nalgebra::DVector;
use proptest::prelude::*;
use random_robots::robot_and_state;
use rne_reference::Reference;
use rne_symbolic::NumericModel;

/// A floating (and possibly coupled) random robot and a state for it: base pose from a random
/// unit quaternion and position, base velocity and acceleration-like entries.
fn floating_robot_and_state() -> impl Strategy<Value = (NumericModel, Vec<f64>, Vec<f64>, Vec<f64>)>
{
    (
        robot_and_state(),
        [-1.0..1.0f64, -1.0..1.0, -1.0..1.0, -1.0..1.0],
        prop::array::uniform6(-2.0..2.0f64),
        prop::array::uniform6(-3.0..3.0f64),
        -2.0..2.0f64,
        -1.0..1.0f64,
        any::<bool>(),
    )
        .prop_filter("a usable quaternion", |(_, quaternion, ..)| {
            quaternion.iter().map(|x| x * x).sum::<f64>() > 0.01
        })
        .prop_map(
            |((model, s), quaternion, base_v, base_a, multiplier, offset, with_joint_terms)| {
                let norm = quaternion.iter().map(|x| x * x).sum::<f64>().sqrt();
                let mut q = vec![0.3, -0.2, 0.5];
                q.extend(quaternion.map(|x| x / norm));
                let mut floating_model = floating(&model);
                if with_joint_terms {
                    floating_model = with_friction_and_armature(&floating_model);
                }
                let mut joints = s.q.clone();
                let (mut v, mut a) = (base_v.to_vec(), base_a.to_vec());
                v.extend(&s.qd);
                a.extend(&s.qdd);
                if model.dof() >= 2 && multiplier.abs() > 0.1 {
                    let mimic = Mimic {
                        follower: model.dof() - 1,
                        leader: 0,
                        multiplier,
                        offset,
                    };
                    floating_model = coupled(&floating_model, mimic).0;
                    joints.pop();
                    v.pop();
                    a.pop();
                }
                q.extend(joints);
                (floating_model, q, v, a)
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_floating_and_coupled_robots_satisfy_the_equations_of_motion(
        (model, q, v, a) in floating_robot_and_state()
    ) {
        let mut reference = Reference::new(&model).with_friction(true);
        let tau = reference.inverse_dynamics(&q, &v, &a).unwrap();
        // RNEA ∘ ABA (or the Cholesky solve of a coupled model) is the identity.
        let qdd = reference.forward_dynamics(&q, &v, tau.as_slice()).unwrap();
        prop_assert!(rel_err(qdd.as_slice(), &a, 1.0) < 1e-8, "{qdd} vs {a:?}");
        // M is symmetric positive definite, and τ = M q̈ + bias + friction.
        let m = reference.mass_matrix(&q).unwrap();
        prop_assert_eq!(&m, &m.transpose());
        prop_assert!(m.clone().cholesky().is_some());
        let split = &m * DVector::from_column_slice(&a)
            + reference.bias_torques(&q, &v).unwrap()
            + reference.friction_torques(&v).unwrap();
        prop_assert!(rel_err(split.as_slice(), tau.as_slice(), 1.0) < 1e-10);
        // T = ½ vᵀ M v, from the COM form of the energy.
        let v_vector = DVector::from_column_slice(&v);
        let kinetic = 0.5 * v_vector.dot(&(&m * &v_vector));
        let energy = reference.kinetic_energy(&q, &v).unwrap();
        prop_assert!((energy - kinetic).abs() < 1e-10 * kinetic.max(1.0));
        // Y π = τ from the per-body regressor.
        let pi = DVector::from_vec(reference.standard_parameters());
        let predicted = reference.regressor(&q, &v, &a).unwrap() * pi;
        prop_assert!(rel_err(predicted.as_slice(), tau.as_slice(), 1.0) < 1e-10);
        // ∂q̈/∂x = −M⁻¹ ∂τ/∂x at q̈ = FD(q, q̇, τ).
        let derivatives = reference.forward_dynamics_derivatives(&q, &v, tau.as_slice()).unwrap();
        let (dtau_dq, dtau_dv) = reference.inverse_dynamics_derivatives(&q, &v, qdd.as_slice()).unwrap();
        let expected = -&derivatives.mass_matrix_inverse * dtau_dq;
        let scale = expected.amax().max(1.0);
        prop_assert!((&derivatives.dqdd_dq - &expected).amax() < 1e-7 * scale);
        let expected = -&derivatives.mass_matrix_inverse * dtau_dv;
        let scale = expected.amax().max(1.0);
        prop_assert!((&derivatives.dqdd_dqd - &expected).amax() < 1e-7 * scale);
    }
}
