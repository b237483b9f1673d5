//! `rne identify MODEL DATA.csv`: base parameters by weighted least squares from measured
//! q, q̇, q̈, τ; `rne identify MODEL --excite OUT.csv`: an optimised excitation trajectory with
//! simulated torques, to identify from (the `rne-identify` crate does the work).

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use rne_identify::{
    candidates, design_with_progress, fit, identify, predict, simulate, torque_figure, BaseSet,
    Design, Estimate, Fit, Limits, Measurements, Regressors, Simulation,
};
use rne_jit::JitError;
use rne_reference::Reference;
use rne_symbolic::RobotModel;
use serde_json::json;

use super::identify_engine::{add_joint_parameters, IdentifyEngine, JitRegressors};

use super::model::ModelOptions;
use super::options::parse_list;
use super::CliError;
use rne_models::RobotSource;

/// Arguments of `rne identify`.
#[derive(Debug, Args)]
#[command(after_help = "\
DATA is a CSV file whose first line names the columns q1..qN, qd1..qdN, qdd1..qddN, tau1..tauN \
(N joints in the order `rne check MODEL` lists; any column order; an optional `t` is ignored; \
lines starting with # are comments). With --floating-base: q1..q(N+7) (base position and \
quaternion first), qd1..qd(N+6) and the others with the base's six entries first, tau1..tau6 \
the wrench on the base; the excitation moves the base by six more Fourier series (x, y, z in m, \
then angles about x, y', z'' in rad; the limits list them first).

Examples:
  rne identify irb140 --excite excite.csv --noise 0.01 --seed 1   # trajectory + simulated torques
  rne identify irb140 --excite fresh.csv --noise 0.01 --seed 2
  rne identify irb140 excite.csv --validate fresh.csv --plot torques.svg")]
pub struct IdentifyArgs {
    /// A built-in robot name or a path to a .toml spec or .urdf file.
    pub model: String,
    /// Measurements to identify from (CSV, see below).
    #[arg(required_unless_present = "excite")]
    pub data: Option<PathBuf>,
    /// Model options.
    #[command(flatten)]
    pub options: ModelOptions,
    /// Identify viscous and Coulomb friction and an offset for every joint (three parameters
    /// each), also for joints whose model has no friction.
    #[arg(long)]
    pub friction: bool,
    /// Identify the armature (reflected rotor inertia) of every joint.
    #[arg(long)]
    pub armature: bool,
    /// Ordinary least squares: no per-joint weights.
    #[arg(long)]
    pub unweighted: bool,
    /// Fresh measurements (CSV) on which to report the identified model's torque error.
    #[arg(long, requires = "data")]
    pub validate: Option<PathBuf>,
    /// Figure of measured against predicted torques (SVG, or PNG by the extension), on the
    /// --validate data if given, else on DATA.
    #[arg(long, requires = "data")]
    pub plot: Option<PathBuf>,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
    /// What evaluates the regressor and the torques: the generated kernels compiled in memory
    /// or the independent numeric reference (the base parameters come from the reference
    /// either way).
    #[arg(long, value_enum, default_value_t = IdentifyEngine::Jit)]
    pub engine: IdentifyEngine,
    /// Instead of identifying: write an excitation trajectory optimised for the condition
    /// number of the stacked base regressor, with torques simulated from the model, to this
    /// CSV.
    #[arg(long, conflicts_with = "data", help_heading = "Excitation")]
    pub excite: Option<PathBuf>,
    /// Period of the Fourier series, s.
    #[arg(long, default_value_t = 10.0, help_heading = "Excitation")]
    pub period: f64,
    /// Harmonics per joint.
    #[arg(long, default_value_t = 5, help_heading = "Excitation")]
    pub harmonics: usize,
    /// Length of the record, s (default: one period).
    #[arg(long, help_heading = "Excitation")]
    pub duration: Option<f64>,
    /// Samples per second.
    #[arg(long, default_value_t = 100.0, help_heading = "Excitation")]
    pub rate: f64,
    /// Position limits |q_i| (rad or m): one value for every joint, or one per joint.
    #[arg(long, default_value = "1.5", help_heading = "Excitation")]
    pub q_limit: String,
    /// Velocity limits |q̇_i|: one value or one per joint.
    #[arg(long, default_value = "2", help_heading = "Excitation")]
    pub qd_limit: String,
    /// Acceleration limits |q̈_i|: one value or one per joint (default: none).
    #[arg(long, help_heading = "Excitation")]
    pub qdd_limit: Option<String>,
    /// Torque noise: standard deviation relative to each joint's RMS torque (0.01 = 1 %).
    #[arg(long, default_value_t = 0.01, help_heading = "Excitation")]
    pub noise: f64,
    /// Seed of the optimisation and of the noise.
    #[arg(long, default_value_t = 1, help_heading = "Excitation")]
    pub seed: u64,
    /// Candidate trajectories the optimisation evaluates.
    #[arg(long, default_value_t = 300, help_heading = "Excitation")]
    pub iterations: usize,
    /// States per period at which the condition number is evaluated.
    #[arg(long, default_value_t = 100, help_heading = "Excitation")]
    pub criterion_states: usize,
}

