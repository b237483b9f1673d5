//! The comparison with Pinocchio (issues 6, 13, 14, 15): its algorithms, its analytical
//! derivatives and its CppADCodeGen-generated code, timed by external scripts on the same URDF
//! files as the built-in robots, within the same `rne bench` run as the generated kernels, and
//! quoted as ratios.
//!
//! The scripts are the repository's peer harness, `tools/peers/` (installed by its `setup.sh`;
//! [`default_script`] finds it); `rne bench --pinocchio [PATH/run.sh]` calls
//! - `run.sh ROBOT.urdf CALLS`: `rnea_ns`, `crba_ns`, `aba_ns`, `nle_ns`;
//! - `run_cg.sh ROBOT.urdf CALLS` beside it (unless skipped): the plain
//!   `minv_ns`, `rnea_derivs_ns`, `aba_derivs_ns` and, for X in [`CODEGEN`], the generated
//!   code's `cg_X_ns` (through Pinocchio's `CodeGenX::evalFunction`), `cg_X_raw_ns` (the
//!   generated function on a pre-packed input: the floor) and `cg_X_maxdiff` (its largest
//!   difference from the plain algorithm);
//! - `run_extra.sh ROBOT.urdf CALLS` beside it (when present, or as given):
//!   `jacobians_ns`, `jacobians_all_ns`, `jdqd_ns`, `jdqd_fk_ns`, `regressor_ns`.
//!
//! Each script is run as `bash SCRIPT ROBOT.urdf CALLS` with `RNE_PIN_DUMP` set to the
//! `dump.py` beside `run.sh`, which writes the model the timing programs read.
//!
//! Each prints lines `name value`. For each robot every script runs [`RUNS`] times (`run_cg.sh`
//! in the first [`PinocchioScript::codegen_runs`] of them): before rne's kernels of that robot
//! are timed, after them, and after its scene variants. Right after each run rne's compared
//! kernels are timed again ([`crate::beside`]), and each ratio is the median over runs of the
//! run's figure over rne's time right after it, so that a change of the machine's speed
//! between runs does not favour either side. Figures are kept under the script's name:
//! `run.rnea_ns`, `cg.cg_aba_ns`, ….

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use rne_codegen::Kernel;

use super::beside::PairedTimes;
use super::error::BenchError;
use super::timing::quantile;
use rne_figures::FigureError;
use rne_models::BuiltinRobot;

/// Built-in robots compared with Pinocchio: the URDF ones.
pub const COMPARED: [&str; 3] = ["ur5", "panda-arm", "panda"];

/// Runs of the scripts per robot: before rne's kernels of the robot are timed, after them,
/// and after its scene variants.
pub const RUNS: usize = 3;

/// The functions `run_cg.sh` generates with CppADCodeGen (its `X`).
pub const CODEGEN: [&str; 6] = ["rnea", "crba", "minv", "aba", "rnea_derivs", "aba_derivs"];

/// One of Pinocchio's timing scripts.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Peer {
    /// `run.sh`: the plain algorithms.
    Plain,
    /// `run_cg.sh`: analytical derivatives, M⁻¹ and the CppADCodeGen code.
    CodeGen,
    /// `run_extra.sh`: Jacobians, J̇q̇ and the joint-torque regressor.
    Extra,
}

impl Peer {
    /// The prefix of its figures' keys.
    pub fn prefix(self) -> &'static str {
        match self {
            Peer::Plain => "run",
            Peer::CodeGen => "cg",
            Peer::Extra => "extra",
        }
    }

    /// The figures a run of the script must print.
    pub fn required(self) -> Vec<String> {
        match self {
            Peer::Plain => ["rnea_ns", "crba_ns", "aba_ns", "nle_ns"]
                .map(String::from)
                .to_vec(),
            Peer::CodeGen => ["minv_ns", "rnea_derivs_ns", "aba_derivs_ns"]
                .into_iter()
                .map(String::from)
                .chain(CODEGEN.iter().flat_map(|x| {
                    [
                        format!("cg_{x}_ns"),
                        format!("cg_{x}_raw_ns"),
                        format!("cg_{x}_maxdiff"),
                    ]
                }))
                .collect(),
            Peer::Extra => [
                "jacobians_ns",
                "jacobians_all_ns",
                "jdqd_ns",
                "jdqd_fk_ns",
                "regressor_ns",
            ]
            .map(String::from)
            .to_vec(),
        }
    }
}

