//! A generated module of a floating-base robot (`base = "floating"` in its spec): NQ = NV + 1,
//! the `Dynamics` handle says so, and every kernel agrees with the independent reference.

mod common;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_codegen::Dynamics;
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};

rne_codegen::derive_dynamics! {
    /// The floating hopper, every kernel.
    mod hopper {
        robot: "fixtures/robots/hopper-floating.toml",
    }
}

#[test]
fn a_floating_module_has_the_free_flyer_in_front_and_agrees_with_the_reference() {
    assert_eq!((hopper::NDOF, hopper::NQ, hopper::NV), (2, 9, 8));
    fn floating<D: Dynamics<9, 8>>(_: &D) -> bool {
        D::FLOATING_BASE
    }
    assert!(floating(&hopper::Model));
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/robots/hopper-floating.toml");
    let model =
        read_robot(Description::file(&path), &LoadOptions::default()).expect("the fixture loads");
    let mut reference = Reference::new(&model.to_numeric());
    let mut rng = ChaCha8Rng::seed_from_u64(0x5eed_f10a);
    for _ in 0..200 {
        let mut q = [0.0; 9];
        for x in &mut q {
            *x = rng.gen_range(-1.0..1.0);
        }
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        for x in &mut q[3..7] {
            *x /= norm;
        }
        let mut draw =
            |scale: f64| -> [f64; 8] { std::array::from_fn(|_| rng.gen_range(-scale..scale)) };
        let (v, a, u) = (draw(2.0), draw(3.0), draw(10.0));
        let tau = hopper::inverse_dynamics(&q, &v, &a);
        let expected = reference.inverse_dynamics(&q, &v, &a).unwrap();
        assert!(common::rel_err(&tau, expected.as_slice()) < 1e-13, "τ");
        let m = hopper::mass_matrix(&q);
        let expected = reference.mass_matrix(&q).unwrap();
        let m_flat: Vec<f64> = m.iter().flatten().copied().collect();
        let e_flat: Vec<f64> = (0..8)
            .flat_map(|i| (0..8).map(move |j| (i, j)))
            .map(|(i, j)| expected[(i, j)])
            .collect();
        assert!(common::rel_err(&m_flat, &e_flat) < 1e-13, "M");
        let qdd = hopper::forward_dynamics(&q, &v, &u);
        let expected = reference.forward_dynamics(&q, &v, &u).unwrap();
        assert!(common::rel_err(&qdd, expected.as_slice()) < 1e-11, "FD");
        let bias = hopper::bias_torques(&q, &v);
        let expected = reference.bias_torques(&q, &v).unwrap();
        assert!(common::rel_err(&bias, expected.as_slice()) < 1e-13, "bias");
        let c = hopper::coriolis_matrix(&q, &v);
        let g = hopper::gravity_torques(&q);
        let cv: Vec<f64> = (0..8)
            .map(|i| (0..8).map(|j| c[i][j] * v[j]).sum::<f64>() + g[i])
            .collect();
        assert!(common::rel_err(&cv, &bias) < 1e-12, "C v + g = bias");
        let t = hopper::kinetic_energy(&q, &v);
        assert!(
            (t - reference.kinetic_energy(&q, &v).unwrap()).abs() < 1e-12 * t.max(1.0),
            "T"
        );
        let p = hopper::potential_energy(&q);
        assert!(
            (p - reference.potential_energy(&q).unwrap()).abs() < 1e-12 * p.abs().max(1.0),
            "V"
        );
    }
}
