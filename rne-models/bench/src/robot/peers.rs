//! Pinocchio and Pinocchio + CppADCodeGen on the same robot, through the repository's peer
//! scripts (`tools/peers/run.sh` and `run_cg.sh`): their ns per call under the names of rne's
//! kernels, and the seconds CppADCodeGen takes to tape, write and compile its six functions.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::Command;

use rne_codegen::Kernel;

use super::{Engine, KernelTiming};
use crate::error::BenchError;
use crate::pinocchio::{parse, Peer, CODEGEN};

/// The peer scripts to run on one URDF.
#[derive(Clone, Debug)]
pub struct PeerScripts {
    /// `run.sh`: plain Pinocchio.
    pub run_sh: PathBuf,
    /// `run_cg.sh`, when CppADCodeGen is timed too.
    pub run_cg_sh: Option<PathBuf>,
    /// The robot's URDF (Pinocchio reads URDF only).
    pub urdf: PathBuf,
    /// Calls per measurement.
    pub calls: u64,
}

/// The figures the scripts printed, by name (`run.rnea_ns`, `cg.cg_aba_cc_s`, ...).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PeerFigures {
    /// Every figure.
    pub figures: BTreeMap<String, f64>,
}

/// Pinocchio's name of each kernel it times (plain `run.sh`, or `run_cg.sh`), and the name
/// of its CppADCodeGen function.
const NAMES: [(Kernel, Peer, &str, Option<&str>); 8] = [
    (Kernel::InverseDynamics, Peer::Plain, "rnea", Some("rnea")),
    (Kernel::MassMatrix, Peer::Plain, "crba", Some("crba")),
    (Kernel::BiasTorques, Peer::Plain, "nle", None),
    (Kernel::GravityTorques, Peer::Plain, "gravity", None),
    (Kernel::ForwardDynamics, Peer::Plain, "aba", Some("aba")),
    (
        Kernel::MassMatrixInverse,
        Peer::CodeGen,
        "minv",
        Some("minv"),
    ),
    (
        Kernel::InverseDynamicsDerivatives,
        Peer::CodeGen,
        "rnea_derivs",
        Some("rnea_derivs"),
    ),
    (
        Kernel::ForwardDynamicsDerivatives,
        Peer::CodeGen,
        "aba_derivs",
        Some("aba_derivs"),
    ),
];

impl PeerScripts {
    /// Runs the scripts; an error names the robot `source` and what failed.
    pub fn run(&self, source: &str) -> Result<PeerFigures, BenchError> {
        let failure = |problem: String| BenchError::Pinocchio {
            robot: source.to_owned(),
            problem,
        };
        let mut figures = BTreeMap::new();
        let scripts = [
            (Peer::Plain, Some(&self.run_sh)),
            (Peer::CodeGen, self.run_cg_sh.as_ref()),
        ];
        for (peer, script) in scripts {
            let Some(script) = script else { continue };
            let output = Command::new("bash")
                .arg(script)
                .arg(&self.urdf)
                .arg(self.calls.to_string())
                .output()
                .map_err(|e| failure(format!("cannot run {}: {e}", script.display())))?;
            if !output.status.success() {
                return Err(failure(format!(
                    "{} exited with {}: {}",
                    script.display(),
                    output.status,
                    String::from_utf8_lossy(&output.stderr).trim()
                )));
            }
            let parsed = parse(&String::from_utf8_lossy(&output.stdout), peer)
                .map_err(|problem| failure(format!("{}: {problem}", script.display())))?;
            figures.extend(
                parsed
                    .into_iter()
                    .map(|(k, v)| (format!("{}.{k}", peer.prefix()), v)),
            );
        }
        Ok(PeerFigures { figures })
    }
}

impl PeerFigures {
    /// Seconds CppADCodeGen took to obtain its six functions (taping, C source, gcc), when
    /// `run_cg.sh` ran.
    pub fn cppadcodegen_s(&self) -> Option<f64> {
        CODEGEN
            .iter()
            .flat_map(|x| ["tape", "src", "cc"].map(|step| format!("cg.cg_{x}_{step}_s")))
            .map(|key| self.figures.get(&key).copied())
            .sum()
    }

    /// The peers' ns per call of `kernels`, under rne's kernel names.
    pub fn timings(&self, kernels: &[Kernel]) -> Vec<KernelTiming> {
        let mut timings = Vec::new();
        for (kernel, peer, name, generated) in NAMES {
            if !kernels.contains(&kernel) {
                continue;
            }
            let plain = self.figures.get(&format!("{}.{name}_ns", peer.prefix()));
            let generated = generated.and_then(|x| self.figures.get(&format!("cg.cg_{x}_ns")));
            let engines = [
                (Engine::Pinocchio, plain),
                (Engine::CppAdCodeGen, generated),
            ];
            for (engine, ns) in engines {
                if let Some(&ns) = ns {
                    timings.push(KernelTiming {
                        kernel,
                        engine,
                        ns,
                        quartiles: None,
                        max_rel_error: None,
                    });
                }
            }
        }
        timings
    }
}