/// One row of the comparison: a quantity, rne's kernel for it, and Pinocchio's figures.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Comparison {
    /// What is computed.
    pub quantity: &'static str,
    /// rne's generated kernel.
    pub kernel: Kernel,
    /// Pinocchio's plain function and the key of its ns per call.
    pub plain: (&'static str, &'static str),
    /// The `X` of the generated code in `run_cg.sh`, if Pinocchio generates this quantity.
    pub codegen: Option<&'static str>,
}

/// The quantities set beside Pinocchio, in the report's order.
pub const COMPARISONS: [Comparison; 10] = [
    Comparison {
        quantity: "ID",
        kernel: Kernel::InverseDynamics,
        plain: ("rnea", "run.rnea_ns"),
        codegen: Some("rnea"),
    },
    Comparison {
        quantity: "M",
        kernel: Kernel::MassMatrix,
        plain: ("crba", "run.crba_ns"),
        codegen: Some("crba"),
    },
    Comparison {
        quantity: "C q̇ + g",
        kernel: Kernel::BiasTorques,
        plain: ("nonLinearEffects", "run.nle_ns"),
        codegen: None,
    },
    Comparison {
        quantity: "FD",
        kernel: Kernel::ForwardDynamics,
        plain: ("aba", "run.aba_ns"),
        codegen: Some("aba"),
    },
    Comparison {
        quantity: "M⁻¹",
        kernel: Kernel::MassMatrixInverse,
        plain: ("computeMinverse", "cg.minv_ns"),
        codegen: Some("minv"),
    },
    Comparison {
        quantity: "∂ID",
        kernel: Kernel::InverseDynamicsDerivatives,
        plain: ("computeRNEADerivatives", "cg.rnea_derivs_ns"),
        codegen: Some("rnea_derivs"),
    },
    Comparison {
        quantity: "∂FD",
        kernel: Kernel::ForwardDynamicsDerivatives,
        plain: ("computeABADerivatives", "cg.aba_derivs_ns"),
        codegen: Some("aba_derivs"),
    },
    Comparison {
        quantity: "J (all frames)",
        kernel: Kernel::FrameJacobians,
        plain: (
            "computeJointJacobians + getJointJacobian per joint",
            "extra.jacobians_all_ns",
        ),
        codegen: None,
    },
    Comparison {
        quantity: "J̇ q̇ (all frames)",
        kernel: Kernel::FrameJacobianDotQd,
        plain: (
            "forwardKinematics(q, q̇, 0) + getClassicalAcceleration per joint",
            "extra.jdqd_fk_ns",
        ),
        codegen: None,
    },
    Comparison {
        quantity: "Y",
        kernel: Kernel::Regressor,
        plain: ("computeJointTorqueRegressor", "extra.regressor_ns"),
        codegen: None,
    },
];

/// Pinocchio's figures on one robot, the median over the runs of each script, keyed
/// `prefix.name` ([`Peer::prefix`]), and the runs themselves with rne's times beside them.
#[derive(Clone, Debug, PartialEq)]
pub struct PinocchioTimes {
    /// The built-in robot.
    pub robot: &'static str,
    /// Every figure the scripts printed: the median over the runs that printed it.
    pub figures: BTreeMap<String, f64>,
    /// Each run's figures and rne's kernels timed right after it, which the ratios pair.
    pub paired: PairedTimes,
    /// Calls per figure of `run.sh` and `run_extra.sh`.
    pub calls: u64,
    /// Calls per measurement of `run_cg.sh`, if it ran.
    pub codegen_calls: Option<u64>,
    /// How many runs of `run_cg.sh` its medians are over.
    pub codegen_runs: usize,
}

impl PinocchioTimes {
    /// The figure `key` (`prefix.name`), NaN if no script printed it.
    pub fn get(&self, key: &str) -> f64 {
        self.figures.get(key).copied().unwrap_or(f64::NAN)
    }

