//! The f32 and generic variants of the generated kernels.

mod common;

use common::{rel_err, state};
use rne_codegen::DoubleDouble;

rne_codegen::derive_dynamics! {
    mod double {
        robot: "fixtures/robots/irb140-3dof.toml",
    }
}

rne_codegen::derive_dynamics! {
    mod single {
        robot: "fixtures/robots/irb140-3dof.toml",
        scalar: f32,
    }
}

rne_codegen::derive_dynamics! {
    mod generic {
        robot: "fixtures/robots/irb140-3dof.toml",
        scalar: generic,
    }
}

fn to_f32(v: &[f64; 3]) -> [f32; 3] {
    v.map(|x| x as f32)
}

fn to_f64(v: [f32; 3]) -> Vec<f64> {
    v.iter().map(|&x| x as f64).collect()
}

#[test]
fn generic_kernels_in_f64_are_bit_identical_to_the_f64_kernels() {
    let mut rng = common::rng(21);
    for _ in 0..1000 {
        let (q, qd, qdd) = state(&mut rng, 3);
        let (q, qd, qdd): ([f64; 3], [f64; 3], [f64; 3]) = (
            q.try_into().unwrap(),
            qd.try_into().unwrap(),
            qdd.try_into().unwrap(),
        );
        assert_eq!(
            generic::inverse_dynamics(&q, &qd, &qdd),
            double::inverse_dynamics(&q, &qd, &qdd)
        );
        assert_eq!(generic::mass_matrix(&q), double::mass_matrix(&q));
        assert_eq!(
            generic::coriolis_matrix(&q, &qd),
            double::coriolis_matrix(&q, &qd)
        );
        assert_eq!(
            generic::forward_dynamics(&q, &qd, &qdd),
            double::forward_dynamics(&q, &qd, &qdd)
        );
        assert_eq!(
            generic::kinetic_energy(&q, &qd),
            double::kinetic_energy(&q, &qd)
        );
        assert_eq!(generic::potential_energy(&q), double::potential_energy(&q));
    }
}

#[test]
fn f32_kernels_agree_with_f64_to_single_precision() {
    let mut rng = common::rng(22);
    let mut worst = 0.0f64;
    for _ in 0..1000 {
        let (q, qd, qdd) = state(&mut rng, 3);
        let (q, qd, qdd): ([f64; 3], [f64; 3], [f64; 3]) = (
            q.try_into().unwrap(),
            qd.try_into().unwrap(),
            qdd.try_into().unwrap(),
        );
        let tau32 = single::inverse_dynamics(&to_f32(&q), &to_f32(&qd), &to_f32(&qdd));
        let generic32 = generic::inverse_dynamics(&to_f32(&q), &to_f32(&qd), &to_f32(&qdd));
        assert_eq!(tau32, generic32, "generic in f32 equals the f32 kernel");
        worst = worst.max(rel_err(
            &to_f64(tau32),
            &double::inverse_dynamics(&q, &qd, &qdd),
        ));
        let m32 = single::mass_matrix(&to_f32(&q));
        let m64 = double::mass_matrix(&q);
        for i in 0..3 {
            worst = worst.max(rel_err(&to_f64(m32[i]), &m64[i]) * 0.5);
        }
    }
    assert!(worst < 1e-4, "f32 relative error {worst:e}");
}

#[test]
fn generic_kernels_in_double_double_agree_with_f64_and_are_more_precise() {
    let dd = |v: &[f64; 3]| v.map(DoubleDouble::from_f64);
    let mut rng = common::rng(23);
    for _ in 0..300 {
        let (q, qd, qdd) = state(&mut rng, 3);
        let (q, qd, qdd): ([f64; 3], [f64; 3], [f64; 3]) = (
            q.try_into().unwrap(),
            qd.try_into().unwrap(),
            qdd.try_into().unwrap(),
        );
        let precise = generic::inverse_dynamics(&dd(&q), &dd(&qd), &dd(&qdd)).map(|x| x.to_f64());
        assert!(rel_err(&double::inverse_dynamics(&q, &qd, &qdd), &precise) < 1e-13);
        let m_precise = generic::mass_matrix(&dd(&q));
        let m = double::mass_matrix(&q);
        for i in 0..3 {
            assert!(rel_err(&m[i], &m_precise[i].map(|x| x.to_f64())) < 1e-13);
        }
        // The double-double result is not just the f64 one widened: it carries more digits.
        let widened = generic::inverse_dynamics(&dd(&q), &dd(&qd), &dd(&qdd));
        assert!(
            widened.iter().any(|x| x.lo() != 0.0),
            "no low-order digits at all"
        );
    }
}
