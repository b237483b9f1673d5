//! `parameters: base` on the planar elbow, compiled: the `Params` fields are the six base
//! parameters (the thesis's groups of (4.45)–(4.47)), `Params::default()` those of the spec,
//! `Params::from_standard` those of any masses and inertias, and every kernel is an exact
//! function of them — equal to the constant-parameter kernels at the defaults, to the
//! numeric reference of another robot at its base parameters, and blind to the standard
//! parameters the dynamics do not determine.

mod common;

use common::{rel_err, state};
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::NumericModel;
use rne_symbolic::{read_robot, Description};

rne_codegen::derive_dynamics! {
    /// Constant parameters.
    mod elbow {
        robot: "fixtures/robots/planar-elbow.toml",
        outputs: [inverse_dynamics, mass_matrix, coriolis_matrix, gravity_torques, bias_torques,
                  forward_dynamics, kinetic_energy, potential_energy,
                  inverse_dynamics_derivatives, base_regressor],
    }
}

rne_codegen::derive_dynamics! {
    /// The base parameters at run time.
    mod elbow_base {
        robot: "fixtures/robots/planar-elbow.toml",
        outputs: [inverse_dynamics, mass_matrix, coriolis_matrix, gravity_torques, bias_torques,
                  forward_dynamics, kinetic_energy, potential_energy,
                  inverse_dynamics_derivatives, base_regressor],
        parameters: base,
    }
}

fn planar_elbow() -> NumericModel {
    let spec = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/robots/planar-elbow.toml"
    );
    read_robot(Description::file(spec.as_ref()), &LoadOptions::default())
        .expect("the planar elbow loads")
        .to_numeric()
}

type State = ([f64; 2], [f64; 2], [f64; 2]);

fn states(seed: u64, count: usize) -> Vec<State> {
    let mut rng = common::rng(seed);
    (0..count)
        .map(|_| {
            let (q, qd, qdd) = state(&mut rng, 2);
            (
                q.try_into().unwrap(),
                qd.try_into().unwrap(),
                qdd.try_into().unwrap(),
            )
        })
        .collect()
}

/// The standard parameters of `model` in `PARAMETERS` order, as the module's array.
fn standard(model: &NumericModel) -> [f64; elbow_base::NP] {
    let reference = Reference::new(model);
    assert_eq!(reference.parameter_names(), elbow_base::PARAMETERS);
    reference
        .standard_parameters()
        .try_into()
        .expect("NP parameters")
}

#[test]
fn the_fields_are_the_thesiss_groups_and_default_to_the_spec() {
    assert_eq!(
        elbow_base::BASE_PARAMETERS,
        [
            "link1.mcxR",
            "link1.mcy",
            "link1.IzzR",
            "link2.mcx",
            "link2.mcy",
            "link2.Izz"
        ]
    );
    let p = elbow_base::Params::default();
    // Table 6.1: m = 15 kg, l = 0.3 m, lc = l/2, I = m (l² + w²)/12 with w² = m / (ρ l).
    let (m, l, lc) = (15.0, 0.3, 0.15);
    let i = m * (l * l + m / (7850.0 * l)) / 12.0;
    let thesis = [
        (p.link1_mcxR, m * lc + m * l),
        (p.link1_mcy, 0.0),
        (p.link1_IzzR, i + m * lc * lc + m * l * l),
        (p.link2_mcx, m * lc),
        (p.link2_mcy, 0.0),
        (p.link2_Izz, i + m * lc * lc),
    ];
    for (value, expected) in thesis {
        assert!((value - expected).abs() <= 1e-14 * expected.abs().max(1.0));
    }
    let pi = standard(&planar_elbow());
    let from_standard = elbow_base::Params::from_standard(&pi);
    let mapped = elbow_base::base_parameters(&p, &pi);
    let fields = [
        from_standard.link1_mcxR,
        from_standard.link1_mcy,
        from_standard.link1_IzzR,
        from_standard.link2_mcx,
        from_standard.link2_mcy,
        from_standard.link2_Izz,
    ];
    assert!(
        rel_err(&fields, &mapped) < 1e-15,
        "from_standard = base_parameters"
    );
    assert!(
        rel_err(&fields, &thesis.map(|(v, _)| v)) < 1e-15,
        "from_standard(π̄) = default"
    );
}

