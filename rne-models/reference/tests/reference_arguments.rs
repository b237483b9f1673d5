//! The reference's handling of non-finite input, wrong argument lengths and invalid models on
//! random fixed-base robots.

mod random_robots;

use nalgebra::DVector;
use random_robots::*;
use rne_reference::{Reference, ReferenceError};
use rne_symbolic::{JointKind, NumericModel};

/// A serial chain with all-NaN input gives NaN outputs, and no panic. Of M only the
/// off-diagonal entries are asserted: each passes through the transform of its column's joint,
/// while some diagonal entries (the last, `S_nᵀ I_n S_n`) do not depend on q at all.
#[test]
fn nan_input_gives_nan_output() {
    let mut specs = sample_link_specs(4);
    for (spec, kind) in specs.iter_mut().zip([0, 2, 1, 0]) {
        spec.kind = kind;
        spec.parent_choice = 0.0;
    }
    let mut reference = Reference::new(&robot(&specs, 0, [0.0, 0.0, -9.81]));
    let (finite, nan) = ([0.1, 0.2, 0.3, 0.4], [f64::NAN; 4]);
    let all_nan = |v: DVector<f64>| v.iter().all(|x| x.is_nan());
    assert!(all_nan(
        reference.inverse_dynamics(&nan, &finite, &finite).unwrap()
    ));
    assert!(all_nan(
        reference.inverse_dynamics(&finite, &nan, &finite).unwrap()
    ));
    assert!(all_nan(
        reference.inverse_dynamics(&finite, &finite, &nan).unwrap()
    ));
    assert!(all_nan(reference.gravity_torques(&nan).unwrap()));
    assert!(all_nan(reference.bias_torques(&finite, &nan).unwrap()));
    assert!(all_nan(
        reference.forward_dynamics(&nan, &finite, &finite).unwrap()
    ));
    assert!(all_nan(
        reference.forward_dynamics(&finite, &nan, &finite).unwrap()
    ));
    assert!(all_nan(
        reference.forward_dynamics(&finite, &finite, &nan).unwrap()
    ));
    assert!(reference.kinetic_energy(&finite, &nan).unwrap().is_nan());
    assert!(reference.kinetic_energy(&nan, &finite).unwrap().is_nan());
    assert!(reference.potential_energy(&nan).unwrap().is_nan());
    let m = reference.mass_matrix(&nan).unwrap();
    for (r, c) in (0..4).flat_map(|r| (0..4).map(move |c| (r, c))) {
        assert!(r == c || m[(r, c)].is_nan(), "{m}");
    }
}

#[test]
fn wrong_lengths_are_errors_naming_the_argument() {
    let (model, _) = sample_robot_and_state(3);
    let mut reference = Reference::new(&model);
    let n = reference.dof();
    let (ok, short) = (vec![0.0; n], vec![0.0; n - 1]);
    let wrong = |argument, expected, found| {
        Err::<(), _>(ReferenceError::WrongLength {
            argument,
            expected,
            found,
        })
    };
    assert_eq!(
        reference.inverse_dynamics(&ok, &ok, &short).map(drop),
        wrong("qdd", n, n - 1)
    );
    assert_eq!(
        reference.inverse_dynamics_into(&ok, &ok, &ok, &mut vec![0.0; n + 1]),
        wrong("tau", n, n + 1)
    );
    assert_eq!(
        reference.mass_matrix(&short).map(drop),
        wrong("q", n, n - 1)
    );
    assert_eq!(
        reference.mass_matrix_into(&ok, &mut vec![0.0; n]),
        wrong("out", n * n, n)
    );
    assert_eq!(
        reference.gravity_torques(&short).map(drop),
        wrong("q", n, n - 1)
    );
    assert_eq!(
        reference.bias_torques(&ok, &short).map(drop),
        wrong("qd", n, n - 1)
    );
    assert_eq!(
        reference.forward_dynamics(&ok, &ok, &short).map(drop),
        wrong("tau", n, n - 1)
    );
    assert_eq!(
        reference.kinetic_energy(&ok, &short).map(drop),
        wrong("qd", n, n - 1)
    );
    assert_eq!(reference.potential_energy(&[]).map(drop), wrong("q", n, 0));
}

#[test]
fn into_variants_equal_the_allocating_ones() {
    let (model, s) = sample_robot_and_state(3);
    let mut reference = Reference::new(&model);
    let n = reference.dof();
    let mut out = vec![0.0; n];
    reference
        .inverse_dynamics_into(&s.q, &s.qd, &s.qdd, &mut out)
        .unwrap();
    assert_eq!(
        out,
        reference
            .inverse_dynamics(&s.q, &s.qd, &s.qdd)
            .unwrap()
            .as_slice()
    );
    reference.gravity_torques_into(&s.q, &mut out).unwrap();
    assert_eq!(out, reference.gravity_torques(&s.q).unwrap().as_slice());
    reference.bias_torques_into(&s.q, &s.qd, &mut out).unwrap();
    assert_eq!(out, reference.bias_torques(&s.q, &s.qd).unwrap().as_slice());
    reference
        .forward_dynamics_into(&s.q, &s.qd, &s.qdd, &mut out)
        .unwrap();
    assert_eq!(
        out,
        reference
            .forward_dynamics(&s.q, &s.qd, &s.qdd)
            .unwrap()
            .as_slice()
    );
    let mut matrix = vec![0.0; n * n];
    reference.mass_matrix_into(&s.q, &mut matrix).unwrap();
    assert_eq!(matrix, reference.mass_matrix(&s.q).unwrap().as_slice());
}

#[test]
fn invalid_models_are_rejected_with_the_link_and_field() {
    let (model, _) = sample_robot_and_state(3);
    let field_of = |model: &NumericModel| match Reference::try_new(model) {
        Err(ReferenceError::InvalidModel { link, field, .. }) => (link, field),
        other => panic!("expected an invalid-model error, got {other:?}"),
    };
    let last = model.links.len() - 1;
    let name = model.links[last].name.clone();

    let mut bad = model.clone();
    bad.links[0].parent = Some(last);
    assert_eq!(field_of(&bad), (model.links[0].name.clone(), "parent"));

    let moving = model.links.iter().position(|l| l.joint.is_some()).unwrap();
    let mut bad = model.clone();
    bad.links[moving].axis = [0.0, 0.0, 2.0];
    bad.links[moving].kind = JointKind::Prismatic;
    assert_eq!(field_of(&bad), (model.links[moving].name.clone(), "axis"));

    let mut bad = model.clone();
    bad.links[last].rotation = [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    assert_eq!(field_of(&bad), (name.clone(), "rotation"));

    let mut bad = model.clone();
    bad.links[last].inertia[0][1] += 0.5;
    assert_eq!(field_of(&bad), (name, "inertia"));

    let mut bad = model.clone();
    bad.joint_names.push("extra".into());
    assert_eq!(field_of(&bad), ("joint_names".to_string(), "joint"));

    let second = model.links.iter().rposition(|l| l.joint.is_some()).unwrap();
    let mut bad = model.clone();
    bad.links[second].joint = model.links[moving].joint;
    assert_eq!(field_of(&bad), (model.links[second].name.clone(), "joint"));
}
