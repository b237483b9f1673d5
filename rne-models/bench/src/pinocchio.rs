//! The comparison with Pinocchio (issue 6): its RNEA, CRBA, ABA and nonLinearEffects timed by
//! the scripts of `../shared/tools/pinocchio/` on the same URDF files as the built-in robots,
//! within the same `rne bench` run as the generated kernels, and quoted as ratios.
//!
//! The scripts stay outside the repository; `rne bench --pinocchio PATH/run.sh` calls them.
//! `run.sh ROBOT.urdf CALLS` prints lines `name value`, of which `rnea_ns`, `crba_ns`, `aba_ns`
//! and `nle_ns` are read. For each robot the script runs three times: before rne's
//! kernels of that robot are timed, after them, and after its scene variants; the median of
//! each figure is kept, so that a change of machine load during the run does not favour
//! either side.

use std::path::{Path, PathBuf};
use std::process::Command;

use rne_codegen::Kernel;

use super::error::BenchError;
use super::implementation::Implementation;
use super::kernels::RobotKernels;
use super::timing::quantile;
use rne_figures::FigureError;
use rne_models::BuiltinRobot;

/// Built-in robots compared with Pinocchio: the URDF ones.
pub const COMPARED: [&str; 3] = ["ur5", "panda-arm", "panda"];

/// Pinocchio's algorithms and the generated kernel each is set beside.
pub const ALGORITHMS: [(&str, Kernel); 4] = [
    ("RNEA", Kernel::InverseDynamics),
    ("CRBA", Kernel::MassMatrix),
    ("nonLinearEffects", Kernel::BiasTorques),
    ("ABA", Kernel::ForwardDynamics),
];

/// Pinocchio's ns per call on one robot, the median over the runs, in the order of
/// [`ALGORITHMS`].
#[derive(Clone, Debug, PartialEq)]
pub struct PinocchioTimes {
    /// The built-in robot.
    pub robot: &'static str,
    /// ns per call of each algorithm of [`ALGORITHMS`].
    pub ns: [f64; 4],
    /// Calls per figure in each run of the script.
    pub calls: u64,
}

/// The timing script and how many calls each of its figures averages.
#[derive(Clone, Debug, PartialEq)]
pub struct PinocchioScript {
    /// `run.sh` of `../shared/tools/pinocchio/`.
    pub path: PathBuf,
    /// Calls per figure.
    pub calls: u64,
}

impl PinocchioScript {
    /// Runs the script once on `robot`'s URDF (written to `scratch` first) and returns its ns
    /// per call of each algorithm of [`ALGORITHMS`].
    pub fn run_once(&self, robot: &BuiltinRobot, scratch: &Path) -> Result<[f64; 4], BenchError> {
        let failure = |problem: String| BenchError::Pinocchio {
            robot: robot.name.to_owned(),
            problem,
        };
        std::fs::create_dir_all(scratch).map_err(FigureError::io(scratch))?;
        let urdf = scratch.join(format!("{}.urdf", robot.name));
        std::fs::write(&urdf, robot.source).map_err(FigureError::io(&urdf))?;
        let output = Command::new("bash")
            .arg(&self.path)
            .arg(&urdf)
            .arg(self.calls.to_string())
            .output()
            .map_err(|e| failure(format!("cannot run {}: {e}", self.path.display())))?;
        if !output.status.success() {
            return Err(failure(format!(
                "{} exited with {}: {}",
                self.path.display(),
                output.status,
                String::from_utf8_lossy(&output.stderr).trim()
            )));
        }
        parse(&String::from_utf8_lossy(&output.stdout)).map_err(failure)
    }
}

/// The figures of one run of the script: `rnea_ns`, `crba_ns`, `nle_ns`, `aba_ns`.
pub fn parse(output: &str) -> Result<[f64; 4], String> {
    let figure = |key: &str| -> Result<f64, String> {
        output
            .lines()
            .filter_map(|line| line.split_once(' '))
            .find(|(name, _)| *name == key)
            .ok_or_else(|| format!("no `{key}` line in the script's output"))
            .and_then(|(_, value)| {
                value
                    .trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite() && *v > 0.0)
                    .ok_or_else(|| format!("`{key}` is not a positive number: {value:?}"))
            })
    };
    Ok([
        figure("rnea_ns")?,
        figure("crba_ns")?,
        figure("nle_ns")?,
        figure("aba_ns")?,
    ])
}

/// The median of each figure over several runs.
pub fn median_of(runs: &[[f64; 4]]) -> [f64; 4] {
    std::array::from_fn(|i| quantile(&runs.iter().map(|r| r[i]).collect::<Vec<_>>(), 0.5))
}

/// Pinocchio's time over the generated `f64` kernel's, per algorithm of [`ALGORITHMS`]: how
/// many times faster the generated kernel is.
pub fn speedups(pinocchio: &PinocchioTimes, robot: &RobotKernels) -> [f64; 4] {
    std::array::from_fn(|i| {
        let kernel = ALGORITHMS[i].1;
        robot
            .rows
            .iter()
            .find(|r| r.kernel == kernel && r.implementation == Implementation::Generated)
            .map_or(f64::NAN, |r| pinocchio.ns[i] / r.timing.median())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The script's output is read by name, in any order; missing or bad figures are errors
    /// naming the figure.
    #[test]
    fn parses_the_scripts_output() {
        let output = "nv 6\nrnea_ns 990.5\ncrba_ns 393\naba_ns 1801\nnle_ns 800\ngravity_ns 500\n";
        assert_eq!(parse(output), Ok([990.5, 393.0, 800.0, 1801.0]));
        let missing = parse("rnea_ns 1\ncrba_ns 2\naba_ns 3\n").unwrap_err();
        assert!(missing.contains("nle_ns"), "{missing}");
        let bad = parse("rnea_ns x\ncrba_ns 2\naba_ns 3\nnle_ns 4\n").unwrap_err();
        assert!(bad.contains("rnea_ns"), "{bad}");
        assert_eq!(
            median_of(&[
                [1.0, 5.0, 3.0, 4.0],
                [2.0, 1.0, 9.0, 4.0],
                [3.0, 2.0, 1.0, 4.0]
            ]),
            [2.0, 2.0, 3.0, 4.0]
        );
    }
}
