//! The benchmark report: markdown tables and work-precision charts, written as
//! `bench-report.md` and `bench-*.svg` / `bench-*.png`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Duration;

use rne_codegen::Kernel;

use super::error::BenchError;
use super::implementation::Implementation;
use super::integrators::{Family, IntegratorStudy, REFERENCE_TOLERANCE};
use super::kernels::{KernelRow, RobotKernels};
use super::pinocchio::{codegen_key, PinocchioTimes, COMPARISONS};
use super::robots::{BENCHED, SEED};
use super::sample::{QDD_BOUND, QD_BOUND, TAU_FLOOR};
use super::scenes::{RobotScenes, SceneKernel};
use super::Effort;
use rne_figures::work_precision::{Chart, Marker, Panel, Point, Series};
use rne_figures::{render, sci, ulps, FigureError, Formats};

/// Inverse-dynamics operation counts published for built-in robots (SymPyBotics's): robot,
/// multiplications, additions, source.
pub const PUBLISHED: [(&str, usize, usize, &str); 2] = [
    ("puma560", 410, 343, "SymPyBotics"),
    ("panda-arm", 437, 414, "SymPyBotics"),
];

/// Everything `rne bench` measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// How much was measured.
    pub effort: Effort,
    /// Kernel work-precision, one entry per robot.
    pub kernels: Vec<RobotKernels>,
    /// The control and identification kernels of the URDF robots ([`crate::control`]).
    pub control: Vec<RobotKernels>,
    /// Scene savings, one entry per robot.
    pub scenes: Vec<RobotScenes>,
    /// Integrator work-precision, one entry per problem.
    pub integrators: Vec<IntegratorStudy>,
    /// Pinocchio's times on the URDF robots, when its script was given.
    pub pinocchio: Vec<PinocchioTimes>,
    /// Wall-clock time of the whole run.
    pub elapsed: Duration,
}

/// The file name of the report.
pub const REPORT_FILE: &str = "bench-report.md";

/// The marker of a kernel in the charts.
fn kernel_marker(kernel: Kernel) -> Marker {
    match kernel {
        Kernel::MassMatrix => Marker::Square,
        Kernel::BiasTorques => Marker::Triangle,
        Kernel::ForwardDynamics => Marker::Cross,
        _ => Marker::Circle,
    }
}

/// A time in ns with three significant digits.
fn ns(t: f64) -> String {
    if !t.is_finite() {
        "—".into()
    } else if t >= 100.0 {
        format!("{t:.0}")
    } else if t >= 10.0 {
        format!("{t:.1}")
    } else {
        format!("{t:.2}")
    }
}

/// A ratio.
fn ratio(r: f64) -> String {
    if r.is_finite() {
        format!("{r:.2}×")
    } else {
        "—".into()
    }
}

/// The command that produces a report with `effort` in this build: with the features that
/// built it (`fma`: fused kernels, `derivative-lanes`: derivatives in lanes) in a build for
/// the machine, as such a build is made.
fn command(effort: Effort) -> String {
    let fused = rne_models::generated::FUSED_MULTIPLY_ADD;
    let lanes = rne_models::generated::DERIVATIVE_LANES;
    let flags = match (fused || lanes) && cfg!(target_feature = "fma") {
        true => "RUSTFLAGS=\"-C target-cpu=native\" ",
        false => "",
    };
    let features = match (fused, lanes) {
        (true, true) => " --features fma,derivative-lanes",
        (true, false) => " --features fma",
        (false, true) => " --features derivative-lanes",
        (false, false) => "",
    };
    let quick = match effort {
        Effort::Quick => " --quick",
        Effort::Full => "",
    };
    format!("{flags}cargo run --release -p rne-cli{features} --bin rne -- bench{quick}")
}

/// The processor, as `/proc/cpuinfo` names it (Linux), and the number of hardware threads.
fn machine() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_owned())
        })
        .unwrap_or_else(|| "unknown processor".into());
    let threads = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{model}, {threads} hardware threads")
}

