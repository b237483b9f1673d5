//! `rne identify` end to end on the six-joint IRB 140: an optimised excitation with 1 % torque
//! noise gives back every base parameter to 2 % or three standard deviations, and the
//! identified model predicts the torques of a fresh trajectory to 2 % RMS; and the command's
//! interface (CSV errors, `--excite`, `--json`, `show --what base-parameters`).

use clap::Parser;
use rne_cli::{run, Cli};
use rne_identify::{
    design, fit, identify, predict, simulate, BaseSet, Design, Limits, Measurements, Simulation,
};
use rne_models::builtin::RobotSource;
use rne_models::QUADRUPED;
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;

fn rne(args: &[&str]) -> Result<String, String> {
    let cli = Cli::try_parse_from(std::iter::once("rne").chain(args.iter().copied()))
        .map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    run(cli, &mut out).map_err(|e| e.to_string())?;
    Ok(String::from_utf8(out).expect("utf-8 output"))
}

fn irb140() -> Reference {
    let model = RobotSource::resolve("irb140")
        .load(&LoadOptions::default())
        .expect("built-in robot");
    Reference::new(&model.to_numeric())
}

/// A measured excitation of the IRB 140: `iterations` of the condition-number search, then
/// 10 s at 100 Hz with `noise` relative torque noise.
fn measured(
    reference: &mut Reference,
    base: &BaseSet,
    seed: u64,
    iterations: usize,
) -> (Measurements, f64) {
    let excitation = design(
        reference,
        base,
        &Design {
            period: 10.0,
            harmonics: 5,
            limits: Limits {
                position: vec![1.5; 6],
                velocity: vec![2.0; 6],
                acceleration: vec![f64::INFINITY; 6],
            },
            iterations,
            criterion_states: 60,
            seed,
        },
    )
    .expect("a design");
    let simulation = Simulation {
        duration: 10.0,
        rate: 100.0,
        noise: 0.01,
        seed,
    };
    let data = simulate(reference, &excitation.trajectory, &simulation).expect("simulated");
    (data, excitation.condition)
}

#[test]
fn irb140_base_parameters_are_recovered_from_a_noisy_excitation() {
    let mut reference = irb140();
    let base = BaseSet::find(&mut reference).expect("base parameters");
    assert_eq!(base.len(), 36);
    let (data, condition) = measured(&mut reference, &base, 1, 60);
    assert!(condition < 200.0, "condition number {condition}");
    let estimate = identify(&mut reference, &base, &data, true).expect("identified");
    let truth = base.model_values();
    for (b, &expected) in truth.iter().enumerate() {
        let (value, sigma) = (estimate.values[b], estimate.deviations[b]);
        let error = (value - expected).abs();
        assert!(
            error <= 0.02 * expected.abs() || error <= 3.0 * sigma,
            "b{} = {}: {value:e} vs {expected:e} (σ {sigma:e})",
            b + 1,
            base.combination(b)
        );
    }
    // The weights found each joint's noise, 1 % of its RMS torque.
    for (j, sigma) in estimate.joint_deviations.iter().enumerate() {
        let rms = (data.samples.iter().map(|s| s.tau[j].powi(2)).sum::<f64>()
            / data.samples.len() as f64)
            .sqrt();
        assert!(
            (sigma / (0.01 * rms) - 1.0).abs() < 0.15,
            "joint {}: σ {sigma:e}, RMS {rms:e}",
            j + 1
        );
    }
    let (fresh, _) = measured(&mut reference, &base, 2, 0);
    let predicted = predict(&mut reference, &base, &estimate.values, &fresh).expect("predicted");
    let fit = fit(&predicted, &fresh);
    assert!(
        fit.overall <= 0.02,
        "RMS error {:.3} %",
        100.0 * fit.overall
    );
    for (j, e) in fit.joints.iter().enumerate() {
        assert!(*e <= 0.02, "joint {}: RMS error {:.3} %", j + 1, 100.0 * e);
    }
}

