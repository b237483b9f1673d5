//! The `rne` command: printed equations (snapshots), evaluation, emission and errors.

mod common;
use common::rne;

use std::process::Command;

use rne_scenarios::SCENARIOS;

#[test]
fn show_prints_the_planar_elbow_like_the_thesis() {
    insta::assert_snapshot!(rne(&["show", "planar-elbow", "--symbolic-params"]).unwrap());
}

#[test]
fn show_prints_latex() {
    insta::assert_snapshot!(rne(&[
        "show",
        "planar-elbow",
        "--symbolic-params",
        "--format",
        "latex",
        "--what",
        "M"
    ])
    .unwrap());
}

#[test]
fn show_prints_the_irb140_mass_matrix_with_numbers() {
    insta::assert_snapshot!(rne(&["show", "irb140-3dof", "--what", "M"]).unwrap());
}

#[test]
fn eval_json_has_the_documented_keys_and_engines_agree() {
    let state = [
        "--q",
        "0.3,-0.5,1.1",
        "--qd",
        "1,2,-0.5",
        "--qdd",
        "0.1,0.2,0.3",
        "--tau",
        "1,2,3",
        "--json",
    ];
    let mut symbolic = vec!["eval", "irb140-3dof"];
    symbolic.extend(state);
    let mut numeric = symbolic.clone();
    numeric.extend(["--engine", "numeric", "--what", "tau,M,g,bias,fd,energy"]);
    let symbolic: serde_json::Value = serde_json::from_str(&rne(&symbolic).unwrap()).unwrap();
    let numeric: serde_json::Value = serde_json::from_str(&rne(&numeric).unwrap()).unwrap();
    assert_eq!(symbolic["model"], "irb140-3dof");
    assert_eq!(symbolic["joints"], serde_json::json!(["q1", "q2", "q3"]));
    for key in ["tau", "M", "C", "g", "bias", "qdd", "kinetic", "potential"] {
        assert!(symbolic.get(key).is_some(), "missing key {key}");
    }
    let flat = |v: &serde_json::Value| -> Vec<f64> {
        match v {
            serde_json::Value::Array(items) => items.iter().flat_map(flat_one).collect(),
            other => vec![other.as_f64().unwrap()],
        }
    };
    fn flat_one(v: &serde_json::Value) -> Vec<f64> {
        match v {
            serde_json::Value::Array(items) => items.iter().map(|x| x.as_f64().unwrap()).collect(),
            other => vec![other.as_f64().unwrap()],
        }
    }
    for key in ["tau", "M", "g", "bias", "qdd", "kinetic", "potential"] {
        let (a, b) = (flat(&symbolic[key]), flat(&numeric[key]));
        let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() <= 1e-12 * scale, "{key}: {x} vs {y}");
        }
    }
}

#[test]
fn eval_of_a_spec_file_uses_the_expression_graph() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/planar-elbow.toml"
    );
    let by_file = rne(&[
        "eval", path, "--q", "0.2,0.4", "--qd", "1,-1", "--what", "tau,C", "--json",
    ])
    .unwrap();
    let builtin = rne(&[
        "eval",
        "planar-elbow",
        "--q",
        "0.2,0.4",
        "--qd",
        "1,-1",
        "--what",
        "tau,C",
        "--json",
    ])
    .unwrap();
    let a: serde_json::Value = serde_json::from_str(&by_file).unwrap();
    let b: serde_json::Value = serde_json::from_str(&builtin).unwrap();
    let close = |x: &serde_json::Value, y: &serde_json::Value| {
        (x.as_f64().unwrap() - y.as_f64().unwrap()).abs() < 1e-12
    };
    for i in 0..2 {
        assert!(close(&a["tau"][i], &b["tau"][i]));
        for j in 0..2 {
            assert!(close(&a["C"][i][j], &b["C"][i][j]));
        }
    }
}

#[test]
fn bad_input_is_a_clear_error() {
    let cases: [(&[&str], &str); 12] = [
        (
            &["eval", "planar-elbow", "--q", "1,2,3"],
            "--q has 3 values; the robot needs 2",
        ),
        (
            &["eval", "planar-elbow", "--q", "1,x"],
            "--q: `x` is not a number",
        ),
        (
            &["eval", "no/such/robot.toml", "--q", "1"],
            "no/such/robot.toml",
        ),
        (
            &["emit", "planar-elbow", "--lock", "q7=0"],
            "no joint named `q7`",
        ),
        (
            &["emit", "planar-elbow", "--outputs", "torques"],
            "unknown output `torques`",
        ),
        (
            &["emit", "planar-elbow", "--gravity", "0,1"],
            "--gravity needs 3 values",
        ),
        (
            &["emit", "planar-elbow", "--gravity", "nan,0,0"],
            "gravity must be finite",
        ),
        (
            &["emit", "planar-elbow", "--lock", "q1=inf"],
            "joint `q1` cannot be locked at inf: not a finite number",
        ),
        (
            &["emit", "planar-elbow", "--lock", "q1=0,q1=1"],
            "joint `q1` is locked twice",
        ),
        (
            &["verify", "planar-elbow", "--tolerance", "nan"],
            "--tolerance must be a finite, non-negative number",
        ),
        (
            &["verify", "planar-elbow", "--samples", "0"],
            "--samples must be at least 1",
        ),
        (
            &["simulate", "double-pendulum", "--time", "--repeat", "0"],
            "--repeat must be at least 1",
        ),
    ];
    for (args, expected) in cases {
        let error = rne(args).expect_err("should fail");
        assert!(error.contains(expected), "{args:?}: {error}");
    }
}

