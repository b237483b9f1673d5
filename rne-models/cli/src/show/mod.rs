//! `rne show MODEL`: the dynamics printed for people, in the thesis's notation — expanded
//! (`expanded`) within a size limit, one entry (`--entry`), or as a program with named
//! intermediate quantities (`compact`).

mod compact;
mod entries;
mod expanded;
mod sections;
mod size;
mod summary;

use std::io::Write;

use clap::{Args, ValueEnum};
use rne_symbolic::canonical::{PrintFormat, Printer};
use rne_symbolic::SymbolicDynamics;

use rne_identify::BaseSet;
use rne_reference::Reference;
use rne_symbolic::RobotModel;

use self::entries::EntryKey;
use crate::model::ModelOptions;
use crate::progress::Progress;
use crate::CliError;
use rne_models::RobotSource;

/// Which part of the dynamics to print.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum Part {
    /// The joint torques τ(q, q̇, q̈), grouped by accelerations and velocities as (4.42).
    Tau,
    /// The mass matrix M(q), (4.45).
    #[value(name = "M")]
    M,
    /// The Christoffel C(q, q̇).
    #[value(name = "C")]
    C,
    /// The gravity torques g(q), (4.47).
    #[value(name = "g")]
    G,
    /// Kinetic and potential energy.
    Energy,
    /// The joint reactions f_i and τ_i ((3.21), (3.24)): force and torque the parent exerts on
    /// each link, in the link's body frame; the components off the joint axis are the loads
    /// the joint must resist (thesis section 5.4). Not part of `all`.
    Reactions,
    /// The derivatives ∂τ/∂q and ∂τ/∂q̇ of the joint torques (∂τ/∂q̈ is M), entry by entry: the
    /// derivatives of (4.45)–(4.47) for the planar elbow. Not part of `all`.
    Dtau,
    /// The base parameters: each identifiable combination of the standard parameters (per
    /// body m, m·c and the inertia about the body origin; friction and armature), with exact
    /// coefficients and the model's value; found by Gautier's numerical method on the numeric
    /// reference's regressor. Not part of `all`.
    BaseParameters,
    /// Everything but the reactions, the derivatives and the base parameters.
    All,
}

/// Text or LaTeX.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Plain text with the abbreviations s1, c12, Dq1, DDq1.
    Text,
    /// LaTeX (`\dot{q}_{1}`, `c_{12}`), one equation per line.
    Latex,
}

/// Arguments of `rne show`.
#[derive(Debug, Args)]
pub struct ShowArgs {
    /// A built-in robot name or a path to a .toml spec or .urdf file.
    pub model: String,
    /// Model options.
    #[command(flatten)]
    pub options: ModelOptions,
    /// What to print.
    #[arg(long, value_enum, default_value = "all")]
    pub what: Part,
    /// Output notation.
    #[arg(long, value_enum, default_value = "text")]
    pub format: Format,
    /// Keep the spec's parameters as symbols (m1, l1, ...) instead of numbers.
    #[arg(long)]
    pub symbolic_params: bool,
    /// The most bytes of equations to print (`300K`, `2M`, or bytes): the entries that fit are
    /// printed, the others listed with their size. An entry's expansion also stops once it
    /// could no longer fit, so a large robot costs seconds.
    #[arg(long, default_value = "300K", value_parser = size::parse)]
    pub max_size: usize,
    /// Print only this entry: `M[2,3]`, `g[1]`, `tau[4]`, `C[1,2]`, `dtau_dq[1,2]`, `T`, `V`.
    #[arg(long)]
    pub entry: Option<String>,
    /// The compact form: a program, one operation a line, every quantity used more than once
    /// computed once and named (s1 = sin q1, t12 = ...), as for models too large to expand.
    #[arg(long)]
    pub compact: bool,
}

