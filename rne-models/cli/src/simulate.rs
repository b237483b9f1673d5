//! `rne simulate SCENARIO [--out DIR]`: the thesis's chapter 6 experiments and user scenario
//! files, written as CSV tables and SVG/PNG figures with a report of what was measured.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};

use super::CliError;
use rne_scenarios::{
    FileEngine, Format, Outcome, RunOptions, ScenarioError, UserScenario, SCENARIOS,
};

/// A kind of output file.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum OutputFormat {
    /// CSV tables of the runs: t, q, qd, u, energies (and V for PD runs).
    Csv,
    /// Figures as SVG.
    Svg,
    /// Figures as PNG.
    Png,
    /// The findings as Markdown.
    Md,
}

/// Arguments of `rne simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// A built-in scenario (see --list), `all` for every one, or a .toml scenario file.
    #[arg(required_unless_present = "list")]
    pub scenario: Option<String>,
    /// Directory for the CSV tables, figures and findings (created if missing).
    #[arg(long, default_value = "rne-simulate")]
    pub out: PathBuf,
    /// What to write, comma-separated.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "csv,svg,png,md"
    )]
    pub formats: Vec<OutputFormat>,
    /// List the built-in scenarios with the thesis's figures they reproduce.
    #[arg(long)]
    pub list: bool,
    /// Time the thesis's 70 s run instead of writing output (double-pendulum only; use a
    /// release build).
    #[arg(long)]
    pub time: bool,
    /// Runs to time with --time.
    #[arg(long, default_value_t = 20)]
    pub repeat: usize,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// What computes a scenario file's robot when it is read from a file (built-in robots run
    /// their compiled modules).
    #[arg(long, value_enum, default_value = "jit")]
    pub engine: SimulateEngine,
}

/// The engines of `rne simulate` for a robot read from a file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SimulateEngine {
    /// The kernels compiled in memory (the interpreter, with a warning, where the processor
    /// is not supported).
    Jit,
    /// The programs evaluated operation by operation.
    #[value(alias = "symbolic")]
    Interpreted,
}

/// Runs the scenario(s) and reports what was written and measured.
pub fn run(args: &SimulateArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if args.list {
        for s in SCENARIOS {
            writeln!(out, "{:<24} {:<12} {}", s.name, s.figures, s.description)?;
        }
        return Ok(());
    }
    let Some(name) = args.scenario.as_deref() else {
        return Err(CliError::Argument("name a scenario, or pass --list".into()));
    };
    if args.time {
        return time(name, args.repeat, out);
    }
    let options = RunOptions {
        progress: !args.quiet,
        engine: match args.engine {
            SimulateEngine::Jit => FileEngine::Jit,
            SimulateEngine::Interpreted => FileEngine::Interpreted,
        },
    };
    let outcomes: Vec<Outcome> = if name == "all" {
        SCENARIOS
            .iter()
            .map(|s| s.run(&options))
            .collect::<Result<_, _>>()?
    } else if let Some(scenario) = rne_scenarios::find(name) {
        vec![scenario.run(&options)?]
    } else if Path::new(name).extension().is_some_and(|e| e == "toml") {
        vec![UserScenario::load(Path::new(name)).and_then(|s| s.run(&options))?]
    } else {
        return Err(ScenarioError::Unknown(name.to_owned()).into());
    };
    let formats: Vec<Format> = args
        .formats
        .iter()
        .map(|f| match f {
            OutputFormat::Csv => Format::Csv,
            OutputFormat::Svg => Format::Svg,
            OutputFormat::Png => Format::Png,
            OutputFormat::Md => Format::Md,
        })
        .collect();
    for outcome in &outcomes {
        let written = outcome.write(&args.out, &formats)?;
        writeln!(out, "## {}\n", outcome.scenario)?;
        write!(out, "{}", outcome.findings_table())?;
        writeln!(
            out,
            "\nwrote {} files to {}",
            written.len(),
            args.out.display()
        )?;
        for path in written {
            writeln!(out, "  {}", path.display())?;
        }
        writeln!(out)?;
    }
    Ok(())
}

/// `--time`: the thesis's 70 s double-pendulum run, timed.
fn time(name: &str, repeat: usize, out: &mut dyn Write) -> Result<(), CliError> {
    if name != "double-pendulum" {
        return Err(CliError::Argument(
            "--time measures the thesis's 70 s run: use it with `double-pendulum`".into(),
        ));
    }
    if repeat == 0 {
        return Err(CliError::Argument("--repeat must be at least 1".into()));
    }
    let timing = rne_scenarios::time_thesis_release(repeat)
        .map_err(rne_sim::SimError::in_run("double-pendulum"))
        .map_err(ScenarioError::from)?;
    writeln!(
        out,
        "70 s double-pendulum release, Dormand-Prince rtol 1e-10, generated kernels, {} samples recorded:",
        timing.samples
    )?;
    writeln!(
        out,
        "  {} steps, {} rejected, {} evaluations of (6.2)",
        timing.stats.steps, timing.stats.rejected, timing.stats.evaluations
    )?;
    writeln!(
        out,
        "  best {:.2} ms, median {:.2} ms over {} runs{}",
        timing.best.as_secs_f64() * 1e3,
        timing.median.as_secs_f64() * 1e3,
        timing.runs,
        if cfg!(debug_assertions) {
            " (debug build: use --release for the real figure)"
        } else {
            ""
        }
    )?;
    Ok(())
}