#[test]
fn the_binary_exits_non_zero_with_the_error_on_stderr() {
    let output = Command::new(env!("CARGO_BIN_EXE_rne"))
        .args(["eval", "planar-elbow", "--q", "1,2,3"])
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(output.stdout.is_empty());
}

#[test]
fn emitted_code_is_byte_identical_across_processes() {
    let emit = || {
        let output = Command::new(env!("CARGO_BIN_EXE_rne"))
            .args(["emit", "irb140-3dof"])
            .output()
            .unwrap();
        assert!(output.status.success());
        output.stdout
    };
    let first = emit();
    assert!(first.len() > 1000);
    assert_eq!(first, emit(), "two processes emitted different code");
}

#[test]
fn models_lists_the_builtin_robots() {
    let listing = rne(&["models"]).unwrap();
    for name in ["planar-elbow", "irb140-3dof"] {
        assert!(listing.contains(name), "{listing}");
    }
}

/// A joint that moves no mass makes M(q) singular: forward dynamics asked for by name is an
/// error naming the joint and link, `all` leaves it out and says why, and a simulation of
/// the model is refused before it starts.
#[test]
fn forward_dynamics_of_a_joint_that_moves_no_mass_is_refused_by_name() {
    let dir = std::env::temp_dir().join(format!("rne-cli-massless-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let spec = dir.join("massless.toml");
    let arm = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/massless_tool.toml"
    ))
    .unwrap();
    std::fs::write(&spec, arm).unwrap();
    let spec = spec.to_str().unwrap();
    let expected = "joint `q2` moves no mass: link `tool`";

    let error = rne(&["eval", spec, "--q", "0.1,0.2", "--what", "fd"]).unwrap_err();
    assert!(error.contains(expected) && error.contains(spec), "{error}");
    let all = rne(&["eval", spec, "--q", "0.1,0.2"]).unwrap();
    assert!(
        all.contains("qdd_undefined") && all.contains(expected),
        "{all}"
    );
    assert!(all.contains("M:") && !all.contains("qdd:"), "{all}");

    // `rne stats` generates every other kernel and names each undefined one with the joint.
    let stats = rne(&["stats", spec]).unwrap();
    for kernel in [
        "forward_dynamics",
        "forward_dynamics_derivatives",
        "mass_matrix_inverse",
    ] {
        let line = format!("{kernel:<28} undefined: {expected}");
        assert!(stats.contains(&line), "{line} missing in\n{stats}");
    }
    assert!(stats.contains("inverse_dynamics_derivatives") && stats.contains("base_regressor"));

    let scenario = dir.join("run.toml");
    std::fs::write(
        &scenario,
        "model = \"massless.toml\"\nduration = 0.1\nq0 = [0.1, 0.2]\n",
    )
    .unwrap();
    let out = dir.join("out");
    let error = rne(&[
        "simulate",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ])
    .unwrap_err();
    assert!(error.contains(expected), "{error}");
    std::fs::remove_dir_all(&dir).unwrap();
}