#[test]
fn at_their_defaults_the_base_parameter_kernels_equal_the_constant_kernels() {
    let p = elbow_base::Params::default();
    let zero = [0.0; 2];
    let v0 = elbow::potential_energy(&zero) - elbow_base::potential_energy(&p, &zero);
    for (q, qd, qdd) in states(41, 1000) {
        let close = |a: &[f64], b: &[f64], what: &str| {
            let e = rel_err(a, b);
            assert!(e < 1e-13, "{what}: {e:e} at q = {q:?}");
        };
        close(
            &elbow_base::inverse_dynamics(&p, &q, &qd, &qdd),
            &elbow::inverse_dynamics(&q, &qd, &qdd),
            "τ",
        );
        close(
            elbow_base::mass_matrix(&p, &q).as_flattened(),
            elbow::mass_matrix(&q).as_flattened(),
            "M",
        );
        close(
            elbow_base::coriolis_matrix(&p, &q, &qd).as_flattened(),
            elbow::coriolis_matrix(&q, &qd).as_flattened(),
            "C",
        );
        close(
            &elbow_base::gravity_torques(&p, &q),
            &elbow::gravity_torques(&q),
            "g",
        );
        close(
            &elbow_base::bias_torques(&p, &q, &qd),
            &elbow::bias_torques(&q, &qd),
            "bias",
        );
        close(
            &elbow_base::forward_dynamics(&p, &q, &qd, &qdd),
            &elbow::forward_dynamics(&q, &qd, &qdd),
            "FD",
        );
        close(
            &[elbow_base::kinetic_energy(&p, &q, &qd)],
            &[elbow::kinetic_energy(&q, &qd)],
            "T",
        );
        // V is fixed up to a constant only: its differences are exact.
        close(
            &[elbow_base::potential_energy(&p, &q) + v0],
            &[elbow::potential_energy(&q)],
            "V",
        );
        let (dq, dv) = elbow_base::inverse_dynamics_derivatives(&p, &q, &qd, &qdd);
        let (eq, ev) = elbow::inverse_dynamics_derivatives(&q, &qd, &qdd);
        close(dq.as_flattened(), eq.as_flattened(), "∂τ/∂q");
        close(dv.as_flattened(), ev.as_flattened(), "∂τ/∂q̇");
        let y_b = elbow_base::base_regressor(&p, &q, &qd, &qdd);
        close(
            y_b.as_flattened(),
            elbow::base_regressor(&q, &qd, &qdd).as_flattened(),
            "Y_b",
        );
        let other = elbow_base::Params {
            link2_Izz: 7.0,
            ..elbow_base::Params::default()
        };
        assert_eq!(
            elbow_base::base_regressor(&other, &q, &qd, &qdd),
            y_b,
            "Y_b does not depend on the parameters"
        );
    }
}

/// Another robot of the same geometry (heavier links, COMs off the axis, other inertias):
/// the kernels at `Params::from_standard` of its standard parameters are its dynamics.
#[test]
fn from_standard_gives_the_dynamics_of_any_masses_and_inertias() {
    let mut model = planar_elbow();
    for (k, link) in model.links.iter_mut().enumerate() {
        let k = k as f64;
        link.mass *= 1.3 + 0.2 * k;
        link.com = [0.1 + 0.05 * k, -0.02 + 0.03 * k, 0.01];
        link.inertia[2][2] *= 0.7 + k;
        link.inertia[0][1] = 0.003;
        link.inertia[1][0] = 0.003;
    }
    let p = elbow_base::Params::from_standard(&standard(&model));
    assert_ne!(p, elbow_base::Params::default());
    let mut reference = Reference::new(&model);
    for (q, qd, qdd) in states(43, 200) {
        let tau = reference.inverse_dynamics(&q, &qd, &qdd).expect("sizes");
        let e = rel_err(
            &elbow_base::inverse_dynamics(&p, &q, &qd, &qdd),
            tau.as_slice(),
        );
        assert!(e < 1e-13, "τ: {e:e}");
        let m = reference.mass_matrix(&q).expect("sizes");
        let m: Vec<f64> = m.transpose().iter().copied().collect();
        let e = rel_err(elbow_base::mass_matrix(&p, &q).as_flattened(), &m);
        assert!(e < 1e-13, "M: {e:e}");
    }
}

/// Moving mass from link 2 into link 1's first moment and inertia as the regrouping does
/// (δm₂ with −0.3 δm₂ on link1.mcx and −0.09 δm₂ on link1.Izz), and changing link 2's Ixx,
/// which never acts in the plane: the standard parameters change, the base parameters and
/// every torque do not.
#[test]
fn standard_parameters_the_dynamics_do_not_determine_change_nothing() {
    let pi = standard(&planar_elbow());
    let mut moved = pi;
    let delta = 2.5;
    moved[10] += delta;
    moved[1] -= 0.3 * delta;
    moved[9] -= 0.09 * delta;
    moved[14] += 0.4;
    let (a, b) = (
        elbow_base::Params::from_standard(&pi),
        elbow_base::Params::from_standard(&moved),
    );
    let fields = |p: &elbow_base::Params| {
        [
            p.link1_mcxR,
            p.link1_mcy,
            p.link1_IzzR,
            p.link2_mcx,
            p.link2_mcy,
            p.link2_Izz,
        ]
    };
    assert!(rel_err(&fields(&b), &fields(&a)) < 1e-15, "{a:?} vs {b:?}");
    for (q, qd, qdd) in states(47, 100) {
        let e = rel_err(
            &elbow_base::inverse_dynamics(&b, &q, &qd, &qdd),
            &elbow_base::inverse_dynamics(&a, &q, &qd, &qdd),
        );
        assert!(e < 1e-14, "τ: {e:e}");
    }
}
