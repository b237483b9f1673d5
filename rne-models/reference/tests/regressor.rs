//! The regressor `τ = Y(q, q̇, q̈) π`: against the RNEA on every kind of model, and the layout
//! of the standard parameters.

mod common;

use common::{
    coupled, fixture, floating, floating_three_body, free_body, rel_err, rng, state,
    with_fixed_payload, with_friction_and_armature, Mimic, FIXTURES,
};
use nalgebra::DVector;
use rne_reference::Reference;
use rne_symbolic::NumericModel;

fn models() -> Vec<NumericModel> {
    let mut models: Vec<NumericModel> = FIXTURES.iter().map(|f| fixture(f)).collect();
    models.push(free_body());
    models.push(floating_three_body());
    models.push(floating(&fixture("panda-arm.urdf")));
    let mimic = Mimic {
        follower: 3,
        leader: 1,
        multiplier: -0.6,
        offset: 0.4,
    };
    models.push(coupled(&with_friction_and_armature(&fixture("ur5.urdf")), mimic).0);
    models.push(with_friction_and_armature(&floating_three_body()));
    models.push(with_friction_and_armature(&fixture("puma560.toml")));
    models.push(with_fixed_payload(&fixture("ur5.urdf")));
    models.push(with_fixed_payload(&floating_three_body()));
    models
}

#[test]
fn the_regressor_times_the_standard_parameters_is_inverse_dynamics() {
    let mut rng = rng(41);
    for model in models() {
        for friction in [false, true] {
            let mut reference = Reference::new(&model).with_friction(friction);
            let pi = DVector::from_vec(reference.standard_parameters());
            assert_eq!(pi.len(), reference.parameter_names().len());
            for _ in 0..50 {
                let (q, v, a) = state(&mut rng, &model);
                let y = reference.regressor(&q, &v, &a).unwrap();
                assert_eq!(y.shape(), (model.nv(), pi.len()));
                let tau = reference.inverse_dynamics(&q, &v, &a).unwrap();
                let predicted = &y * &pi;
                assert!(
                    rel_err(predicted.as_slice(), tau.as_slice(), 1.0) < 1e-12,
                    "{} (friction {friction}): {predicted} vs {tau}",
                    model.name
                );
            }
        }
    }
}

#[test]
fn standard_parameters_follow_pinocchios_order_about_the_body_origin() {
    // The free body's inertia about its origin: Ī = I_c + m (|c|² 1 − c cᵀ).
    let model = free_body();
    let link = &model.links[0];
    let reference = Reference::new(&model);
    let pi = reference.standard_parameters();
    let (m, c) = (link.mass, link.com);
    let c2 = c.iter().map(|x| x * x).sum::<f64>();
    let about_origin =
        |r: usize, k: usize| link.inertia[r][k] + m * (if r == k { c2 } else { 0.0 } - c[r] * c[k]);
    let expected = [
        m,
        m * c[0],
        m * c[1],
        m * c[2],
        about_origin(0, 0),
        about_origin(0, 1),
        about_origin(1, 1),
        about_origin(0, 2),
        about_origin(1, 2),
        about_origin(2, 2),
    ];
    assert!(
        rel_err(&pi, &expected, 1.0) < 1e-15,
        "{pi:?} vs {expected:?}"
    );
    assert_eq!(
        reference.parameter_names(),
        ["m", "mcx", "mcy", "mcz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz"]
            .map(|p| format!("torso.{p}"))
    );
}

#[test]
fn joint_parameters_follow_the_bodies_friction_only_when_included() {
    let model = with_friction_and_armature(&fixture("planar-elbow.toml"));
    let bodies = model.links.iter().filter(|l| l.joint.is_some()).count();
    let without = Reference::new(&model);
    let with = Reference::new(&model).with_friction(true);
    assert_eq!(without.parameter_count(), 10 * bodies + bodies);
    assert_eq!(with.parameter_count(), 10 * bodies + 4 * bodies);
    let names = with.parameter_names();
    let first_joint = &model.links.iter().find(|l| l.joint.is_some()).unwrap().name;
    assert_eq!(
        names[10 * bodies..10 * bodies + 4],
        ["fv", "fc", "f0", "Ia"].map(|p| format!("{first_joint}.{p}"))
    );
}
