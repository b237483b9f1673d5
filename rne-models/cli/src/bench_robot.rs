//! `rne bench MODEL [--engines ..] [--kernels ..] [--pinocchio [RUN_SH]] [--json]`: one
//! robot chosen at run time, kernel by kernel: ns per call on the JIT, the interpreter and
//! (built-in robots) the compiled modules, timed together; each engine's largest error against
//! the numeric reference; the time to obtain the kernels on rne's side (generation and JIT)
//! and, with `--pinocchio`, Pinocchio's and its CppADCodeGen code's times and the seconds
//! CppADCodeGen takes to generate and compile.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::ValueEnum;
use rne_bench::pinocchio::default_script;
use rne_bench::robot::{
    bench_robot, Engine, PeerScripts, RobotBench, RobotBenchSettings, DEFAULT_KERNELS,
};
use rne_bench::Effort;
use rne_codegen::Kernel;
use rne_codegen_core::GenerationOptions;
use rne_jit::Tier;
use rne_models::builtin::RobotSource;
use serde_json::json;

use super::bench::BenchArgs;
use super::CliError;

/// An engine of rne that `rne bench MODEL` can time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BenchEngine {
    /// The programs compiled in memory (Cranelift).
    Jit,
    /// The built-in robot's compiled module.
    Compiled,
    /// The programs evaluated operation by operation.
    Interpreted,
}

impl BenchEngine {
    fn engine(self) -> Engine {
        match self {
            BenchEngine::Jit => Engine::Jit,
            BenchEngine::Compiled => Engine::Compiled,
            BenchEngine::Interpreted => Engine::Interpreted,
        }
    }
}

/// The JIT's tier (`--jit-tier`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum JitTier {
    /// Backtracking register allocation: the faster code.
    Optimized,
    /// Single-pass register allocation: the faster compilation.
    Fast,
}

/// Runs `rne bench MODEL` and prints its table or JSON.
pub fn run(model: &str, args: &BenchArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let source = RobotSource::resolve(model);
    let robot = args.options.load(&source, false)?;
    let mut options = GenerationOptions {
        outputs: Kernel::ALL.to_vec(),
        fma: args.fma,
        ..GenerationOptions::default()
    };
    if let Err(e) = robot.check_mass_matrix_invertible() {
        eprintln!(
            "warning: {}: {e}; the kernels that solve with M are left out",
            source.display_name()
        );
        options.outputs.retain(|k| !k.inverts_mass_matrix());
    }
    let effort = if args.quick {
        Effort::Quick
    } else {
        Effort::Full
    };
    let settings = RobotBenchSettings {
        engines: args.engines.iter().map(|e| e.engine()).collect(),
        kernels: kernels(&args.kernels)?,
        scene: args.options.scene(),
        options,
        states: effort.pool(),
        plan: effort.kernel_plan(),
        tier: match args.jit_tier {
            JitTier::Optimized => Tier::Optimized,
            JitTier::Fast => Tier::Fast,
        },
        builtin: match source {
            RobotSource::Builtin(robot) if args.options.keeps_the_file_model() => Some(robot),
            _ => None,
        },
        peers: peers(&source, args)?,
    };
    let name = source.display_name();
    let quiet = args.quiet || args.json;
    let mut progress = |step: &str| {
        if !quiet {
            eprintln!("{name}: {step}");
        }
    };
    let report = bench_robot(&robot, &name, &settings, &mut progress)?;
    if args.json {
        writeln!(
            out,
            "{}",
            serde_json::to_string_pretty(&to_json(&report)).expect("JSON")
        )?;
    } else {
        write!(out, "{}", table(&report))?;
    }
    Ok(())
}

/// The kernels named by `--kernels` (`all`, or names), default [`DEFAULT_KERNELS`].
fn kernels(names: &[String]) -> Result<Vec<Kernel>, CliError> {
    match names {
        [] => Ok(DEFAULT_KERNELS.to_vec()),
        [all] if all == "all" => Ok(Kernel::ALL.to_vec()),
        names => names
            .iter()
            .map(|name| {
                name.parse::<Kernel>()
                    .map_err(|cause| CliError::UnknownKernel {
                        what: "kernel (--kernels)",
                        name: name.clone(),
                        cause,
                    })
            })
            .collect(),
    }
}