/// Identifies, or writes an excitation.
pub fn run(args: &IdentifyArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let source = RobotSource::resolve(&args.model);
    let mut model = args.options.load(&source, false)?;
    add_joint_parameters(&mut model, args.friction, args.armature);
    let mut reference = Reference::try_new(&model.to_numeric())?.with_friction(true);
    let base = BaseSet::find(&mut reference)?;
    let name = source.display_name();
    let mut jit = match args.engine {
        IdentifyEngine::Jit => jit_or_warn(&model, args, &reference)?,
        IdentifyEngine::Numeric => None,
    };
    let engine: &mut dyn Regressors = match jit.as_mut() {
        Some(jit) => jit,
        None => &mut reference,
    };
    match (&args.excite, &args.data) {
        (Some(path), _) => excite(args, &name, engine, &base, path, out),
        (None, Some(data)) => estimate(args, &name, engine, &base, data, out),
        (None, None) => Err(CliError::Argument(
            "give DATA.csv to identify from, or --excite OUT.csv".into(),
        )),
    }
}

/// The compiled kernels, or `None` (with a warning) on a processor without a JIT backend.
fn jit_or_warn(
    model: &RobotModel,
    args: &IdentifyArgs,
    reference: &Reference,
) -> Result<Option<JitRegressors>, CliError> {
    match JitRegressors::compile(model, args.options.scene(), &args.model, reference) {
        Ok(jit) => Ok(Some(jit)),
        Err(CliError::Jit(JitError::UnsupportedHost(why))) => {
            eprintln!("warning: {why}; identifying with the numeric reference");
            Ok(None)
        }
        Err(other) => Err(other),
    }
}

/// `one` value for every joint or one per joint.
fn per_joint(name: &str, text: &str, joints: usize) -> Result<Vec<f64>, CliError> {
    let values = parse_list(name, text)?;
    match values.len() {
        1 => Ok(vec![values[0]; joints]),
        n if n == joints => Ok(values),
        n => Err(CliError::Argument(format!(
            "--{name}: {n} values for {joints} joints (give one, or one per joint)"
        ))),
    }
}

