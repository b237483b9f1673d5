//! Coupled (mimic) joints, friction and armature: each checked against a model built without
//! them and the formula that says what they add.

mod common;

use common::{
    coupled, fixture, floating, floating_three_body, matrix_rel_err, rel_err, rng, state,
    with_friction_and_armature, Mimic,
};
use nalgebra::{DMatrix, DVector};
use rne_reference::Reference;
use rne_symbolic::NumericModel;

/// Models and a mimic constraint on each: fixed-base arms and a floating robot, multipliers of
/// either sign, non-zero offsets.
fn coupled_cases() -> Vec<(NumericModel, Mimic)> {
    let mimic = |follower, leader, multiplier, offset| Mimic {
        follower,
        leader,
        multiplier,
        offset,
    };
    vec![
        (fixture("ur5.urdf"), mimic(2, 1, -0.7, 0.3)),
        (fixture("puma560.toml"), mimic(4, 0, 1.0, 0.0)),
        (fixture("panda-arm.urdf"), mimic(3, 5, 2.5, -0.4)),
        (floating_three_body(), mimic(2, 0, 1.3, -0.2)),
        (floating(&fixture("ur5.urdf")), mimic(0, 4, 0.5, 0.1)),
    ]
}

#[test]
fn a_coupled_model_equals_the_uncoupled_one_reduced_by_the_chain_rule() {
    let mut rng = rng(11);
    for (model, mimic) in coupled_cases() {
        let (coupled_model, map) = coupled(&model, mimic);
        let (mut full, mut reduced) = (Reference::new(&model), Reference::new(&coupled_model));
        let j = &map.jacobian;
        for _ in 0..30 {
            let (q, v, a) = state(&mut rng, &coupled_model);
            let (q_full, v_full, a_full) = (map.full_q(&q), map.full_v(&v), map.full_v(&a));
            let m_full = full.mass_matrix(&q_full).unwrap();
            let expected = j.transpose() * &m_full * j;
            let m = reduced.mass_matrix(&q).unwrap();
            assert!(
                matrix_rel_err(&m, &expected, 1.0) < 1e-12,
                "{}: M",
                model.name
            );
            let tau_full = full.inverse_dynamics(&q_full, &v_full, &a_full).unwrap();
            let expected = j.transpose() * tau_full;
            let tau = reduced.inverse_dynamics(&q, &v, &a).unwrap();
            assert!(
                rel_err(tau.as_slice(), expected.as_slice(), 1.0) < 1e-12,
                "{}: τ",
                model.name
            );
            let g_full = full.gravity_torques(&q_full).unwrap();
            let g = reduced.gravity_torques(&q).unwrap();
            let expected = j.transpose() * g_full;
            assert!(
                rel_err(g.as_slice(), expected.as_slice(), 1.0) < 1e-12,
                "{}: g",
                model.name
            );
            let (t, t_full) = (
                reduced.kinetic_energy(&q, &v).unwrap(),
                full.kinetic_energy(&q_full, &v_full).unwrap(),
            );
            assert!(
                (t - t_full).abs() < 1e-12 * t_full.abs().max(1.0),
                "{}: T",
                model.name
            );
        }
    }
}

#[test]
fn mimic_offsets_place_the_follower_where_the_uncoupled_model_puts_it() {
    let mut rng = rng(12);
    for (model, mimic) in coupled_cases() {
        let (coupled_model, map) = coupled(&model, mimic);
        let (mut full, mut reduced) = (Reference::new(&model), Reference::new(&coupled_model));
        for _ in 0..10 {
            let (q, _, _) = state(&mut rng, &coupled_model);
            let q_full = map.full_q(&q);
            let (frames, frames_full) = (
                reduced.frame_placements(&q).unwrap(),
                full.frame_placements(&q_full).unwrap(),
            );
            for ((r, p), (r_full, p_full)) in frames.iter().zip(&frames_full) {
                assert!((r - r_full).norm() < 1e-13 && (p - p_full).norm() < 1e-13);
            }
            let (v, v_full) = (
                reduced.potential_energy(&q).unwrap(),
                full.potential_energy(&q_full).unwrap(),
            );
            assert!(
                (v - v_full).abs() < 1e-12 * v_full.abs().max(1.0),
                "{}: V",
                model.name
            );
        }
    }
}