/// The peer scripts of `--pinocchio`, on the robot's URDF (a built-in robot's written to a
/// scratch file): Pinocchio reads URDF, on the file's own base.
fn peers(source: &RobotSource, args: &BenchArgs) -> Result<Option<PeerScripts>, CliError> {
    let Some(script) = &args.pinocchio else {
        return Ok(None);
    };
    let urdf = match source {
        RobotSource::File(path) if is_urdf(path) => path.clone(),
        RobotSource::Builtin(robot) if robot.file.ends_with(".urdf") => {
            let path = std::env::temp_dir().join(format!("rne-bench-{}.urdf", robot.name));
            std::fs::write(&path, robot.source).map_err(|cause| CliError::Write {
                path: path.clone(),
                cause,
            })?;
            path
        }
        _ => {
            return Err(CliError::Argument(format!(
                "--pinocchio needs a URDF robot; {} is not one",
                source.display_name()
            )))
        }
    };
    if !args.options.keeps_the_file_model() {
        return Err(CliError::Argument(
            "--pinocchio times the robot as its URDF describes it: leave out --floating-base \
             and --mimic free"
                .into(),
        ));
    }
    let run_sh = script.clone().unwrap_or_else(default_script);
    let run_cg_sh: PathBuf = run_sh.with_file_name("run_cg.sh");
    Ok(Some(PeerScripts {
        run_cg_sh: (!args.no_codegen && run_cg_sh.is_file()).then_some(run_cg_sh),
        run_sh,
        urdf,
        calls: args.codegen_calls,
    }))
}

fn is_urdf(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("urdf"))
}

/// The report as JSON: `{"robot", "time_to_kernels_s": {..}, "kernels": [..]}`.
fn to_json(report: &RobotBench) -> serde_json::Value {
    let t = &report.time_to_kernels;
    json!({
        "robot": report.robot,
        "nq": report.nq,
        "nv": report.nv,
        "fma": report.fused,
        "jit_tier": format!("{:?}", report.tier).to_lowercase(),
        "time_to_kernels_s": {
            "rne_jit": t.rne_jit_s,
            "rne_generation": t.generation_s,
            "rne_compile": t.compile_s,
            "rne_kernels": t.rne_kernels,
            "cppadcodegen": t.cppadcodegen_s,
        },
        "peak_memory_bytes": t.peak_memory_bytes,
        "kernels": report.kernels.iter().map(|k| json!({
            "kernel": k.kernel.to_string(),
            "engine": k.engine.label(),
            "ns": k.ns,
            "ns_quartiles": k.quartiles.map(|(a, b)| [a, b]),
            "max_rel_error": k.max_rel_error,
        })).collect::<Vec<_>>(),
    })
}

/// The report as a text table, each engine's time also as a multiple of the JIT's.
fn table(report: &RobotBench) -> String {
    let t = &report.time_to_kernels;
    let mut s = format!(
        "robot: {} (nq {}, nv {}), JIT tier {:?}, multiply-adds {}\n",
        report.robot,
        report.nq,
        report.nv,
        report.tier,
        if report.fused { "fused" } else { "not fused" }
    );
    s += &format!(
        "time to kernels: rne {:.3} s for {} kernels (generation {:.3} s, JIT {:.3} s)",
        t.rne_jit_s, t.rne_kernels, t.generation_s, t.compile_s
    );
    if let Some(bytes) = t.peak_memory_bytes {
        s += &format!(", peak memory {} MB", bytes / (1 << 20));
    }
    if let Some(cg) = t.cppadcodegen_s {
        s += &format!("; Pinocchio + CppADCodeGen {cg:.1} s for its 6 functions");
    }
    s += "\n\n";
    s += &format!(
        "{:<30} {:<24} {:>10} {:>21} {:>8} {:>14}\n",
        "kernel", "engine", "ns", "ns IQR", "× jit", "max rel. error"
    );
    for k in &report.kernels {
        let jit = report
            .kernels
            .iter()
            .find(|j| j.kernel == k.kernel && j.engine == Engine::Jit)
            .map(|j| j.ns);
        let iqr = k
            .quartiles
            .map_or(String::new(), |(a, b)| format!("{a:.1}–{b:.1}"));
        let ratio = jit.map_or(String::new(), |j| format!("{:.2}", k.ns / j));
        let error = k
            .max_rel_error
            .map_or(String::new(), |e| format!("{e:.1e}"));
        s += &format!(
            "{:<30} {:<24} {:>10.1} {:>21} {:>8} {:>14}\n",
            k.kernel.to_string(),
            k.engine.label(),
            k.ns,
            iqr,
            ratio,
            error
        );
    }
    s
}