    /// The generated code's figure `cg_{x}{suffix}`, NaN without it.
    pub fn codegen(&self, x: &str, suffix: &str) -> f64 {
        self.get(&codegen_key(x, suffix))
    }
}

/// The key of the generated code's figure `cg_{x}{suffix}` of `run_cg.sh`.
pub fn codegen_key(x: &str, suffix: &str) -> String {
    format!("{}.cg_{x}{suffix}", Peer::CodeGen.prefix())
}

/// Where the peer harness's `run.sh` is, relative to the repository's root.
pub const DEFAULT_SCRIPT: &str = "tools/peers/run.sh";

/// The repository's `run.sh` ([`DEFAULT_SCRIPT`]), what `rne bench --pinocchio` runs when given
/// no path: under the root of the repository this crate was built in (found from
/// `CARGO_MANIFEST_DIR` at build time), else under the current directory (a binary copied
/// elsewhere, run from a checkout's root). When neither exists, the first, so that the error
/// of running it names where the script was expected.
pub fn default_script() -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let built_in = root.join(DEFAULT_SCRIPT);
    if let Ok(path) = built_in.canonicalize() {
        return path;
    }
    let here = PathBuf::from(DEFAULT_SCRIPT);
    if here.is_file() {
        return here;
    }
    built_in
}

/// The `run_extra.sh` beside `run_sh`, if there is one.
pub fn extra_beside(run_sh: &Path) -> Option<PathBuf> {
    Some(run_sh.with_file_name("run_extra.sh")).filter(|extra| extra.is_file())
}

/// The timing scripts and how many calls each figure averages.
#[derive(Clone, Debug, PartialEq)]
pub struct PinocchioScript {
    /// `run.sh` of the peer harness (`tools/peers/run.sh` by default, [`default_script`]).
    pub path: PathBuf,
    /// Calls per figure of `run.sh` and `run_extra.sh`.
    pub calls: u64,
    /// `run_cg.sh` and its calls per measurement, unless skipped.
    pub codegen: Option<(PathBuf, u64)>,
    /// In how many of the runs on each robot `run_cg.sh` takes part (the first ones): it
    /// generates and compiles its code every time, minutes per robot.
    pub codegen_runs: usize,
    /// `run_extra.sh` (by default the one beside `run.sh`, [`extra_beside`]), if present.
    pub extra: Option<PathBuf>,
}

impl PinocchioScript {
    /// `run.sh` at `path` with `calls` per figure, `run_cg.sh` beside it with `codegen_calls`
    /// (none: skipped) and `extra`.
    pub fn new(
        path: PathBuf,
        calls: u64,
        codegen_calls: Option<u64>,
        extra: Option<PathBuf>,
    ) -> Self {
        let codegen = codegen_calls.map(|c| (path.with_file_name("run_cg.sh"), c));
        PinocchioScript {
            path,
            calls,
            codegen,
            codegen_runs: RUNS,
            extra,
        }
    }

    /// The scripts of run `run` (counted from 0), with their calls.
    fn scripts(&self, run: usize) -> Vec<(Peer, &Path, u64)> {
        let mut scripts = vec![(Peer::Plain, self.path.as_path(), self.calls)];
        if let Some((path, calls)) = self.codegen.as_ref().filter(|_| run < self.codegen_runs) {
            scripts.push((Peer::CodeGen, path, *calls));
        }
        if let Some(path) = &self.extra {
            scripts.push((Peer::Extra, path, self.calls));
        }
        scripts
    }

