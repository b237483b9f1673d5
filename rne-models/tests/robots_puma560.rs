//! The PUMA 560's published check torques (Corke & Armstrong-Hélouvry's parameters, no motor
//! inertia or friction, gravity [0, 0, −9.81]; computed with SymPyBotics) through the
//! generated kernels, the symbolic dynamics and the numeric reference.

mod robots_common;

use rne_models::{builtin, RobotSource};
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use robots_common::Symbolic;

const Q: [f64; 6] = [
    0.7504516826728697,
    0.8395156106908136,
    0.16851233582594916,
    0.3849629637427072,
    0.5252993946810777,
    0.6701207256444748,
];
const QD: [f64; 6] = [
    0.24721855939629367,
    0.9805915670454258,
    0.9895299755642817,
    0.7861135739668947,
    0.273842245476577,
    0.17182358900767503,
];
const QDD: [f64; 6] = [
    0.707405815485141,
    0.25295715193420953,
    0.9763909835998361,
    0.8412822676113918,
    0.4867768296473465,
    0.11480270540937143,
];
const TAU: [f64; 6] = [
    0.986185688341252,
    16.1055550633721,
    -6.54839494827661,
    0.00626452648190803,
    -0.0208972707132494,
    5.59805923645945e-5,
];

fn assert_check_value(what: &str, tau: &[f64]) {
    for (k, (t, expected)) in tau.iter().zip(TAU).enumerate() {
        assert!(
            (t - expected).abs() <= 1e-12,
            "{what}: tau[{k}] = {t:e}, published {expected:e}, error {:e}",
            (t - expected).abs()
        );
    }
}

#[test]
fn generated_kernels_reproduce_the_published_torques() {
    assert_check_value(
        "kernels",
        &rne_models::generated::puma560::inverse_dynamics(&Q, &QD, &QDD),
    );
}

#[test]
fn symbolic_dynamics_and_reference_reproduce_the_published_torques() {
    let model = RobotSource::Builtin(builtin("puma560").unwrap())
        .load(&LoadOptions::default())
        .unwrap();
    let zero = [0.0; 6];
    assert_check_value(
        "symbolic",
        &Symbolic::new(&model).eval(&Q, &QD, &QDD, &zero).tau,
    );
    let tau: Vec<f64> = Reference::new(&model.to_numeric())
        .inverse_dynamics(&Q, &QD, &QDD)
        .unwrap()
        .data
        .into();
    assert_check_value("reference", &tau);
}
