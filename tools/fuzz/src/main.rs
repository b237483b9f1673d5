//! `rne-fuzz`: fuzzes rne's robot readers and generator for a time or a number of inputs and
//! prints, per target, the inputs tried, loaded and rejected, the failures and the time.
//!
//! ```text
//! cargo run --release -p rne-fuzz -- --target urdf --seconds 600 --seed 1
//! cargo run --release -p rne-fuzz -- --target toml --replay 1234 --seed 1
//! ```

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::Parser;
use rne_fuzz::{
    input, repository_root, run, Config, Corpus, Target, DEFAULT_BUDGET, DEFAULT_LONGEST_CHAIN,
};

/// Fuzzes rne's robot readers (urdf, toml) and its generator (generate).
#[derive(Parser, Debug)]
#[command(name = "rne-fuzz")]
struct Args {
    /// Targets to run, one after the other: urdf, toml, generate (default: all three).
    #[arg(long = "target", value_parser = parse_target)]
    targets: Vec<Target>,
    /// Seconds each target runs.
    #[arg(long)]
    seconds: Option<f64>,
    /// Inputs each target tries (default 1000 when --seconds is not given).
    #[arg(long)]
    iterations: Option<u64>,
    /// The seed every input's generator derives from.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// The first iteration.
    #[arg(long, default_value_t = 0)]
    first: u64,
    /// Seconds an input may take before it is a hang.
    #[arg(long, default_value_t = DEFAULT_BUDGET.as_secs_f64())]
    budget: f64,
    /// The longest chain of copied joints or links a mutation builds (100, 1000 or 3000).
    #[arg(long, default_value_t = DEFAULT_LONGEST_CHAIN)]
    longest_chain: usize,
    /// The repository whose fixtures seed the mutations (default: the one this was built in).
    #[arg(long)]
    root: Option<PathBuf>,
    /// Also print samples of the errors inputs got.
    #[arg(long)]
    verbose: bool,
    /// Print input ITERATION of the (single) target instead of fuzzing: its mutations and text.
    #[arg(long)]
    replay: Option<u64>,
}

fn parse_target(name: &str) -> Result<Target, String> {
    Target::from_name(name).ok_or_else(|| format!("unknown target '{name}' (urdf, toml, generate)"))
}

fn main() -> ExitCode {
    let args = Args::parse();
    let targets = if args.targets.is_empty() {
        Target::ALL.to_vec()
    } else {
        args.targets.clone()
    };
    let config = Config {
        seed: args.seed,
        seconds: args.seconds,
        iterations: args.iterations.or(args.seconds.is_none().then_some(1000)),
        first: args.first,
        budget: Duration::from_secs_f64(args.budget),
        root: args.root.clone().unwrap_or_else(repository_root),
        longest_chain: args.longest_chain,
    };
    if let Some(iteration) = args.replay {
        return replay(&targets, &config, iteration);
    }
    let mut failed = false;
    for target in targets {
        match fuzz(target, &config, args.verbose) {
            Ok(found) => failed |= found,
            Err(e) => {
                eprintln!(
                    "rne-fuzz: cannot read the seed files under {}: {e}",
                    config.root.display()
                );
                return ExitCode::FAILURE;
            }
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// Runs one target, printing progress every 10 s to stderr and the report to stdout; whether
/// it found failures.
fn fuzz(target: Target, config: &Config, verbose: bool) -> std::io::Result<bool> {
    let mut last = Instant::now();
    let report = run(target, config, &mut |report| {
        if last.elapsed() >= Duration::from_secs(10) {
            last = Instant::now();
            eprintln!(
                "{}: {} inputs, {} failures, {:.0} s",
                target.name(),
                report.inputs,
                report.failure_count,
                report.elapsed.as_secs_f64()
            );
        }
    })?;
    println!("{report}");
    if verbose {
        for sample in &report.samples {
            println!("  {sample}");
        }
    }
    Ok(report.failure_count > 0)
}

fn replay(targets: &[Target], config: &Config, iteration: u64) -> ExitCode {
    let [target] = targets else {
        eprintln!("rne-fuzz: --replay needs exactly one --target");
        return ExitCode::FAILURE;
    };
    let corpus = match Corpus::load(&config.root) {
        Ok(corpus) => corpus,
        Err(e) => {
            eprintln!("rne-fuzz: cannot read the seed files: {e}");
            return ExitCode::FAILURE;
        }
    };
    let input = input(*target, &corpus, config, iteration);
    eprintln!(
        "{}\nfile {}, {:?}, {:?}",
        input.describe(),
        input.file,
        input.format,
        input.options
    );
    if let Some(scene) = &input.scene {
        eprintln!("{scene:?}");
    }
    use std::io::Write;
    let _ = std::io::stdout().write_all(&input.bytes);
    ExitCode::SUCCESS
}