    /// Runs the scripts of run `run` (of [`RUNS`], counted from 0) once on `robot`'s URDF
    /// (written to `scratch` first) and returns their figures, keyed `prefix.name`.
    pub fn run_once(
        &self,
        robot: &BuiltinRobot,
        scratch: &Path,
        run: usize,
    ) -> Result<BTreeMap<String, f64>, BenchError> {
        let failure = |problem: String| BenchError::Pinocchio {
            robot: robot.name.to_owned(),
            problem,
        };
        std::fs::create_dir_all(scratch).map_err(FigureError::io(scratch))?;
        let urdf = scratch.join(format!("{}.urdf", robot.name));
        std::fs::write(&urdf, robot.source).map_err(FigureError::io(&urdf))?;
        let mut figures = BTreeMap::new();
        for (peer, path, calls) in self.scripts(run) {
            let output = Command::new("bash")
                .arg(path)
                .arg(&urdf)
                .arg(calls.to_string())
                .env("RNE_PIN_DUMP", self.path.with_file_name("dump.py"))
                .output()
                .map_err(|e| failure(format!("cannot run {}: {e}", path.display())))?;
            if !output.status.success() {
                return Err(failure(format!(
                    "{} exited with {}: {}",
                    path.display(),
                    output.status,
                    String::from_utf8_lossy(&output.stderr).trim()
                )));
            }
            let parsed = parse(&String::from_utf8_lossy(&output.stdout), peer)
                .map_err(|problem| failure(format!("{}: {problem}", path.display())))?;
            figures.extend(
                parsed
                    .into_iter()
                    .map(|(name, value)| (format!("{}.{name}", peer.prefix()), value)),
            );
        }
        Ok(figures)
    }

    /// The runs on `robot`, with rne's times beside them, and the medians of their figures.
    pub fn times(&self, robot: &'static str, paired: PairedTimes) -> PinocchioTimes {
        let runs = paired.runs();
        PinocchioTimes {
            robot,
            figures: median_of(&paired.peer),
            paired,
            calls: self.calls,
            codegen_calls: self.codegen.as_ref().map(|(_, calls)| *calls),
            codegen_runs: self.codegen_runs.min(runs),
        }
    }
}

/// The figures of one run of `peer`'s script: every `name value …` line whose first word
/// after the name is a number; an error names a figure of [`Peer::required`] that is missing or not a positive
/// number (differences, `_maxdiff`, may be 0).
pub fn parse(output: &str, peer: Peer) -> Result<BTreeMap<String, f64>, String> {
    let figures: BTreeMap<String, f64> = output
        .lines()
        .filter_map(|line| line.trim().split_once(' '))
        .filter_map(|(name, rest)| {
            let value = rest.split_whitespace().next()?.parse::<f64>().ok()?;
            Some((name.to_owned(), value))
        })
        .collect();
    for key in peer.required() {
        let value = figures.get(&key).copied();
        let valid = match value {
            None => return Err(format!("no `{key}` line in the script's output")),
            Some(v) if key.ends_with("_maxdiff") => v.is_finite() && v >= 0.0,
            Some(v) => v.is_finite() && v > 0.0,
        };
        if !valid {
            return Err(format!("`{key}` is not a positive number: {value:?}"));
        }
    }
    Ok(figures)
}