#[test]
fn forward_dynamics_of_a_coupled_model_inverts_its_inverse_dynamics() {
    let mut rng = rng(13);
    for (model, mimic) in coupled_cases() {
        let (coupled_model, _) = coupled(&with_friction_and_armature(&model), mimic);
        let mut reference = Reference::new(&coupled_model).with_friction(true);
        for _ in 0..30 {
            let (q, v, tau) = state(&mut rng, &coupled_model);
            let qdd = reference.forward_dynamics(&q, &v, &tau).unwrap();
            let back = reference.inverse_dynamics(&q, &v, qdd.as_slice()).unwrap();
            assert!(
                rel_err(back.as_slice(), &tau, 1.0) < 1e-10,
                "{}",
                model.name
            );
        }
    }
}

#[test]
fn friction_adds_viscous_coulomb_and_offset_torques_and_armature_adds_to_the_diagonal() {
    let mut rng = rng(14);
    for model in [fixture("ur5.urdf"), floating_three_body()] {
        let rich = with_friction_and_armature(&model);
        let mut plain = Reference::new(&model);
        let mut with_both = Reference::new(&rich).with_friction(true);
        let mut armature_only = Reference::new(&rich);
        let base = model.nv() - model.dof();
        let armature: Vec<f64> = (0..model.nv())
            .map(|k| {
                let link = rich
                    .links
                    .iter()
                    .find(|l| l.joint.map(|j| j + base) == Some(k));
                link.and_then(|l| l.armature).unwrap_or(0.0)
            })
            .collect();
        for _ in 0..20 {
            let (q, v, a) = state(&mut rng, &model);
            let m = plain.mass_matrix(&q).unwrap()
                + DMatrix::from_diagonal(&DVector::from_vec(armature.clone()));
            assert!(matrix_rel_err(&with_both.mass_matrix(&q).unwrap(), &m, 1.0) < 1e-14);
            let friction = with_both.friction_torques(&v).unwrap();
            for k in 0..model.nv() {
                let link = rich
                    .links
                    .iter()
                    .find(|l| l.joint.map(|j| j + base) == Some(k));
                let expected = link.and_then(|l| l.friction).map_or(0.0, |f| {
                    f.viscous * v[k] + f.coulomb * v[k].signum() + f.offset
                });
                assert_eq!(friction[k], expected);
            }
            let tau = plain.inverse_dynamics(&q, &v, &a).unwrap()
                + DVector::from_vec(armature.clone())
                    .component_mul(&DVector::from_column_slice(&a))
                + &friction;
            let actual = with_both.inverse_dynamics(&q, &v, &a).unwrap();
            assert!(rel_err(actual.as_slice(), tau.as_slice(), 1.0) < 1e-12);
            let without_friction = armature_only.inverse_dynamics(&q, &v, &a).unwrap();
            assert!(
                rel_err(
                    (actual - without_friction).as_slice(),
                    friction.as_slice(),
                    1.0
                ) < 1e-12
            );
            // The ABA with armature and friction inverts the RNEA with them.
            let qdd = with_both.forward_dynamics(&q, &v, tau.as_slice()).unwrap();
            assert!(rel_err(qdd.as_slice(), &a, 1.0) < 1e-10, "{}", model.name);
        }
    }
}

#[test]
fn coulomb_friction_vanishes_at_rest_leaving_the_offset() {
    let rich = with_friction_and_armature(&fixture("ur5.urdf"));
    let reference = Reference::new(&rich);
    let friction = reference.friction_torques(&[0.0; 6]).unwrap();
    for link in rich.links.iter().filter(|l| l.joint.is_some()) {
        assert_eq!(friction[link.joint.unwrap()], link.friction.unwrap().offset);
    }
}