/// The build: its profile, whether its target has fused multiply-add (AVX2 and FMA, as in a
/// `RUSTFLAGS="-C target-cpu=native"` build on this kind of machine; Pinocchio's generated
/// code is built with `-march=native`), whether the URDF robots' kernels fuse (the `fma`
/// feature) and whether their derivatives are in lanes (the `derivative-lanes` feature).
fn build() -> String {
    let profile = if cfg!(debug_assertions) {
        "debug"
    } else {
        "release"
    };
    let target = match (cfg!(target_feature = "avx2"), cfg!(target_feature = "fma")) {
        (true, true) => "target with AVX2 and FMA",
        (false, true) => "target with FMA",
        (true, false) => "target with AVX2, no FMA",
        (false, false) => "baseline target, no FMA",
    };
    let fused = match (
        rne_models::generated::FUSED_MULTIPLY_ADD,
        cfg!(target_feature = "fma"),
    ) {
        (true, true) => "`fma: true`, fused",
        (true, false) => "`fma: true`, unfused on this target",
        (false, _) => "",
    };
    let lanes = match rne_models::generated::DERIVATIVE_LANES {
        true => "`derivatives: lanes`",
        false => "",
    };
    let kernels = match (fused, lanes) {
        ("", "") => String::new(),
        (only, "") | ("", only) => format!("; the URDF robots' kernels {only}"),
        (fused, lanes) => format!("; the URDF robots' kernels {fused}, and {lanes}"),
    };
    format!("{profile} build, {target}{kernels}")
}

impl Report {
    /// The report as markdown; figures are linked by their PNG file names.
    pub fn markdown(&self) -> String {
        let mut md = String::new();
        let effort = self.effort;
        let plan = effort.kernel_plan();
        let _ = writeln!(md, "# rne bench: run time against error\n");
        let _ = writeln!(
            md,
            "`{}` on {} ({}), {:.1} s. Kernels: {} seeded states per robot (ChaCha8, seed \
             {SEED:#x}; |q| ≤ π, |q̇| ≤ {QD_BOUND}, |q̈| ≤ {QDD_BOUND}, |τ| ≤ max({TAU_FLOOR}, \
             ‖g(q)‖∞)) for the errors, the first {} cycled through for the times; {} \
             interleaved rounds of batches of at least {} µs per implementation. Times are \
             medians over rounds with the interquartile range; ratios are medians of per-round \
             ratios, measured in this run. Errors are normwise relative, ‖a − x‖∞ / ‖x‖∞, and \
             in ulps of ‖x‖∞ in the implementation's format, against the double-double value x \
             of the same program.\n",
            command(effort),
            machine(),
            build(),
            self.elapsed.as_secs_f64(),
            effort.samples(),
            effort.pool(),
            plan.rounds,
            plan.batch.as_micros(),
        );
        self.pinocchio_table(&mut md);
        self.kernel_tables(&mut md);
        self.control_table(&mut md);
        self.scene_table(&mut md);
        self.published_table(&mut md);
        self.integrator_tables(&mut md);
        md
    }

    /// Writes [`REPORT_FILE`] and every chart (SVG and PNG) to `dir`, created if missing, and
    /// returns the paths written.
    pub fn write(&self, dir: &Path) -> Result<Vec<PathBuf>, BenchError> {
        std::fs::create_dir_all(dir).map_err(FigureError::io(dir))?;
        let mut written = Vec::new();
        for chart in self.charts() {
            written.extend(render(&chart, dir, Formats::BOTH)?);
        }
        let report = dir.join(REPORT_FILE);
        std::fs::write(&report, self.markdown()).map_err(FigureError::io(&report))?;
        written.push(report);
        Ok(written)
    }

    /// The charts: one per robot, one per integrator study.
    pub fn charts(&self) -> Vec<Chart> {
        let mut charts: Vec<Chart> = self.kernels.iter().map(kernel_chart).collect();
        charts.extend(self.integrators.iter().map(integrator_chart));
        charts
    }

