//! `rne bench MODEL`: a robot chosen at run time timed kernel by kernel on every engine, with
//! each engine's error against the numeric reference and the time to obtain the kernels.

mod common;
use common::rne;

use serde_json::Value;

fn bench_json(args: &[&str]) -> Value {
    let mut all = vec!["bench"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--quick", "--json"]);
    serde_json::from_str(&rne(&all).unwrap()).expect("JSON")
}

/// The entries of `kernel` in the report, by engine.
fn engines_of<'a>(report: &'a Value, kernel: &str) -> Vec<&'a str> {
    report["kernels"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|k| k["kernel"] == kernel)
        .map(|k| k["engine"].as_str().unwrap())
        .collect()
}

/// A built-in robot: every default kernel on the JIT and the interpreter, the compiled
/// module's dynamics beside them, positive times and errors at round-off against the
/// reference; the JIT's time to kernels covers all 18 kernels.
#[test]
fn a_builtin_robot_is_timed_on_every_engine_with_its_errors() {
    let report = bench_json(&["irb140-3dof"]);
    assert_eq!(report["robot"], "irb140-3dof");
    assert_eq!(report["nv"], 3);
    let time = &report["time_to_kernels_s"];
    assert!(time["rne_jit"].as_f64().unwrap() > 0.0);
    assert_eq!(time["rne_kernels"], 18);
    assert_eq!(
        engines_of(&report, "inverse_dynamics"),
        ["jit", "interpreted", "compiled"]
    );
    assert_eq!(
        engines_of(&report, "forward_dynamics_derivatives")[..2],
        ["jit", "interpreted"]
    );
    for k in report["kernels"].as_array().unwrap() {
        assert!(k["ns"].as_f64().unwrap() > 0.0, "{k}");
        let error = k["max_rel_error"].as_f64().unwrap();
        assert!(error < 1e-12, "{k}");
    }
}

/// A built-in URDF robot's derivatives and M⁻¹ are timed on its compiled `control` module
/// beside the JIT (the default module has the dynamics only), with the same errors; kernels
/// with no compiled module to call are timed on the JIT alone.
#[test]
fn a_urdf_robots_derivatives_have_a_compiled_column() {
    let kernels = [
        "mass_matrix_inverse",
        "inverse_dynamics_derivatives",
        "forward_dynamics_derivatives",
    ];
    let report = bench_json(&[
        "ur5",
        "--engines",
        "jit,compiled",
        "--kernels",
        &kernels.join(","),
    ]);
    for kernel in kernels {
        assert_eq!(engines_of(&report, kernel), ["jit", "compiled"], "{kernel}");
    }
    for k in report["kernels"].as_array().unwrap() {
        assert!(k["ns"].as_f64().unwrap() > 0.0, "{k}");
        assert!(k["max_rel_error"].as_f64().unwrap() < 1e-12, "{k}");
    }
    // The frames' kernels have no compiled module to time through: the JIT alone.
    let report = bench_json(&[
        "ur5",
        "--engines",
        "jit,compiled",
        "--kernels",
        "frame_jacobians",
    ]);
    assert_eq!(engines_of(&report, "frame_jacobians"), ["jit"]);
}

/// A robot file on a floating base, with chosen kernels: no compiled module, only the JIT
/// and the interpreter, and only the kernels asked for.
#[test]
fn a_robot_file_on_a_floating_base_times_the_kernels_asked_for() {
    let report = bench_json(&[
        "../robots/quadruped.urdf",
        "--floating-base",
        "--kernels",
        "mass_matrix,frame_jacobians",
        "--engines",
        "jit,interpreted",
    ]);
    let kernels: Vec<&str> = report["kernels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k["kernel"].as_str().unwrap())
        .collect();
    assert_eq!(
        kernels,
        [
            "mass_matrix",
            "mass_matrix",
            "frame_jacobians",
            "frame_jacobians"
        ]
    );
    assert_eq!(engines_of(&report, "mass_matrix"), ["jit", "interpreted"]);
}

/// Unknown kernels and Pinocchio on a robot that is not a URDF are errors before any timing.
#[test]
fn bad_requests_are_errors() {
    let error = rne(&["bench", "planar-elbow", "--kernels", "mass_matrx"]).unwrap_err();
    assert!(
        error.contains("--kernels") && error.contains("mass_matrx"),
        "{error}"
    );
    let error = rne(&[
        "bench",
        "planar-elbow",
        "--pinocchio",
        "/nonexistent/run.sh",
    ])
    .unwrap_err();
    assert!(error.contains("needs a URDF robot"), "{error}");
}