/// Designs an excitation trajectory for `reference` (Fourier series, the base parameters
/// `base` best conditioned), simulates its measurements into `path` and reports it.
fn excite(
    args: &IdentifyArgs,
    name: &str,
    reference: &mut dyn Regressors,
    base: &BaseSet,
    path: &Path,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let spec = design_spec(args, reference.nv())?;
    let bar = candidates_bar(candidates(&spec) as u64);
    let excitation = design_with_progress(reference, base, &spec, |k| bar.set_position(k as u64))?;
    bar.finish_and_clear();
    let simulation = Simulation {
        duration: args.duration.unwrap_or(args.period),
        rate: args.rate,
        noise: args.noise,
        seed: args.seed,
    };
    let data = simulate(reference, &excitation.trajectory, &simulation)?;
    data.write(path)?;
    let f = &excitation.trajectory;
    if args.json {
        let report = json!({
            "model": name,
            "file": path.display().to_string(),
            "samples": data.samples.len(),
            "duration": simulation.duration,
            "noise": args.noise,
            "seed": args.seed,
            "base_parameters": base.len(),
            "condition_number": excitation.condition,
            "period": f.period,
            "offsets": f.offsets,
            "a": f.a,
            "b": f.b,
        });
        writeln!(out, "{report}")?;
    } else {
        writeln!(
            out,
            "{name}: wrote {} ({} samples over {} s, torque noise {} % of each joint's RMS torque, seed {})",
            path.display(),
            data.samples.len(),
            simulation.duration,
            100.0 * args.noise,
            args.seed
        )?;
        writeln!(
            out,
            "Fourier series of {} harmonics, period {} s (Swevers et al. 1997): condition number {:.4e} of the stacked base regressor ({} base parameters)",
            args.harmonics,
            f.period,
            excitation.condition,
            base.len()
        )?;
        for i in 0..f.joints() {
            writeln!(
                out,
                "  joint {}: q0 = {:.6}, a = [{}], b = [{}]",
                i + 1,
                f.offsets[i],
                list(&f.a[i]),
                list(&f.b[i])
            )?;
        }
    }
    Ok(())
}

/// The excitation's design as `args` gives it for `n` joints: the Fourier series' period and
/// harmonics, the joint limits (no acceleration limit unless given), the search's iterations,
/// criterion states and seed.
fn design_spec(args: &IdentifyArgs, n: usize) -> Result<Design, CliError> {
    let limits = Limits {
        position: per_joint("q-limit", &args.q_limit, n)?,
        velocity: per_joint("qd-limit", &args.qd_limit, n)?,
        acceleration: match &args.qdd_limit {
            Some(text) => per_joint("qdd-limit", text, n)?,
            None => vec![f64::INFINITY; n],
        },
    };
    Ok(Design {
        period: args.period,
        harmonics: args.harmonics,
        limits,
        iterations: args.iterations,
        criterion_states: args.criterion_states,
        seed: args.seed,
    })
}

/// A progress bar on stderr over the candidate trajectories of the excitation's design
/// (hidden when stderr is not a terminal).
fn candidates_bar(len: u64) -> ProgressBar {
    let bar = ProgressBar::new(len);
    if let Ok(style) = ProgressStyle::with_template(
        "designing the excitation {bar:30} {pos}/{len} candidates, {eta} left",
    ) {
        bar.set_style(style);
    }
    bar
}