    /// rne's generated `f64` kernel on `robot`, from the kernel or the control tables.
    fn generated(&self, robot: &str, kernel: Kernel) -> Option<&KernelRow> {
        self.kernels
            .iter()
            .chain(&self.control)
            .filter(|k| k.robot == robot)
            .flat_map(|k| &k.rows)
            .find(|r| r.kernel == kernel && r.implementation == Implementation::Generated)
    }

    fn pinocchio_table(&self, md: &mut String) {
        let Some(first) = self.pinocchio.first() else {
            return;
        };
        let (calls, runs) = (first.calls, first.paired.runs());
        let codegen = match first.codegen_calls {
            Some(c) => format!(
                "; `run_cg.sh ROBOT.urdf {c}` beside it (in {} of the runs) times Pinocchio's \
                 analytical derivatives, `computeMinverse` and the CppADCodeGen code of each \
                 algorithm (CG: through `CodeGenX::evalFunction`, what a Pinocchio user calls; CG \
                 floor: the generated function on a pre-packed input; gcc -Ofast, median of 5 \
                 interleaved repetitions); max diff is the generated code's largest difference \
                 from the plain algorithm over 64 states",
                first.codegen_runs
            ),
            None => "; `run_cg.sh` was skipped".to_owned(),
        };
        let _ = writeln!(
            md,
            "## Beside Pinocchio\n\nPinocchio 4.1.0 on the same URDF as each built-in robot, \
             timed {runs} times during this run (before, between and after rne's timings of \
             that robot), median kept: `tools/peers/run.sh ROBOT.urdf {calls}` \
             times the plain algorithms (header-only C++, -O3 -march=native, seeded states, \
             mean over {calls} calls){codegen}; `tools/peers/run_extra.sh ROBOT.urdf \
             {calls}` times the Jacobians (`computeJointJacobians`, then each joint's 6 × nv \
             Jacobian in world axes), J̇q̇ and the regressor. Right after each run the \
             generated f64 kernels of this table are timed together again: rne's time is the \
             median over those runs and its error the largest normwise relative error against \
             the double-double value (tables below). × = the median over runs of Pinocchio's \
             time in the run / rne's time right after it, so that the machine's changes of \
             speed between runs favour neither side.\n\n\
             | robot | quantity | rne kernel | rne ns | rne max rel. error | Pinocchio | ns | × \
             | CG ns | × | CG floor ns | × | CG max diff |\n\
             |---|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|"
        );
        for times in &self.pinocchio {
            for c in COMPARISONS {
                let Some(ours) = self.generated(times.robot, c.kernel) else {
                    continue;
                };
                let rne = times.paired.rne(c.kernel);
                // A figure of Pinocchio's, and rne's ratio to it (paired run by run).
                let peer = |key: &str| (times.get(key), times.paired.ratio(key, c.kernel));
                let plain = peer(c.plain.1);
                let none = (f64::NAN, f64::NAN);
                let (cg, raw) = c.codegen.map_or((none, none), |x| {
                    (
                        peer(&codegen_key(x, "_ns")),
                        peer(&codegen_key(x, "_raw_ns")),
                    )
                });
                let diff = c.codegen.map(|x| times.codegen(x, "_maxdiff"));
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                    times.robot,
                    c.quantity,
                    c.kernel.name(),
                    ns(rne),
                    sci(ours.errors.max_relative),
                    c.plain.0,
                    ns(plain.0),
                    ratio(plain.1),
                    ns(cg.0),
                    ratio(cg.1),
                    ns(raw.0),
                    ratio(raw.1),
                    diff.map_or_else(|| "—".to_owned(), sci),
                );
            }
        }
        let _ = writeln!(md);
    }

    fn control_table(&self, md: &mut String) {
        if self.control.is_empty() {
            return;
        }
        let _ = writeln!(
            md,
            "## Control and identification kernels\n\nThe URDF robots' generated `control` \
             modules (derivatives, M⁻¹, the Jacobians and J̇q̇ of every link's frame, the \
             joint-torque regressor), timed together; errors against the double-double value \
             of the same programs over the whole sample.\n\n\
             | robot | kernel | ns/call | IQR | max rel. error | median rel. error | max ulps \
             | median ulps |\n|---|---|---:|---:|---:|---:|---:|---:|"
        );
        for robot in &self.control {
            for row in &robot.rows {
                let (q1, q3) = row.timing.quartiles();
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {}–{} | {} | {} | {} | {} |",
                    robot.robot,
                    row.kernel.name(),
                    ns(row.timing.median()),
                    ns(q1),
                    ns(q3),
                    sci(row.errors.max_relative),
                    sci(row.errors.median_relative),
                    ulps(row.errors.max_ulps),
                    ulps(row.errors.median_ulps),
                );
            }
        }
        let _ = writeln!(md);
    }

    fn kernel_tables(&self, md: &mut String) {
        let _ = writeln!(md, "## Kernels\n");
        for robot in &self.kernels {
            let _ = writeln!(md, "### {} ({} joints)\n", robot.robot, robot.dof);
            let _ = writeln!(
                md,
                "![{0}: time per call against error](bench-{0}.png)\n",
                robot.robot
            );
            let _ = writeln!(
                md,
                "| kernel | implementation | ns/call | IQR | × generated f64 | max rel. error \
                 | median rel. error | max ulps | median ulps |\n|---|---|---:|---:|---:|---:|---:|---:|---:|"
            );
            for row in &robot.rows {
                let (q1, q3) = row.timing.quartiles();
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {}–{} | {} | {} | {} | {} | {} |",
                    row.kernel.name(),
                    row.implementation.label(),
                    ns(row.timing.median()),
                    ns(q1),
                    ns(q3),
                    ratio(row.relative_time),
                    sci(row.errors.max_relative),
                    sci(row.errors.median_relative),
                    ulps(row.errors.max_ulps),
                    ulps(row.errors.median_ulps),
                );
            }
            let _ = writeln!(md);
        }
    }

    fn scene_table(&self, md: &mut String) {
        let _ = writeln!(
            md,
            "## Scene savings: inverse dynamics\n\nOperations of the emitted program (mul, add, \
             cost in additions: div and sqrt 4, sin or cos 5) and ns per call, timed together; \
             × full is the median per-round ratio to the full kernel.\n\n\
             | robot | scene | mul | add | cost | ns/call | × full |\n|---|---|---:|---:|---:|---:|---:|"
        );
        for robot in &self.scenes {
            for row in &robot.rows {
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {} | {} | {} | {} |",
                    robot.robot,
                    row.scene.label(),
                    row.ops.mul,
                    row.ops.add,
                    row.ops.cost(),
                    ns(row.timing.median()),
                    ratio(row.relative_time),
                );
            }
        }
        let _ = writeln!(md);
    }

    fn published_table(&self, md: &mut String) {
        let _ = writeln!(
            md,
            "## Operation counts beside published ones\n\nInverse dynamics with numeric \
             parameters (published with SymPyBotics); rne's counts are those of `rne stats`.\n\n\
             | robot | rne mul | rne add | published mul | published add | source |\n|---|---:|---:|---:|---:|---|"
        );
        for (robot, mul, add, source) in PUBLISHED {
            let ours = self
                .scenes
                .iter()
                .find(|s| s.robot == robot)
                .and_then(|s| s.rows.iter().find(|r| r.scene == SceneKernel::Full));
            if let Some(row) = ours {
                let _ = writeln!(
                    md,
                    "| {robot} | {} | {} | {mul} | {add} | {source} |",
                    row.ops.mul, row.ops.add
                );
            }
        }
        let _ = writeln!(md);
    }

    fn integrator_tables(&self, md: &mut String) {
        let _ = writeln!(md, "## Integrators\n");
        for study in &self.integrators {
            let _ = writeln!(
                md,
                "### {}, {} s\n\n![{0}](bench-{}.png)\n\nReference: Dormand–Prince at rtol = atol = \
                 {REFERENCE_TOLERANCE:.0e}; its distance to a Gauss–Legendre run with a 100 \
                 times finer step is {}, its energy drift {} J. Final-state error: max |Δq| \
                 (rad), |Δq̇| (rad/s) at {} s; energy drift: max |E(t) − E(0)| (J) on a 0.01 s \
                 grid.\n",
                study.title,
                study.duration,
                study.name,
                sci(study.reference_error),
                sci(study.reference_drift),
                study.duration,
            );
            let _ = writeln!(
                md,
                "| method | parameter | steps | evaluations | time to solution (ms) | IQR (ms) \
                 | final-state error | energy drift (J) |\n|---|---|---:|---:|---:|---:|---:|---:|"
            );
            for row in &study.rows {
                let (q1, q3) = row.timing.quartiles();
                let ms = |t: f64| format!("{:.3}", t * 1e-6);
                let _ = writeln!(
                    md,
                    "| {} | {} {:.0e} | {} | {} | {} | {}–{} | {} | {} |",
                    row.family.label(),
                    row.family.parameter_name(),
                    row.parameter,
                    row.stats.steps,
                    row.stats.evaluations,
                    ms(row.timing.median()),
                    ms(q1),
                    ms(q3),
                    sci(row.final_error),
                    sci(row.energy_drift),
                );
            }
            let _ = writeln!(md);
        }
    }
}