/// Prints the requested parts of the dynamics.
pub fn run(args: &ShowArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if args.what == Part::BaseParameters && args.symbolic_params {
        return Err(CliError::Argument(
            "--symbolic-params with --what base-parameters: the base parameters are found \
             numerically at the spec's parameter values (their coefficients come from the \
             geometry), so they cannot be kept as symbols; leave out --symbolic-params"
                .into(),
        ));
    }
    let source = RobotSource::resolve(&args.model);
    let model = args.options.load(&source, args.symbolic_params)?;
    if args.what == Part::BaseParameters {
        return base_parameters(&source, &model, args.format, out);
    }
    let mut dynamics = SymbolicDynamics::new(&model);
    let sections = {
        let _progress = Progress::start("building the equations");
        sections::build(&mut dynamics, args.what)
    };
    let sections = match &args.entry {
        Some(entry) => entries::select(sections, &EntryKey::parse(entry)?)?,
        None => sections,
    };
    let latex = args.format == Format::Latex;
    let comment = if latex { "%" } else { "#" };
    let n = dynamics.layout().nv();
    writeln!(
        out,
        "{comment} {} ({} joints: {})",
        source.display_name(),
        n,
        model.joint_names().join(", ")
    )?;
    let graph = &dynamics.model.graph;
    if args.compact {
        let printed = compact::print(graph, &sections, latex, args.max_size, out)?;
        return summary::compact(args, comment, printed, out);
    }
    let format = if latex {
        PrintFormat::Latex
    } else {
        PrintFormat::Text
    };
    let printer = Printer::new(graph.symbols(), format);
    let printer = if args.symbolic_params {
        printer
    } else {
        printer.significant_digits(6)
    };
    let style = expanded::Style {
        printer,
        latex,
        max_size: args.max_size,
    };
    let what = format!("the equations of {}", source.display_name());
    let printed = expanded::print(graph, &sections, &style, &what, out)?;
    summary::expanded(args, comment, &printed, out)
}

/// Prints each base parameter as a combination of standard ones, with its value.
fn base_parameters(
    source: &RobotSource,
    model: &RobotModel,
    format: Format,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let failed = |e: &dyn std::fmt::Display| CliError::Argument(e.to_string());
    let mut reference = Reference::try_new(&model.to_numeric())
        .map_err(|e| failed(&e))?
        .with_friction(true);
    let base = BaseSet::find(&mut reference).map_err(|e| failed(&e))?;
    let values = base.model_values();
    let latex = format == Format::Latex;
    let comment = if latex { "%" } else { "#" };
    writeln!(
        out,
        "{comment} {}: {} base parameters of {} standard ones (the numeric rank of the regressor stacked over random states; Gautier 1991)",
        source.display_name(),
        base.len(),
        base.standard_len()
    )?;
    let bodies: Vec<String> = base
        .bodies
        .iter()
        .enumerate()
        .map(|(k, b)| format!("{} = {b}", k + 1))
        .collect();
    writeln!(
        out,
        "{comment} bodies: {}; m·c and I about each body frame's origin, in its axes",
        bodies.join(", ")
    )?;
    let lines: Vec<(String, String)> = (0..base.len())
        .map(|b| {
            if latex {
                (
                    format!("b_{{{}}} &= {}", b + 1, base.combination_latex(b)),
                    " \\\\ %".to_owned(),
                )
            } else {
                (
                    format!("b{} = {}", b + 1, base.combination(b)),
                    "  #".to_owned(),
                )
            }
        })
        .collect();
    let width = lines
        .iter()
        .map(|(l, _)| l.chars().count())
        .max()
        .unwrap_or(0);
    for ((line, comment), value) in lines.iter().zip(&values) {
        let pad = width - line.chars().count();
        writeln!(out, "{line}{:pad$}{comment} = {}", "", significant(*value))?;
    }
    Ok(())
}

/// `x` to 7 significant digits, in the shortest form that shows them.
fn significant(x: f64) -> String {
    let rounded: f64 = format!("{x:.6e}").parse().unwrap_or(x);
    if rounded == 0.0 || (1e-4..1e7).contains(&rounded.abs()) {
        format!("{rounded}")
    } else {
        format!("{rounded:e}")
    }
}