/// The median of each figure over the runs that printed it.
pub fn median_of(runs: &[BTreeMap<String, f64>]) -> BTreeMap<String, f64> {
    let mut values: BTreeMap<&str, Vec<f64>> = BTreeMap::new();
    for run in runs {
        for (key, &value) in run {
            values.entry(key).or_default().push(value);
        }
    }
    values
        .into_iter()
        .map(|(key, v)| (key.to_owned(), quantile(&v, 0.5)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A recorded output of each script (`fixtures/pinocchio/`).
    const PLAIN: &str = include_str!("../fixtures/pinocchio/run-ur5.txt");
    const CODEGEN_OUTPUT: &str = include_str!("../fixtures/pinocchio/run_cg-ur5.txt");
    const EXTRA: &str = include_str!("../fixtures/pinocchio/run_extra-ur5.txt");

    /// Every script's recorded output parses with all its required figures, which the
    /// comparison table reads.
    #[test]
    fn recorded_outputs_parse() {
        for (output, peer) in [
            (PLAIN, Peer::Plain),
            (CODEGEN_OUTPUT, Peer::CodeGen),
            (EXTRA, Peer::Extra),
        ] {
            let figures = parse(output, peer).expect("the recorded output parses");
            for key in peer.required() {
                assert!(figures.contains_key(&key), "{peer:?}: {key}");
            }
        }
        let plain = parse(PLAIN, Peer::Plain).unwrap();
        assert_eq!(plain["nv"], 6.0);
        let codegen = parse(CODEGEN_OUTPUT, Peer::CodeGen).unwrap();
        assert!(codegen["cg_aba_derivs_raw_ns"] <= codegen["cg_aba_derivs_ns"]);
    }

    /// Figures are read by name, in any order; missing or bad figures are errors naming the
    /// figure; a difference may be 0, a time may not.
    #[test]
    fn missing_or_bad_figures_are_named() {
        let output = "nv 6\nrnea_ns 990.5\ncrba_ns 393\naba_ns 1801\nnle_ns 800\ngravity_ns 500\n";
        let figures = parse(output, Peer::Plain).unwrap();
        assert_eq!(figures["rnea_ns"], 990.5);
        assert_eq!(figures["nle_ns"], 800.0);
        let missing = parse("rnea_ns 1\ncrba_ns 2\naba_ns 3\n", Peer::Plain).unwrap_err();
        assert!(missing.contains("nle_ns"), "{missing}");
        let bad = parse("rnea_ns x\ncrba_ns 2\naba_ns 3\nnle_ns 4\n", Peer::Plain).unwrap_err();
        assert!(bad.contains("rnea_ns"), "{bad}");
        let zero = CODEGEN_OUTPUT.replace("cg_rnea_ns ", "cg_rnea_ns 0 #");
        assert!(parse(&zero, Peer::CodeGen)
            .unwrap_err()
            .contains("cg_rnea_ns"));
        let exact = CODEGEN_OUTPUT.replace("cg_rnea_maxdiff ", "cg_rnea_maxdiff 0 #");
        assert_eq!(
            parse(&exact, Peer::CodeGen).unwrap()["cg_rnea_maxdiff"],
            0.0
        );
    }

    /// Each figure's median is over the runs that have it.
    #[test]
    fn medians_per_figure() {
        let run = |pairs: &[(&str, f64)]| -> BTreeMap<String, f64> {
            pairs.iter().map(|&(k, v)| (k.to_owned(), v)).collect()
        };
        let medians = median_of(&[
            run(&[("a", 1.0), ("b", 5.0)]),
            run(&[("a", 2.0), ("b", 1.0), ("c", 7.0)]),
            run(&[("a", 3.0), ("b", 2.0)]),
        ]);
        assert_eq!(medians, run(&[("a", 2.0), ("b", 2.0), ("c", 7.0)]));
    }

    /// Without a path, `rne bench --pinocchio` runs the repository's own harness: the default
    /// resolves to `tools/peers/run.sh` of this checkout, which exists, with `run_cg.sh`,
    /// `run_extra.sh` and `dump.py` beside it.
    #[test]
    fn the_default_script_is_the_repositorys_peer_harness() {
        let script = default_script();
        assert!(script.is_file(), "{}", script.display());
        assert!(script.ends_with(DEFAULT_SCRIPT), "{}", script.display());
        let root = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .canonicalize()
            .unwrap();
        assert_eq!(script, root.join(DEFAULT_SCRIPT));
        for beside in ["run_cg.sh", "run_extra.sh", "dump.py", "setup.sh"] {
            assert!(script.with_file_name(beside).is_file(), "{beside}");
        }
        assert_eq!(
            extra_beside(&script),
            Some(script.with_file_name("run_extra.sh"))
        );
        let script = PinocchioScript::new(script.clone(), 10, Some(5), extra_beside(&script));
        assert_eq!(
            script.codegen.as_ref().map(|(path, _)| path.clone()),
            Some(script.path.with_file_name("run_cg.sh"))
        );
    }

    /// No `run_extra.sh` beside a script elsewhere: the figures it would give are left out.
    #[test]
    fn no_extra_script_beside_a_script_without_one() {
        assert_eq!(extra_beside(Path::new("/nonexistent/run.sh")), None);
    }

    /// Every comparison's plain figure and generated code are ones the scripts print.
    #[test]
    fn comparisons_name_printed_figures() {
        let printed: Vec<String> = [Peer::Plain, Peer::CodeGen, Peer::Extra]
            .into_iter()
            .flat_map(|p| {
                p.required()
                    .into_iter()
                    .map(move |k| format!("{}.{k}", p.prefix()))
            })
            .collect();
        for c in COMPARISONS {
            assert!(printed.contains(&c.plain.1.to_owned()), "{}", c.plain.1);
            if let Some(x) = c.codegen {
                assert!(CODEGEN.contains(&x), "{x}");
            }
        }
    }
}
