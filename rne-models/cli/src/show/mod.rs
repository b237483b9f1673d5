//! `rne show MODEL`: the dynamics printed for people, in the thesis's notation — expanded
//! (`expanded`) within a size limit, one entry (`--entry`), or as a program with named
//! intermediate quantities (`compact`); as text, LaTeX, or a web page (`html`).

mod compact;
mod entries;
mod expanded;
mod html;
mod sections;
mod size;
mod summary;

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use rne_symbolic::canonical::{PrintFormat, Printer};
use rne_symbolic::{ExprGraph, SymbolicDynamics};

use rne_identify::BaseSet;
use rne_reference::Reference;
use rne_symbolic::RobotModel;

use self::entries::{EntryKey, Section};
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

/// Text, LaTeX or a web page.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Plain text with the abbreviations s1, c12, Dq1, DDq1.
    Text,
    /// LaTeX (`\dot{q}_{1}`, `c_{12}`), one equation per line.
    Latex,
    /// A self-contained web page, `index.html` in `--out DIR`: each entry collapsible, the
    /// mathematics in MathML (rendered by the browser, offline), the compact program after.
    Html,
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
    /// printed, the others listed with their size, or by name when they were not expanded. An
    /// entry's expansion stops once it could no longer fit, and the expansion and printing of
    /// all entries take at most a fixed amount of work per byte of the limit, so a large robot
    /// costs seconds.
    #[arg(long, default_value = "300K", value_parser = size::parse)]
    pub max_size: usize,
    /// Print only this entry: `M[2,3]`, `g[1]`, `tau[4]`, `C[1,2]`, `dtau_dq[1,2]`, `T`, `V`.
    #[arg(long)]
    pub entry: Option<String>,
    /// The compact form: a program, one operation a line, every quantity used more than once
    /// computed once and named (s1 = sin q1, t12 = ...), as for models too large to expand.
    #[arg(long)]
    pub compact: bool,
    /// The directory `--format html` writes its page to (created if needed, checked first).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// The robot's name and joints, as each form's header gives them.
struct Header {
    name: String,
    /// Degrees of freedom (a floating base's six included).
    dofs: usize,
    joints: Vec<String>,
    /// Whether q, v, q̈ and τ begin with a floating base's coordinates.
    floating: bool,
}

/// How the equations name a floating base's coordinates (rne_symbolic::SymbolTable).
const BASE_NOTATION: &str = "floating base: position x y z, orientation quaternion qx qy qz qw; \
     velocity vx vy vz and angular velocity wx wy wz in the base frame, their rates Dvx … Dwz; \
     force fx fy fz and moment nx ny nz on the base";

impl Header {
    /// The robot's name and what moves: `panda (7 joints: q1, …)`, or with a floating base
    /// `g1 (35 degrees of freedom: a floating base and 29 joints: …)`.
    fn describe(&self) -> String {
        let joints = self.joints.join(", ");
        match self.floating {
            false => format!("{} ({} joints: {joints})", self.name, self.dofs),
            true => format!(
                "{} ({} degrees of freedom: a floating base and {} joints: {joints})",
                self.name,
                self.dofs,
                self.joints.len()
            ),
        }
    }
}

/// Prints the requested parts of the dynamics, or writes them as a web page.
pub fn run(args: &ShowArgs, out: &mut dyn Write) -> Result<(), CliError> {
    check(args)?;
    if let Some(dir) = &args.out {
        crate::long_run::prepare_out(dir)?;
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
    let header = Header {
        name: source.display_name(),
        dofs: dynamics.layout().nv(),
        joints: model.joint_names(),
        floating: model.is_floating(),
    };
    let graph = &dynamics.model.graph;
    match &args.out {
        Some(dir) => html::write(args, &header, graph, &sections, dir, out),
        None => print(args, &header, graph, &sections, out),
    }
}

/// Refuses combinations of options that cannot be honoured, before any work.
fn check(args: &ShowArgs) -> Result<(), CliError> {
    let refuse = |message: &str| Err(CliError::Argument(message.to_owned()));
    let html = args.format == Format::Html;
    if args.what == Part::BaseParameters && args.symbolic_params {
        return refuse(
            "--symbolic-params with --what base-parameters: the base parameters are found \
             numerically at the spec's parameter values (their coefficients come from the \
             geometry), so they cannot be kept as symbols; leave out --symbolic-params",
        );
    }
    if html && args.what == Part::BaseParameters {
        return refuse(
            "--format html with --what base-parameters: the page shows the equations; \
             print the base parameters as text or LaTeX",
        );
    }
    match (html, &args.out) {
        (true, None) => refuse("--format html writes a page: give the directory with --out DIR"),
        (false, Some(_)) => refuse("--out DIR is where --format html writes its page: add --format html, or leave out --out to print"),
        _ => Ok(()),
    }
}

/// Prints the sections as text or LaTeX: the header line, then the expanded equations or the
/// program, then what was left out.
fn print(
    args: &ShowArgs,
    header: &Header,
    graph: &ExprGraph,
    sections: &[Section],
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let latex = args.format == Format::Latex;
    let comment = if latex { "%" } else { "#" };
    writeln!(out, "{comment} {}", header.describe())?;
    if header.floating {
        writeln!(out, "{comment} {BASE_NOTATION}")?;
    }
    if args.compact {
        let printed = compact::print(graph, sections, args.format, args.max_size, out)?;
        return summary::compact(args, printed, out);
    }
    let format = if latex {
        PrintFormat::Latex
    } else {
        PrintFormat::Text
    };
    let style = expanded::Style {
        printer: printer(args, graph, format),
        format: args.format,
        max_size: args.max_size,
    };
    let what = format!("the equations of {}", header.name);
    let printed = expanded::print(graph, sections, &style, &what, out)?;
    summary::expanded(args, &printed, out)
}

/// The polynomial printer: numbers to six significant digits unless the parameters are kept
/// as symbols.
fn printer<'g>(args: &ShowArgs, graph: &'g ExprGraph, format: PrintFormat) -> Printer<'g> {
    let printer = Printer::new(graph.symbols(), format);
    if args.symbolic_params {
        printer
    } else {
        printer.significant_digits(6)
    }
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