/// Bad measurement files are errors naming the file, the line and the column.
#[test]
fn identify_reports_bad_data_with_file_line_and_column() {
    let dir = std::env::temp_dir().join(format!("rne-identify-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("bad.csv");
    std::fs::write(
        &path,
        "q1,q2,qd1,qd2,qdd1,qdd2,tau1,tau2\n0,0,0,0,0,0,0,0\n0,0,0,0,0,zero,0,0\n",
    )
    .expect("written");
    let file = path.to_str().expect("utf-8 path");
    let error = rne(&["identify", "planar-elbow", file]).expect_err("bad data");
    assert_eq!(
        error,
        format!("{file}:3: column 6 (`qdd2`): `zero` is not a number")
    );
    let error = rne(&["identify", "irb140-3dof", file]).expect_err("wrong robot");
    assert!(
        error.starts_with(&format!("{file}:1: missing columns")),
        "{error}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `--excite` writes data that `rne identify` reads back; the JSON report has the documented
/// keys and recovers the planar elbow's base parameters; `rne show --what base-parameters`
/// prints the thesis's groups with their values.
#[test]
fn excite_then_identify_through_the_command() {
    let dir = std::env::temp_dir().join(format!("rne-excite-{}", std::process::id()));
    let path = dir.join("elbow.csv");
    let file = path.to_str().expect("utf-8 path");
    let report = rne(&[
        "identify",
        "planar-elbow",
        "--excite",
        file,
        "--iterations",
        "20",
        "--noise",
        "0.001",
        "--seed",
        "5",
    ])
    .expect("excitation written");
    assert!(report.contains("condition number"), "{report}");
    let json = rne(&[
        "identify",
        "planar-elbow",
        file,
        "--json",
        "--validate",
        file,
    ])
    .expect("identified");
    let json: serde_json::Value = serde_json::from_str(&json).expect("one JSON object");
    for key in [
        "model",
        "samples",
        "condition_number",
        "joint_std",
        "base_parameters",
        "validation",
    ] {
        assert!(json.get(key).is_some(), "missing {key}");
    }
    // The elbow's spec carries the thesis's viscous joint friction, so the six groups of
    // (4.45) and (4.47) come with f_v, f_c and an offset per joint, each its own base parameter.
    let parameters = json["base_parameters"].as_array().expect("a list");
    assert_eq!(parameters.len(), 12);
    assert_eq!(parameters[2]["combination"], "I1zz + 0.09·m2");
    assert_eq!(parameters[6]["combination"], "fv1");
    assert_eq!(parameters[9]["combination"], "fv2");
    for p in parameters {
        let (estimate, model, std) = (
            p["estimate"].as_f64().unwrap(),
            p["model"].as_f64().unwrap(),
            p["std"].as_f64().unwrap(),
        );
        // Unbiased: every estimate within five of its reported standard deviations; and the
        // parameters the data determine well (all nonzero ones here) to 0.5 %.
        assert!((estimate - model).abs() < 5.0 * std, "{p}");
        if model != 0.0 {
            assert!((estimate - model).abs() < 5e-3 * model.abs(), "{p}");
        }
    }
    assert!(json["validation"]["relative_rms"].as_f64().unwrap() < 0.002);
    std::fs::remove_dir_all(&dir).ok();

    let shown = rne(&["show", "planar-elbow", "--what", "base-parameters"]).expect("shown");
    let lines: Vec<&str> = shown.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(lines[0], "b1 = m1·cx1 + 0.3·m2  # = 6.75");
    assert_eq!(lines[2], "b3 = I1zz + 0.09·m2   # = 1.807962");
}

/// `--floating-base`: rne-models' quadruped on a free-flyer is excited (base and legs) and
/// identified through the command, from data of NQ = 15 positions and NV = 14 rates and forces,
/// and its figure is drawn.
#[test]
fn a_floating_base_is_excited_and_identified_through_the_command() {
    let robot = QUADRUPED.path();
    let robot = robot.to_str().expect("utf-8 path");
    let dir = std::env::temp_dir().join(format!("rne-floating-{}", std::process::id()));
    let path = dir.join("quadruped.csv");
    let file = path.to_str().expect("utf-8 path");
    let figure_path = dir.join("quadruped.svg");
    let figure = figure_path.to_str().expect("utf-8 path");
    let limits = "0.3,0.3,0.3,0.8,0.8,0.8,1.2,1.2,1.2,1.2,1.2,1.2,1.2,1.2";
    rne(&[
        "identify",
        robot,
        "--floating-base",
        "--excite",
        file,
        "--iterations",
        "10",
        "--noise",
        "0.001",
        "--q-limit",
        limits,
    ])
    .expect("excitation written");
    let header = std::fs::read_to_string(&path).expect("written");
    let header = header.lines().next().expect("a header");
    assert!(header.contains("q15") && header.contains("tau14") && !header.contains("qd15"));
    let json = rne(&[
        "identify",
        robot,
        "--floating-base",
        file,
        "--json",
        "--validate",
        file,
        "--plot",
        figure,
    ])
    .expect("identified");
    // The figure's panels name the base's wrench (first six forces) apart from the joints.
    let svg = std::fs::read_to_string(&figure_path).expect("figure written");
    for label in [
        "base force x (N)",
        "base moment z (N·m)",
        "joint 8 torque (N·m)",
    ] {
        assert!(svg.contains(label), "{label} missing from the figure");
    }
    assert!(!svg.contains("joint 9 torque"));
    let json: serde_json::Value = serde_json::from_str(&json).expect("one JSON object");
    for p in json["base_parameters"].as_array().expect("a list") {
        let (estimate, model) = (
            p["estimate"].as_f64().unwrap(),
            p["model"].as_f64().unwrap(),
        );
        let sigma = p["std"].as_f64().unwrap();
        assert!(
            (estimate - model).abs() <= 0.02 * model.abs() + 3.0 * sigma,
            "{p}"
        );
    }
    assert!(json["validation"]["relative_rms"].as_f64().unwrap() < 0.002);
    std::fs::remove_dir_all(&dir).ok();
}

/// `--engine jit` (the generated regressor compiled in memory) and `--engine numeric` (the
/// independent reference) identify the same base parameters from the same data, with joint
/// friction and armature added to the model (`--friction --armature`: their columns come
/// after the bodies' in both), and the excitation they design has the same condition number.
#[test]
fn the_jit_and_the_numeric_reference_identify_the_same_parameters() {
    let dir = std::env::temp_dir().join(format!("rne-engines-{}", std::process::id()));
    let path = dir.join("irb140.csv");
    let file = path.to_str().expect("utf-8 path");
    let excite = |engine: &str| {
        let args = ["identify", "irb140", "--excite", file, "--iterations", "5"];
        let json = rne(&[&args[..], &["--json", "--engine", engine, "--friction"]].concat())
            .expect("excitation written");
        let json: serde_json::Value = serde_json::from_str(&json).expect("one JSON object");
        json["condition_number"].as_f64().expect("a number")
    };
    let (numeric, jit) = (excite("numeric"), excite("jit"));
    assert!(
        (numeric - jit).abs() <= 1e-9 * numeric,
        "{numeric} vs {jit}"
    );
    let estimates = |engine: &str| -> Vec<f64> {
        let args = [
            "identify",
            "irb140",
            file,
            "--json",
            "--friction",
            "--armature",
        ];
        let json = rne(&[&args[..], &["--engine", engine]].concat()).expect("identified");
        let json: serde_json::Value = serde_json::from_str(&json).expect("one JSON object");
        json["base_parameters"]
            .as_array()
            .expect("a list")
            .iter()
            .map(|p| p["estimate"].as_f64().expect("a number"))
            .collect()
    };
    let (numeric, jit) = (estimates("numeric"), estimates("jit"));
    assert_eq!(numeric.len(), jit.len());
    let scale = numeric.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (a, b) in numeric.iter().zip(&jit) {
        assert!((a - b).abs() <= 1e-8 * scale, "{numeric:?} vs {jit:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
