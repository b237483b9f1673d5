//! `rne corpus VALUES.json --robots DIR`: every URDF Pinocchio's values were computed for
//! (`tools/peers/pinocchio_values.py`), loaded by rne and compared with Pinocchio on a fixed
//! and a floating base; prints one line per robot and writes the table of `docs/robots.md`.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;

use super::CliError;
use rne_corpus::{
    check_robot, markdown_table, replace_table, summary, CaseReport, KernelSummary, PinocchioValues,
};

/// Arguments of `rne corpus`.
#[derive(Debug, Args)]
pub struct CorpusArgs {
    /// The JSON written by `tools/peers/pinocchio_values.py`.
    pub values: PathBuf,
    /// The directory the script read (the files' paths are relative to it).
    #[arg(long)]
    pub robots: PathBuf,
    /// A markdown file whose generated table (between the `rne corpus` markers) is replaced,
    /// or which gets one appended.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Largest relative error accepted; the command fails above it (or when rne refuses a file
    /// Pinocchio loads), after writing the table.
    #[arg(long, default_value_t = 1e-10)]
    pub tolerance: f64,
}

/// Compares every robot and writes the report.
pub fn run(args: &CorpusArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let text = std::fs::read_to_string(&args.values).map_err(|cause| CliError::Read {
        path: args.values.clone(),
        cause,
    })?;
    let values: PinocchioValues =
        serde_json::from_str(&text).map_err(|cause| CliError::PinocchioValues {
            path: args.values.clone(),
            cause,
        })?;
    let mut reports = Vec::new();
    let mut failures = Vec::new();
    for robot in &values.robots {
        let report = check_robot(&args.robots, robot);
        for (base, case) in [("fixed", &report.fixed), ("floating", &report.floating)] {
            let line = match case {
                CaseReport::Compared(c) => {
                    let (symbolic, what) = c.symbolic.max();
                    let (numeric, _) = c.numeric.max();
                    if symbolic.max(numeric) > args.tolerance || symbolic.is_nan() {
                        failures.push(format!("{} ({base})", report.file));
                    }
                    let KernelSummary { worst, failed } = summary(&c.kernels);
                    for (kernel, why) in &failed {
                        failures.push(format!("{} ({base}) {kernel}: {why}", report.file));
                    }
                    let every = match worst {
                        Some((error, kernel)) => {
                            if error > args.tolerance {
                                failures.push(format!("{} ({base}) {kernel}", report.file));
                            }
                            format!("every kernel {error:.1e} ({kernel})")
                        }
                        None => String::new(),
                    };
                    format!(
                        "NV {:3}  gen {:8.1} ms  max error {symbolic:.1e} ({what}) / {numeric:.1e}  {every}",
                        c.nv,
                        c.generation.as_secs_f64() * 1e3
                    )
                }
                CaseReport::PinocchioRefuses(_) => "Pinocchio refuses".to_owned(),
                CaseReport::RneRefuses(e) => {
                    failures.push(format!("{} ({base})", report.file));
                    format!("rne refuses: {e}")
                }
                CaseReport::NothingMoves => "nothing moves".to_owned(),
            };
            writeln!(out, "{:<64} {base:<8} {line}", report.file)?;
        }
        reports.push(report);
    }
    if let Some(path) = &args.out {
        let table = markdown_table(&values, &reports, args.tolerance);
        let document = std::fs::read_to_string(path).unwrap_or_default();
        std::fs::write(path, replace_table(&document, &table)).map_err(|cause| {
            CliError::Write {
                path: path.clone(),
                cause,
            }
        })?;
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(CliError::CorpusDisagreement {
            tolerance: args.tolerance,
            failures,
        })
    }
}
