//! `rne eval --what derivatives|kinematics|regressor` and `rne show --what dtau`: the JSON keys
//! of docs/design.md §5, the generator's programs against the independent reference, and the
//! planar elbow's torque derivatives in the thesis's notation.

mod common;
use common::rne;

use serde_json::Value;

/// Every number in a JSON value, in order.
fn numbers(value: &Value, out: &mut Vec<f64>) {
    match value {
        Value::Number(n) => out.push(n.as_f64().unwrap()),
        Value::Array(items) => items.iter().for_each(|v| numbers(v, out)),
        _ => {}
    }
}

#[test]
fn control_and_identification_keys_agree_between_the_engines() {
    let state = [
        "eval",
        "ur5",
        "--q",
        "0.3,-0.5,1.1,0.2,-1.0,0.7",
        "--qd",
        "1,2,-0.5,0.3,0.1,-0.2",
        "--qdd",
        "0.1,0.2,0.3,-0.4,0.5,0.6",
        "--tau",
        "1,2,3,0.5,0.2,0.1",
        "--json",
        "--what",
        "derivatives,kinematics,regressor",
    ];
    let symbolic: Value = serde_json::from_str(&rne(&state).unwrap()).unwrap();
    let mut numeric_args = state.to_vec();
    numeric_args.extend(["--engine", "numeric"]);
    let numeric: Value = serde_json::from_str(&rne(&numeric_args).unwrap()).unwrap();
    let keys = [
        "dtau_dq",
        "dtau_dqd",
        "dqdd_dq",
        "dqdd_dqd",
        "Minv",
        "placements",
        "jacobians",
        "jacobian_dot_qd",
        "regressor",
        "base_regressor",
    ];
    for key in keys {
        let (mut a, mut b) = (Vec::new(), Vec::new());
        numbers(&symbolic[key], &mut a);
        numbers(&numeric[key], &mut b);
        assert!(
            !a.is_empty() && a.len() == b.len(),
            "{key}: {} vs {}",
            a.len(),
            b.len()
        );
        let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        let error = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
            / scale;
        assert!(error < 1e-12, "{key}: engines differ by {error:e}");
    }
    assert_eq!(symbolic["dtau_dq"].as_array().unwrap().len(), 6, "6 × 6");
    assert_eq!(
        symbolic["jacobians"][0].as_array().unwrap().len(),
        6,
        "6 rows per frame"
    );
    assert_eq!(
        symbolic["frames"][0], "world",
        "the root link of the URDF is a frame"
    );
    assert_eq!(symbolic["parameters"], numeric["parameters"]);
    assert_eq!(symbolic["parameters"].as_array().unwrap().len(), 60);
    let base = symbolic["base_parameters"].as_array().unwrap().len();
    assert!(base < 60 && base == symbolic["base_regressor"][0].as_array().unwrap().len());
}

#[test]
fn show_prints_the_planar_elbow_torque_derivatives_in_the_thesis_notation() {
    let text = rne(&[
        "show",
        "planar-elbow",
        "--what",
        "dtau",
        "--symbolic-params",
    ])
    .unwrap();
    // ∂/∂q of (4.45)–(4.47): gravity and Coriolis terms differentiated by hand.
    for line in [
        "dtau_dq[1,1] = -g (lc1 m1 s1 + m2 (l1 s1 + lc2 s12))",
        "dtau_dq[2,1] = -g lc2 m2 s12",
        "dtau_dq[2,2] = -l1 lc2 m2 s2 DDq1 + l1 lc2 m2 c2 Dq1^2 - g lc2 m2 s12",
        "dtau_dqd[1,1] = -2 l1 lc2 m2 s2 Dq2",
        "dtau_dqd[2,1] = 2 l1 lc2 m2 s2 Dq1",
        "dtau_dqd[2,2] = 0",
    ] {
        assert!(text.contains(line), "missing `{line}` in\n{text}");
    }
}

#[test]
fn a_state_of_the_wrong_size_is_an_error_not_a_panic() {
    let error = rne(&[
        "eval",
        "planar-elbow",
        "--q",
        "0.1,0.2,0.3",
        "--what",
        "kinematics",
    ])
    .unwrap_err();
    assert!(
        error.contains("--q has 3 values") && error.contains("needs 2"),
        "{error}"
    );
    let error = rne(&[
        "eval",
        "planar-elbow",
        "--q",
        "0.1,0.2",
        "--qd",
        "1",
        "--what",
        "derivatives",
        "--engine",
        "numeric",
    ])
    .unwrap_err();
    assert!(error.contains("qd"), "{error}");
}