fn fixture(name: &str) -> String {
    format!("{}/tests/fixtures/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// `rne check` reports what it read of a robot as published (odd names, a mimic joint, joint
/// friction, a fixed tool flange) and its warnings, and succeeds with warnings.
#[test]
fn check_reports_the_robot_and_its_warnings() {
    let path = fixture("published.urdf");
    let report = rne(&["check", &path]).unwrap();
    for expected in [
        "model: published",
        "base: fixed",
        "degrees of freedom: 1",
        "state: NQ = 1, NV = 1",
        "total mass: 2.1 kg",
        "links (4):",
        "  base_link <- world: fixed, mass 0",
        "  arm <- base_link: revolute '8', mass 2, friction",
        "  finger <- arm: prismatic 'FL-finger', mass 0.1, mimics '8'",
        "  tool0 <- arm: fixed, mass 0",
        "mimic joints: 1",
        "warnings: 1",
        ":17: link 'arm', field 'inertial.inertia': inertia breaks the triangle inequality",
    ] {
        assert!(report.contains(expected), "{expected}\n{report}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&rne(&["check", &path, "--json"]).unwrap()).unwrap();
    assert_eq!(
        json["joints"],
        serde_json::json!(["8"]),
        "the follower has no variable"
    );
    assert_eq!(json["dof"], 1);
    assert_eq!(json["mimic"], serde_json::json!(["FL-finger"]));
    assert_eq!(json["warnings"].as_array().unwrap().len(), 1);
}

/// The binary prints warnings to stderr and exits 0; `--strict` makes them errors, on `check`
/// and on every command that takes a MODEL.
#[test]
fn warnings_go_to_stderr_and_strict_makes_them_errors() {
    let path = fixture("published.urdf");
    let output = Command::new(env!("CARGO_BIN_EXE_rne"))
        .args(["check", &path])
        .output()
        .unwrap();
    assert!(output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.starts_with("warning: ") && stderr.contains("triangle inequality"),
        "{stderr}"
    );
    let output = Command::new(env!("CARGO_BIN_EXE_rne"))
        .args(["check", &path, "--strict"])
        .output()
        .unwrap();
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("error under strict validation"), "{stderr}");
    for command in [
        vec!["show", path.as_str(), "--what", "g", "--strict"],
        vec!["eval", path.as_str(), "--q", "0,0", "--strict"],
        vec![
            "emit",
            path.as_str(),
            "--outputs",
            "gravity_torques",
            "--strict",
        ],
        vec!["stats", path.as_str(), "--strict"],
    ] {
        let error = rne(&command).unwrap_err();
        assert!(
            error.contains("(an error under strict validation)"),
            "{command:?}: {error}"
        );
    }
    assert!(rne(&["show", &path, "--what", "g"]).is_ok());
}

#[test]
fn check_of_a_builtin_and_of_a_broken_file() {
    let report = rne(&["check", "planar-elbow"]).unwrap();
    assert!(
        report.contains("degrees of freedom: 2") && report.contains("warnings: 0"),
        "{report}"
    );
    let dir = std::env::temp_dir().join(format!("rne-cli-check-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let broken = dir.join("broken.urdf");
    let text = std::fs::read_to_string(fixture("published.urdf"))
        .unwrap()
        .replace("<mimic joint=\"8\"", "<mimic joint=\"9\"");
    std::fs::write(&broken, text).unwrap();
    let error = rne(&["check", broken.to_str().unwrap()]).unwrap_err();
    assert!(
        error.contains("joint 'FL-finger', field 'mimic.joint': the mimic joint follows '9'"),
        "{error}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The command line: `--list`, a bad scenario name and a scenario file with an unknown key fail
/// with a message on stderr naming the problem and a non-zero exit code, without panicking.
#[test]
fn command_line_lists_and_reports_errors() {
    let rne = env!("CARGO_BIN_EXE_rne");
    let list = Command::new(rne)
        .args(["simulate", "--list"])
        .output()
        .unwrap();
    assert!(list.status.success());
    let text = String::from_utf8(list.stdout).unwrap();
    assert_eq!(text.lines().count(), SCENARIOS.len());
    assert!(text.contains("double-pendulum") && text.contains("6.4-6.7"));

    let unknown = Command::new(rne)
        .args(["simulate", "no-such-scenario"])
        .output()
        .unwrap();
    assert!(!unknown.status.success());
    let message = String::from_utf8(unknown.stderr).unwrap();
    assert!(
        message.contains("unknown scenario `no-such-scenario`"),
        "{message}"
    );

    let dir = std::env::temp_dir().join(format!("rne-cli-simulate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("typo.toml");
    std::fs::write(
        &file,
        "model = \"planar-elbow\"\nduration = 1\nq0 = [0, 0]\ndamping = 2\n",
    )
    .unwrap();
    let bad = Command::new(rne)
        .args([
            "simulate",
            file.to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(!bad.status.success());
    let message = String::from_utf8(bad.stderr).unwrap();
    assert!(
        message.contains("typo.toml") && message.contains("damping"),
        "{message}"
    );
    assert!(!message.contains("panicked"), "{message}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Base parameters of a spec whose parameters are symbols (the planar elbow's `[parameters]`):
/// they are found numerically at the spec's values, so `show --what base-parameters
/// --symbolic-params` is refused with the reason, while `stats --parameters base` reads the
/// spec at its values, as `derive_dynamics!` does, and generates every kernel.
#[test]
fn base_parameters_of_symbolic_parameters_are_refused_with_the_reason_and_found_at_values() {
    let error = rne(&[
        "show",
        "planar-elbow",
        "--what",
        "base-parameters",
        "--symbolic-params",
    ])
    .expect_err("symbols cannot be kept");
    assert!(
        error.contains("--symbolic-params") && error.contains("found numerically"),
        "{error}"
    );
    let json = rne(&["stats", "planar-elbow", "--parameters", "base", "--json"]).expect("stats");
    let json: serde_json::Value = serde_json::from_str(&json).expect("JSON");
    assert_eq!(json["dof"], 2);
    let kernels = json["kernels"].as_array().expect("kernels");
    assert!(kernels.iter().any(|k| k["kernel"] == "base_regressor"));
}
