//! `rne bench --quick` end to end: every robot, kernel and implementation measured, errors of
//! the right size for each format, the URDF robots' control kernels measured, integrators ordered by accuracy, and the report and its
//! figures written.

use std::collections::BTreeSet;

use rne_bench::control::CONTROL;
use rne_bench::integrators::Family;
use rne_bench::robots::BENCHED;
use rne_bench::{self as bench, Effort, Implementation};
use rne_models::BUILTIN_ROBOTS;

#[test]
fn quick_bench_measures_every_robot_and_writes_its_report() {
    let report = bench::run(Effort::Quick, None, |_| {}).expect("the quick bench runs");

    assert_eq!(report.kernels.len(), BUILTIN_ROBOTS.len());
    for robot in &report.kernels {
        for kernel in BENCHED {
            let rows: Vec<_> = robot.rows.iter().filter(|r| r.kernel == kernel).collect();
            let implementations: BTreeSet<Implementation> =
                rows.iter().map(|r| r.implementation).collect();
            for always in [
                Implementation::Generated,
                Implementation::Single,
                Implementation::Interpreted,
                Implementation::Reference,
            ] {
                assert!(
                    implementations.contains(&always),
                    "{} {}: no {:?} row",
                    robot.robot,
                    kernel.name(),
                    always
                );
            }
            for row in &rows {
                let what = format!(
                    "{} {} {}",
                    robot.robot,
                    kernel.name(),
                    row.implementation.label()
                );
                assert!(row.timing.median() > 0.0, "{what}: no time");
                let bound = match row.implementation {
                    Implementation::Single => 1e-4,
                    _ => 1e-13,
                };
                assert!(
                    row.errors.max_relative <= bound,
                    "{what}: max relative error {:e} above {bound:e}",
                    row.errors.max_relative
                );
            }
            let generated = rows
                .iter()
                .find(|r| r.implementation == Implementation::Generated)
                .expect("generated row");
            let interpreted = rows
                .iter()
                .find(|r| r.implementation == Implementation::Interpreted)
                .expect("interpreted row");
            assert_eq!(
                generated.errors,
                interpreted.errors,
                "{} {}: the interpreted program is the emitted one, bit for bit",
                robot.robot,
                kernel.name()
            );
            let single = rows
                .iter()
                .find(|r| r.implementation == Implementation::Single)
                .expect("f32 row");
            assert!(
                single.errors.median_relative > 1e3 * generated.errors.median_relative,
                "{} {}: f32 should be visibly less accurate than f64",
                robot.robot,
                kernel.name()
            );
        }
    }

    let urdf = ["ur5", "panda", "panda-arm"];
    assert_eq!(
        report.control.iter().map(|c| c.robot).collect::<Vec<_>>(),
        urdf,
        "the URDF robots' control kernels are measured"
    );
    for robot in &report.control {
        let kernels: Vec<_> = robot.rows.iter().map(|r| r.kernel).collect();
        assert_eq!(kernels, CONTROL, "{}: every control kernel", robot.robot);
        for row in &robot.rows {
            assert!(
                row.timing.median() > 0.0,
                "{} {:?}: no time",
                robot.robot,
                row.kernel
            );
            assert!(
                row.errors.states > 0 && row.errors.max_relative <= 1e-12,
                "{} {:?}: max relative error {:e} above 1e-12",
                robot.robot,
                row.kernel,
                row.errors.max_relative
            );
        }
    }

    assert_eq!(report.integrators.len(), 2);
    for study in &report.integrators {
        for family in Family::ALL {
            let errors: Vec<f64> = study
                .rows
                .iter()
                .filter(|r| r.family == family && family != Family::Dopri5)
                .map(|r| r.final_error)
                .collect();
            assert!(
                errors.windows(2).all(|w| w[1] < w[0]),
                "{} {}: a finer step must be more accurate: {errors:?}",
                study.name,
                family.label()
            );
        }
    }

    let dir = std::env::temp_dir().join(format!("rne-bench-report-{}", std::process::id()));
    let written = report.write(&dir).expect("the report is written");
    let markdown = std::fs::read_to_string(dir.join("bench-report.md")).expect("report");
    for robot in BUILTIN_ROBOTS {
        assert!(markdown.contains(&format!("### {} (", robot.name)));
        let png = std::fs::read(dir.join(format!("bench-{}.png", robot.name))).expect("figure");
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n") && png.len() > 10_000);
    }
    assert!(markdown.contains("## Scene savings"));
    assert!(markdown.contains("## Control and identification kernels"));
    assert!(markdown.contains("| panda | inverse_dynamics_derivatives | "));
    assert!(markdown.contains("| puma560 | "));
    assert_eq!(
        written.len(),
        2 * (BUILTIN_ROBOTS.len() + 2) + 1,
        "SVG and PNG per chart, and the report"
    );
    std::fs::remove_dir_all(&dir).expect("clean up");
}

/// Right after each run of Pinocchio's scripts every kernel of the comparison table is timed
/// again (`beside`), the control module's as well as the dynamics kernels: the ratios pair
/// each run's figures with these times.
#[test]
fn every_kernel_set_beside_pinocchio_is_timed_in_the_paired_pass() {
    use rne_bench::pinocchio::COMPARISONS;
    let effort = Effort::Quick;
    let ur5 = BUILTIN_ROBOTS
        .iter()
        .find(|r| r.name == "ur5")
        .expect("UR5 is built in");
    let cases = rne_bench::robots::Cases::new(ur5, effort.samples()).expect("UR5's cases");
    let times = rne_bench::beside::time_compared(&cases, &effort.kernel_plan(), effort.pool())
        .expect("the paired pass runs");
    for c in COMPARISONS {
        let ns = times.get(&c.kernel).copied().unwrap_or(f64::NAN);
        assert!(ns > 0.0, "{}: not timed ({ns})", c.kernel.name());
    }
    assert_eq!(times.len(), COMPARISONS.len());
}
