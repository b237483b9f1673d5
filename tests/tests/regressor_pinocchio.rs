//! The joint-torque regressor against Pinocchio's `computeJointTorqueRegressor` on the built-in
//! UR5 and Panda (9 joints: the fingers as two prismatic joints): Pinocchio 4.1's values at
//! seeded states are committed in `tests/fixtures/pinocchio/regressor-*.json`, written by
//! `tools/peers/regressor.py` (CI has no Python):
//!
//! ```sh
//! PY=~/.cache/rne-peers/venv/bin/python      # bash tools/peers/setup.sh
//! $PY tools/peers/regressor.py rne-models/robots/ur5.urdf > tests/fixtures/pinocchio/regressor-ur5.json
//! $PY tools/peers/regressor.py rne-models/robots/panda.urdf > tests/fixtures/pinocchio/regressor-panda.json
//! ```
//!
//! Both order the columns per moving body as m, m·cx, m·cy, m·cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz
//! about the body frame's origin (docs/design.md §4.4), bodies depth-first, fixed links merged into
//! their moving parent.

use nalgebra::DMatrix;
use rne_codegen_core::{build_kernel, Kernel, Scene};
use rne_models::builtin::RobotSource;
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{Symbol, SymbolicDynamics};
use serde_json::Value;

/// Largest entry-wise difference allowed, relative to the largest entry of Pinocchio's
/// regressor at that state.
const TOLERANCE: f64 = 1e-12;

/// A regressor implementation: Y(q, v, a).
type Engine<'a> = &'a mut dyn FnMut(&[f64], &[f64], &[f64]) -> DMatrix<f64>;

/// One state of a fixture and Pinocchio's regressor there.
struct Expected {
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    regressor: DMatrix<f64>,
}

fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

fn fixture(text: &str) -> (Vec<String>, Vec<Expected>) {
    let json: Value = serde_json::from_str(text).expect("valid JSON");
    let joints = json["joints"]
        .as_array()
        .expect("joint names")
        .iter()
        .map(|j| j.as_str().expect("a name").to_owned())
        .collect();
    let states = json["states"]
        .as_array()
        .expect("states")
        .iter()
        .map(|s| {
            let rows: Vec<Vec<f64>> = s["regressor"]
                .as_array()
                .expect("rows")
                .iter()
                .map(numbers)
                .collect();
            let (n, p) = (rows.len(), rows[0].len());
            Expected {
                q: numbers(&s["q"]),
                v: numbers(&s["v"]),
                a: numbers(&s["a"]),
                regressor: DMatrix::from_fn(n, p, |i, j| rows[i][j]),
            }
        })
        .collect();
    (joints, states)
}

/// The largest difference between `regressor` and each state's expected one, relative to the
/// expected one's largest entry.
fn worst_relative_error(
    states: &[Expected],
    mut regressor: impl FnMut(&[f64], &[f64], &[f64]) -> DMatrix<f64>,
) -> f64 {
    states
        .iter()
        .map(|s| {
            let y = regressor(&s.q, &s.v, &s.a);
            assert_eq!(y.shape(), s.regressor.shape(), "regressor shape");
            (y - &s.regressor).amax() / s.regressor.amax()
        })
        .fold(0.0, f64::max)
}

/// Every regressor rne computes for `robot` agrees with Pinocchio's to `TOLERANCE`: the
/// reference's and the generator's `regressor` kernel (its program, which the emitted function
/// computes bit for bit: `control_kernels.rs`).
fn check_against_pinocchio(robot: &str, expected: &str) {
    let (joints, states) = fixture(expected);
    let model = RobotSource::resolve(robot)
        .load(&LoadOptions::default())
        .expect("built-in robot");
    assert_eq!(model.joint_names(), joints, "{robot}: joint order");
    let mut reference = Reference::new(&model.to_numeric());
    let dynamics = SymbolicDynamics::new(&Scene::default().apply(&model).expect("scene"));
    let program = build_kernel(&dynamics, Kernel::Regressor).program;
    let np = dynamics.parameter_names().len();
    let engines: [(&str, Engine); 2] = [
        ("reference", &mut |q, v, a| {
            reference.regressor(q, v, a).expect("state sizes")
        }),
        ("generated", &mut |q, v, a| {
            let y = program.eval(|s| match s {
                Symbol::Position(k) => q[k as usize],
                Symbol::Velocity(k) => v[k as usize],
                Symbol::Acceleration(k) => a[k as usize],
                other => panic!("the regressor reads {other:?}"),
            });
            DMatrix::from_row_slice(v.len(), np, &y)
        }),
    ];
    for (engine, regressor) in engines {
        let error = worst_relative_error(&states, regressor);
        assert!(
            error <= TOLERANCE,
            "{robot}: the {engine} regressor differs from Pinocchio's by {error:e} (relative)"
        );
    }
}

#[test]
fn the_ur5_regressor_matches_pinocchio() {
    check_against_pinocchio(
        "ur5",
        include_str!("../fixtures/pinocchio/regressor-ur5.json"),
    );
}

#[test]
fn the_panda_regressor_matches_pinocchio() {
    check_against_pinocchio(
        "panda",
        include_str!("../fixtures/pinocchio/regressor-panda.json"),
    );
}