/// Errors at or below this are drawn at it on the kernel charts.
const ERROR_FLOOR: f64 = 1e-18;

/// The work-precision chart of one robot: a point per implementation and kernel at (median
/// time, largest error), with the interquartile range of the time and a bar down to the median
/// error.
fn kernel_chart(robot: &RobotKernels) -> Chart {
    let series = Implementation::ALL
        .iter()
        .enumerate()
        .filter_map(|(colour, &implementation)| {
            let points: Vec<Point> = robot
                .rows
                .iter()
                .filter(|r| r.implementation == implementation)
                .map(|r| Point {
                    x: r.timing.median(),
                    y: r.errors.max_relative,
                    x_bar: Some(r.timing.quartiles()),
                    y_bar: Some((r.errors.median_relative, r.errors.max_relative)),
                    marker: kernel_marker(r.kernel),
                })
                .collect();
            (!points.is_empty()).then(|| Series {
                label: implementation.label().to_owned(),
                colour,
                points,
                joined: false,
            })
        })
        .collect();
    let kernel_names = [
        "inverse dynamics",
        "mass matrix",
        "bias torques",
        "forward dynamics",
    ];
    Chart {
        file: format!("bench-{}", robot.robot),
        title: format!(
            "{} ({} joints): time per call against error",
            robot.robot, robot.dof
        ),
        panels: vec![Panel {
            x_label: "ns per call (median, bar: interquartile range)".into(),
            y_label: format!(
                "relative error (max, bar from median; ≤ {ERROR_FLOOR:.0e} drawn at it)"
            ),
            series,
            marker_legend: BENCHED
                .iter()
                .zip(kernel_names)
                .map(|(&k, name)| (kernel_marker(k), name.to_owned()))
                .collect(),
            y_floor: ERROR_FLOOR,
        }],
    }
}

