//! Every generated module's `Model` implements the runtime's `Dynamics` trait: the kernels
//! the module has return exactly what its functions return, the others `None`, whatever the
//! scalar and parameter mode.

use rne_codegen::{Dynamics, Kernel};

rne_codegen::derive_dynamics! {
    /// Constant parameters, f64.
    mod elbow {
        robot: "fixtures/robots/planar-elbow.toml",
        outputs: [inverse_dynamics, mass_matrix, kinetic_energy],
    }
}

rne_codegen::derive_dynamics! {
    /// Runtime parameters, generic scalar.
    mod elbow_generic {
        robot: "fixtures/robots/planar-elbow.toml",
        outputs: [gravity_torques, forward_dynamics, coriolis_matrix, bias_torques, potential_energy],
        parameters: runtime,
        scalar: generic,
    }
}

const Q: [f64; 2] = [0.4, -1.1];
const QD: [f64; 2] = [0.7, 0.2];
const QDD: [f64; 2] = [-0.3, 1.5];

#[test]
fn the_model_returns_the_modules_functions_and_none_for_the_rest() {
    let m = elbow::Model;
    assert_eq!(
        m.inverse_dynamics(&Q, &QD, &QDD),
        Some(elbow::inverse_dynamics(&Q, &QD, &QDD))
    );
    assert_eq!(m.mass_matrix(&Q), Some(elbow::mass_matrix(&Q)));
    assert_eq!(
        m.kinetic_energy(&Q, &QD),
        Some(elbow::kinetic_energy(&Q, &QD))
    );
    assert_eq!(m.gravity_torques(&Q), None);
    assert_eq!(m.forward_dynamics(&Q, &QD, &QDD), None);
    assert_eq!(
        elbow::Model::KERNELS,
        [
            Kernel::InverseDynamics,
            Kernel::MassMatrix,
            Kernel::KineticEnergy
        ]
    );
    assert_eq!(elbow::Model::NAME, "planar-elbow");
    assert_eq!(elbow::Model::JOINTS, elbow::JOINTS);
    const { assert!(!elbow::Model::FLOATING_BASE) };
    assert_eq!((elbow::NQ, elbow::NV), (2, 2));
}

#[test]
fn a_runtime_parameter_model_reads_its_own_parameters() {
    let model = elbow_generic::Model::<f64>::default();
    let p = elbow_generic::Params::default();
    assert_eq!(
        model.gravity_torques(&Q),
        Some(elbow_generic::gravity_torques(&p, &Q))
    );
    // g(q) is linear in the link masses.
    let heavier = elbow_generic::Params {
        m1: 2.0 * p.m1,
        m2: 2.0 * p.m2,
        ..p.clone()
    };
    let g = elbow_generic::Model::<f64>::new(heavier)
        .gravity_torques(&Q)
        .unwrap();
    let g1 = model.gravity_torques(&Q).unwrap();
    for k in 0..2 {
        assert!(
            (g[k] - 2.0 * g1[k]).abs() <= 1e-12 * g1[k].abs(),
            "{g:?} vs {g1:?}"
        );
    }
    assert!(model.has(Kernel::ForwardDynamics) && !model.has(Kernel::MassMatrix));
}

#[test]
fn a_generic_model_computes_in_its_scalar() {
    let p = elbow_generic::Params::default();
    let q32 = Q.map(|x| x as f32);
    let qd32 = QD.map(|x| x as f32);
    let model = elbow_generic::Model::<f32>::new(p.clone());
    let bias32 = model.bias_torques(&q32, &qd32).unwrap();
    let bias64 = elbow_generic::bias_torques(&p, &Q, &QD);
    for k in 0..2 {
        assert!((f64::from(bias32[k]) - bias64[k]).abs() <= 1e-4 * bias64[k].abs().max(1.0));
    }
    // Debug, Clone and Default need nothing of the scalar.
    let copy = model.clone();
    assert_eq!(format!("{copy:?}"), format!("Model {{ params: {p:?} }}"));
}

/// Generic code written once against the trait, for a model or a reference to one.
fn total_energy<D: Dynamics<2, 2, Scalar = f64>>(
    robot: D,
    q: &[f64; 2],
    qd: &[f64; 2],
) -> Option<f64> {
    Some(robot.kinetic_energy(q, qd)? + robot.potential_energy(q)?)
}

#[test]
fn generic_code_sees_which_kernels_a_module_has() {
    assert_eq!(total_energy(elbow::Model, &Q, &QD), None);
    let by_reference: &elbow::Model = &elbow::Model;
    assert_eq!(total_energy(by_reference, &Q, &QD), None);
}