fn list(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| format!("{v:.6}"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn estimate(
    args: &IdentifyArgs,
    name: &str,
    reference: &mut dyn Regressors,
    base: &BaseSet,
    path: &Path,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let (nq, n) = (reference.nq(), reference.nv());
    let data = Measurements::read_sized(path, nq, n)?;
    let estimate = identify(reference, base, &data, !args.unweighted)?;
    let validation = match &args.validate {
        Some(fresh) => {
            let fresh_data = Measurements::read_sized(fresh, nq, n)?;
            let predicted = predict(reference, base, &estimate.values, &fresh_data)?;
            Some((fresh.as_path(), fresh_data, predicted))
        }
        None => None,
    };
    if let Some(figure) = &args.plot {
        let own;
        let (shown, predicted, label) = match &validation {
            Some((fresh, fresh_data, predicted)) => (fresh_data, predicted, *fresh),
            None => {
                own = predict(reference, base, &estimate.values, &data)?;
                (&data, &own, path)
            }
        };
        let file = label.file_name().map_or_else(
            || label.display().to_string(),
            |f| f.to_string_lossy().into_owned(),
        );
        let title =
            format!("{name}: measured torques ({file}) and the identified model's prediction");
        torque_figure(figure, &title, shown, predicted)?;
    }
    let fit_of = validation
        .as_ref()
        .map(|(fresh, data, predicted)| (*fresh, fit(predicted, data)));
    if args.json {
        write_json(name, base, &data, &estimate, fit_of, out)
    } else {
        write_text(name, base, &data, &estimate, fit_of, out)
    }
}

fn write_json(
    name: &str,
    base: &BaseSet,
    data: &Measurements,
    estimate: &Estimate,
    validation: Option<(&Path, Fit)>,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let model = base.model_values();
    let parameters: Vec<serde_json::Value> = (0..base.len())
        .map(|b| {
            json!({
                "name": format!("b{}", b + 1),
                "combination": base.combination(b),
                "estimate": estimate.values[b],
                "std": estimate.deviations[b],
                "model": model[b],
            })
        })
        .collect();
    let mut report = json!({
        "model": name,
        "samples": data.samples.len(),
        "standard_parameters": base.standard_len(),
        "bodies": base.bodies,
        "weighted": estimate.weighted,
        "joint_std": estimate.joint_deviations,
        "condition_number": estimate.condition,
        "base_parameters": parameters,
    });
    if let Some((file, fit)) = validation {
        report["validation"] = json!({
            "file": file.display().to_string(),
            "relative_rms": fit.overall,
            "joints": fit.joints,
        });
    }
    writeln!(out, "{report}")?;
    Ok(())
}

fn write_text(
    name: &str,
    base: &BaseSet,
    data: &Measurements,
    estimate: &Estimate,
    validation: Option<(&Path, Fit)>,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let model = base.model_values();
    writeln!(
        out,
        "# {name}: {} base parameters of {} standard ones, from {} samples ({} equations)",
        base.len(),
        base.standard_len(),
        data.samples.len(),
        data.samples.len() * data.joints
    )?;
    writeln!(
        out,
        "# {}; condition number of the stacked base regressor {:.4e}",
        if estimate.weighted {
            "weighted least squares (Gautier & Poignet 2001)"
        } else {
            "ordinary least squares"
        },
        estimate.condition
    )?;
    writeln!(
        out,
        "# equation error σ_j of each joint, from its own equations (weights 1/σ_j): {}",
        estimate
            .joint_deviations
            .iter()
            .map(|s| format!("{s:.4e}"))
            .collect::<Vec<_>>()
            .join(", ")
    )?;
    let bodies: Vec<String> = base
        .bodies
        .iter()
        .enumerate()
        .map(|(k, b)| format!("{} = {b}", k + 1))
        .collect();
    writeln!(out, "# bodies: {}", bodies.join(", "))?;
    writeln!(
        out,
        "{:>4}  {:>13}  {:>10}  {:>8}  {:>13}  combination",
        "", "estimate", "std", "std/|θ|", "model"
    )?;
    let relative = estimate.relative_deviations();
    for b in 0..base.len() {
        writeln!(
            out,
            "{:>4}  {:>13.6e}  {:>10.3e}  {:>7.2} %  {:>13.6e}  {}",
            format!("b{}", b + 1),
            estimate.values[b],
            estimate.deviations[b],
            100.0 * relative[b],
            model[b],
            base.combination(b)
        )?;
    }
    if let Some((file, fit)) = validation {
        writeln!(
            out,
            "# prediction on {}: RMS torque error {:.3} % of the RMS torque (per joint: {})",
            file.display(),
            100.0 * fit.overall,
            fit.joints
                .iter()
                .map(|e| format!("{:.3} %", 100.0 * e))
                .collect::<Vec<_>>()
                .join(", ")
        )?;
    }
    Ok(())
}
