//! Small URDFs as robots are published (mimic chains, a follower before its leader, a mimic on
//! a fixed joint, a mimic of a joint the file does not have, continuous joints, odd names, stray
//! elements, slightly wrong inertias, a body without joints) and rne-models' quadruped, against Pinocchio 4.1's values committed here:
//! CI checks rne against Pinocchio without Python. Regenerate the values with
//! `python tools/peers/pinocchio_values.py rne-models/corpus/tests/fixtures --states 3 --out
//! rne-models/corpus/tests/fixtures/pinocchio.json` and `python tools/peers/pinocchio_values.py
//! rne-models/robots --only quadruped --states 3 --out
//! rne-models/corpus/tests/fixtures/pinocchio-robots.json` (`python`: the one of the environment
//! `tools/peers/setup.sh` installs, `~/.cache/rne-peers/venv/bin/python`).

use std::path::{Path, PathBuf};

use rne_codegen::Kernel;
use rne_corpus::{check_robot, CaseReport, KernelOutcome, PinocchioValues, RobotReport};
use rne_models::robots_dir;

/// The bar: every error at most 1e-10 of the robot's torque scale.
const TOLERANCE: f64 = 1e-10;

/// The fixtures' reports, then those of the robot files Pinocchio's values were computed for.
fn reports() -> Vec<RobotReport> {
    let values = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    let mut reports = compare(&values, "pinocchio.json", &values);
    reports.extend(compare(&values, "pinocchio-robots.json", robots_dir()));
    reports
}

/// Every robot of `values_dir/values_file` read from `robots`.
fn compare(values_dir: &Path, values_file: &str, robots: &Path) -> Vec<RobotReport> {
    let text = std::fs::read_to_string(values_dir.join(values_file)).unwrap();
    let values: PinocchioValues = serde_json::from_str(&text).unwrap();
    assert_eq!(values.pinocchio, "4.1.0");
    values
        .robots
        .iter()
        .map(|robot| check_robot(robots, robot))
        .collect()
}

fn compared<'a>(report: &'a RobotReport, case: &'a CaseReport) -> &'a rne_corpus::Comparison {
    match case {
        CaseReport::Compared(c) => c,
        other => panic!("{}: {other:?}", report.file),
    }
}

#[test]
fn every_fixture_agrees_with_pinocchio_on_id_m_g_bias_and_fd_on_both_bases() {
    let reports = reports();
    let files: Vec<&str> = reports.iter().map(|r| r.file.as_str()).collect();
    assert_eq!(
        files,
        [
            "arm_mimic_chain.urdf",
            "baxter.urdf",
            "brick.urdf",
            "finger_missing_leader.urdf",
            "hand_mimic.urdf",
            "iris.urdf",
            "tiago_no_hand.urdf",
            "quadruped.urdf"
        ]
    );
    for report in &reports {
        // A mimic of a missing joint is an error with mimic joints constrained (rne's
        // default); the comparison reads that file with mimic joints free.
        let refused = report.file == "finger_missing_leader.urdf";
        assert_eq!(
            report.load.is_err(),
            refused,
            "{}: {:?}",
            report.file,
            report.load
        );
        let cases = [("fixed", &report.fixed), ("floating", &report.floating)];
        for (base, case) in cases {
            if report.file == "brick.urdf" && base == "fixed" {
                assert!(matches!(case, CaseReport::NothingMoves), "{case:?}");
                continue;
            }
            let c = compared(report, case);
            assert_eq!(c.forward_skipped, None, "{} {base}", report.file);
            for (engine, errors) in [("symbolic", &c.symbolic), ("numeric", &c.numeric)] {
                let (error, what) = errors.max();
                assert!(
                    error <= TOLERANCE,
                    "{} {base} {engine}: {what} differs from Pinocchio by {error:e}",
                    report.file
                );
                assert!(errors.forward.is_some());
            }
        }
    }
}

/// The cases the fixtures were written for reached the comparison as intended.
#[test]
fn the_fixtures_exercise_mimic_both_ways_floating_bases_and_warnings() {
    let reports = reports();
    let by_name = |name: &str| reports.iter().find(|r| r.file == name).unwrap();
    let arm = by_name("arm_mimic_chain.urdf");
    assert_eq!(
        compared(arm, &arm.fixed).mimic,
        "projected",
        "the follower before its leader: Pinocchio's mimic=True refuses it"
    );
    assert_eq!(
        arm.load.as_ref().unwrap().dof,
        4,
        "two followers constrained"
    );
    let hand = by_name("hand_mimic.urdf");
    assert_eq!(compared(hand, &hand.fixed).mimic, "pinocchio");
    let warnings = &hand.load.as_ref().unwrap().warnings;
    assert!(warnings.contains(&"triangle inequality"), "{warnings:?}");
    assert!(
        warnings.contains(&"negligible negative inertia"),
        "{warnings:?}"
    );
    let quadruped = by_name("quadruped.urdf");
    assert_eq!(compared(quadruped, &quadruped.floating).nv, 6 + 8);
    let brick = by_name("brick.urdf");
    assert_eq!(compared(brick, &brick.floating).nv, 6);
    let finger = by_name("finger_missing_leader.urdf");
    let error = finger.load.as_ref().unwrap_err();
    assert!(
        error.contains("Left_index_q2") && error.contains("index_q1"),
        "the default reading names the follower and its missing leader: {error}"
    );
    for case in [&finger.fixed, &finger.floating] {
        let c = compared(finger, case);
        assert_eq!(
            c.mimic, "free",
            "Pinocchio's mimic=False, every follower free"
        );
    }
    assert_eq!(
        compared(finger, &finger.fixed).nv,
        2,
        "the follower of a missing joint is a joint of its own"
    );
}

/// Every kernel the generator can emit is generated for every fixture on both bases and agrees
/// with the numeric reference: Baxter's, TIAGo's and Iris's forward-dynamics derivatives, which
/// ended in a panic while their joints of constant, decoupled inertia (wheels, gripper fingers,
/// rotors) let the graph fold the held accelerations away, among them.
#[test]
fn every_kernel_of_every_fixture_agrees_with_the_reference_on_both_bases() {
    let reports = reports();
    let mut compared_kernels = 0;
    for report in &reports {
        for (base, case) in [("fixed", &report.fixed), ("floating", &report.floating)] {
            let CaseReport::Compared(c) = case else {
                continue;
            };
            assert_eq!(c.kernels.len(), Kernel::ALL.len());
            for check in &c.kernels {
                match &check.outcome {
                    KernelOutcome::Compared(error) => {
                        compared_kernels += 1;
                        assert!(
                            *error <= TOLERANCE,
                            "{} {base} {}: error {error:e} against the reference",
                            report.file,
                            check.kernel
                        );
                    }
                    other => panic!("{} {base} {}: {other:?}", report.file, check.kernel),
                }
            }
        }
    }
    // 7 robots with a fixed and a floating base and the brick on a floating base only, every
    // kernel of each.
    assert_eq!(compared_kernels, 15 * Kernel::ALL.len());
}
