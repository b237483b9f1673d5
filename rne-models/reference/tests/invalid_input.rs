//! Wrong lengths, broken models and non-finite input on the floating-base, coupled and
//! derivative entry points: errors naming what is wrong, never a panic.

mod common;

use common::{coupled, floating_three_body, Mimic};
use rne_reference::{Reference, ReferenceError};
use rne_symbolic::model::Base;
use rne_symbolic::{JointKind, NumericModel};

fn wrong_length(argument: &'static str, expected: usize, found: usize) -> ReferenceError {
    ReferenceError::WrongLength {
        argument,
        expected,
        found,
    }
}

#[test]
fn a_floating_model_takes_nq_configurations_and_nv_velocities_and_names_the_wrong_argument() {
    let model = floating_three_body();
    let mut r = Reference::new(&model);
    assert_eq!((r.nq(), r.nv(), r.dof()), (10, 9, 3));
    let (q, v) = (vec![0.0; 10], vec![0.0; 9]);
    let short_q = &q[..9];
    let long_v = &q[..];
    assert_eq!(
        r.mass_matrix(short_q).unwrap_err(),
        wrong_length("q", 10, 9)
    );
    assert_eq!(
        r.inverse_dynamics(&q, long_v, &v).unwrap_err(),
        wrong_length("qd", 9, 10)
    );
    assert_eq!(
        r.forward_dynamics(&q, &v, long_v).unwrap_err(),
        wrong_length("tau", 9, 10)
    );
    assert_eq!(
        r.inverse_dynamics_derivatives(&q, &v, long_v).unwrap_err(),
        wrong_length("qdd", 9, 10)
    );
    assert_eq!(
        r.forward_dynamics_derivatives(short_q, &v, &v).unwrap_err(),
        wrong_length("q", 10, 9)
    );
    assert_eq!(
        r.mass_matrix_inverse(short_q).unwrap_err(),
        wrong_length("q", 10, 9)
    );
    assert_eq!(
        r.frame_placements(short_q).unwrap_err(),
        wrong_length("q", 10, 9)
    );
    assert_eq!(
        r.frame_jacobians(short_q).unwrap_err(),
        wrong_length("q", 10, 9)
    );
    assert_eq!(
        r.frame_jacobian_dot_qd(&q, long_v).unwrap_err(),
        wrong_length("qd", 9, 10)
    );
    assert_eq!(
        r.regressor(&q, &v, long_v).unwrap_err(),
        wrong_length("qdd", 9, 10)
    );
    assert_eq!(
        r.integrate(&q, long_v).unwrap_err(),
        wrong_length("v", 9, 10)
    );
    assert_eq!(
        r.friction_torques(long_v).unwrap_err(),
        wrong_length("qd", 9, 10)
    );
    assert_eq!(
        r.kinetic_energy(short_q, &v).unwrap_err(),
        wrong_length("q", 10, 9)
    );
    let mut m = vec![0.0; 80];
    assert_eq!(
        r.mass_matrix_into(&q, &mut m).unwrap_err(),
        wrong_length("out", 81, 80)
    );
}

#[test]
fn non_finite_input_gives_non_finite_derivatives_and_kinematics_without_panicking() {
    let model = floating_three_body();
    let mut r = Reference::new(&model);
    let mut q = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.1, 0.2, 0.3];
    q[8] = f64::NAN;
    let v = vec![0.5; 9];
    let (dq, _) = r.inverse_dynamics_derivatives(&q, &v, &v).unwrap();
    assert!(dq.iter().any(|x| x.is_nan()));
    let derivatives = r.forward_dynamics_derivatives(&q, &v, &v).unwrap();
    assert!(derivatives.dqdd_dq.iter().any(|x| x.is_nan()));
    assert!(r.frame_jacobians(&q).unwrap()[3].iter().any(|x| x.is_nan()));
    assert!(r.regressor(&q, &v, &v).unwrap().iter().any(|x| x.is_nan()));
}

/// The field named by an `InvalidModel` error.
fn invalid_field(model: &NumericModel) -> (String, &'static str) {
    match Reference::try_new(model).unwrap_err() {
        ReferenceError::InvalidModel { link, field, .. } => (link, field),
        other => panic!("{other}"),
    }
}

#[test]
fn broken_floating_and_coupled_models_are_rejected_naming_the_link_and_field() {
    let good = floating_three_body();

    let mut no_free_flyer = good.clone();
    no_free_flyer.links[0].kind = JointKind::Fixed;
    assert_eq!(invalid_field(&no_free_flyer), ("torso".into(), "kind"));

    let mut fixed_base_with_free_flyer = good.clone();
    fixed_base_with_free_flyer.base = Base::Fixed;
    assert_eq!(
        invalid_field(&fixed_base_with_free_flyer),
        ("torso".into(), "kind")
    );

    let mut free_flyer_inside = good.clone();
    free_flyer_inside.links[2].kind = JointKind::FreeFlyer;
    free_flyer_inside.links[2].joint = None;
    assert_eq!(invalid_field(&free_flyer_inside), ("slider".into(), "kind"));

    let mut coupled_fixed = good.clone();
    coupled_fixed.links[0].coupling = Some((1.0, 0.0));
    assert_eq!(invalid_field(&coupled_fixed), ("torso".into(), "coupling"));

    let mut shared = good.clone();
    shared.links[3].joint = Some(0);
    assert_eq!(invalid_field(&shared), ("hand".into(), "joint"));

    let mimic = Mimic {
        follower: 2,
        leader: 0,
        multiplier: 1.0,
        offset: 0.0,
    };
    let (coupled_model, _) = coupled(&good, mimic);
    assert!(Reference::try_new(&coupled_model).is_ok());
}