/// The work-precision chart of one integrator study: time to solution against final-state
/// error (left) and against energy drift (right), a line per integrator family.
fn integrator_chart(study: &IntegratorStudy) -> Chart {
    let series = |value: fn(&super::integrators::IntegratorRow) -> f64| -> Vec<Series> {
        Family::ALL
            .iter()
            .enumerate()
            .map(|(colour, &family)| Series {
                label: family.label().to_owned(),
                colour,
                points: study
                    .rows
                    .iter()
                    .filter(|r| r.family == family)
                    .map(|r| {
                        let (q1, q3) = r.timing.quartiles();
                        Point {
                            x: r.timing.median() * 1e-6,
                            y: value(r),
                            x_bar: Some((q1 * 1e-6, q3 * 1e-6)),
                            y_bar: None,
                            marker: Marker::Circle,
                        }
                    })
                    .collect(),
                joined: true,
            })
            .collect()
    };
    let floor = 1e-16;
    Chart {
        file: format!("bench-{}", study.name),
        title: format!("{}, {} s", study.title, study.duration),
        panels: vec![
            Panel {
                x_label: "time to solution (ms)".into(),
                y_label: "final-state error (rad, rad/s)".into(),
                series: series(|r| r.final_error),
                marker_legend: Vec::new(),
                y_floor: floor,
            },
            Panel {
                x_label: "time to solution (ms)".into(),
                y_label: "energy drift (J)".into(),
                series: series(|r| r.energy_drift),
                marker_legend: Vec::new(),
                y_floor: floor,
            },
        ],
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::beside::PairedTimes;
    use crate::pinocchio::PinocchioScript;
    use crate::precision::ErrorSummary;
    use crate::timing::Timing;

    /// The comparison table's row: rne's time is the median of its paired passes, Pinocchio's
    /// the median of its runs, and each × the median of the per-run ratios (CppADCodeGen's
    /// over the one run that timed it), not a ratio of the two medians.
    #[test]
    fn the_pinocchio_table_shows_ratios_paired_run_by_run() {
        let id = Kernel::InverseDynamics;
        let row = KernelRow {
            kernel: id,
            implementation: Implementation::Generated,
            timing: Timing {
                samples: vec![60.0],
                calls: 1,
            },
            relative_time: 1.0,
            errors: ErrorSummary {
                states: 1,
                max_relative: 4e-15,
                median_relative: 1e-16,
                max_ulps: 2.0,
                median_ulps: 0.5,
            },
        };
        let figures = |pairs: &[(&str, f64)]| -> BTreeMap<String, f64> {
            pairs.iter().map(|&(k, v)| (k.to_owned(), v)).collect()
        };
        let mut paired = PairedTimes::default();
        paired.push(
            figures(&[
                ("run.rnea_ns", 400.0),
                ("cg.cg_rnea_ns", 200.0),
                ("cg.cg_rnea_raw_ns", 150.0),
                ("cg.cg_rnea_maxdiff", 1e-15),
            ]),
            [(id, 50.0)].into(),
        );
        paired.push(figures(&[("run.rnea_ns", 800.0)]), [(id, 100.0)].into());
        paired.push(figures(&[("run.rnea_ns", 900.0)]), [(id, 90.0)].into());
        let script = PinocchioScript::new(PathBuf::from("run.sh"), 1000, Some(500), None);
        let report = Report {
            effort: Effort::Quick,
            kernels: vec![RobotKernels {
                robot: "ur5",
                dof: 6,
                rows: vec![row],
            }],
            control: Vec::new(),
            scenes: Vec::new(),
            integrators: Vec::new(),
            pinocchio: vec![script.times("ur5", paired)],
            elapsed: Duration::from_secs(1),
        };
        let mut md = String::new();
        report.pinocchio_table(&mut md);
        let line = md
            .lines()
            .find(|l| l.starts_with("| ur5 | ID |"))
            .expect("a row for UR5's inverse dynamics");
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        // rne ns (median of 50, 100, 90), error, Pinocchio ns (median of 400, 800, 900), ×
        // (median of 8, 8, 10), CG ns and × (200 / 50), floor ns and × (150 / 50).
        assert_eq!(
            cells[4..13],
            ["90.0", "4.0e-15", "rnea", "800", "8.00×", "200", "4.00×", "150", "3.00×"],
            "{line}"
        );
        assert!(md.contains("runs favour neither side"), "{md}");
    }
}
