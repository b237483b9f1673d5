//! `rne show MODEL`: the dynamics printed for people, in the thesis's notation.

use std::io::Write;

use clap::{Args, ValueEnum};
use rne_symbolic::canonical::{Polynomial, PrintFormat, Printer};
use rne_symbolic::{Id, SymbolicDynamics};

use rne_identify::BaseSet;
use rne_reference::Reference;
use rne_symbolic::RobotModel;

use super::model::ModelOptions;
use super::CliError;
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
    let mut dynamics = SymbolicDynamics::new(&model);
    let n = dynamics.layout().nv();
    if args.what == Part::BaseParameters {
        return base_parameters(&source, &model, args.format, out);
    }
    let want = |p: Part| {
        args.what == p || (args.what == Part::All && !matches!(p, Part::Reactions | Part::Dtau))
    };
    let mut sections: Vec<(&str, Vec<(String, Id)>)> = Vec::new();
    let latex = args.format == Format::Latex;
    let sub = |a: usize, b: Option<usize>| match (latex, b) {
        (false, Some(b)) => format!("[{a},{b}]"),
        (false, None) => format!("{a}"),
        (true, Some(b)) => format!("_{{{a}{b}}}"),
        (true, None) => format!("_{{{a}}}"),
    };
    let name = |text: &str, tex: &str| {
        if latex {
            tex.to_owned()
        } else {
            text.to_owned()
        }
    };
    if want(Part::Tau) {
        let tau = dynamics.inverse_dynamics();
        let entries = (0..n)
            .map(|i| {
                (
                    format!("{}{}", name("tau", "\\tau"), sub(i + 1, None)),
                    tau[i],
                )
            })
            .collect();
        sections.push((
            "joint torques, M(q) qdd + C(q, qd) qd + g(q) = tau (3.1)",
            entries,
        ));
    }
    if want(Part::M) {
        let m = dynamics.mass_matrix();
        let entries = (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .map(|(i, j)| (format!("M{}", sub(i + 1, Some(j + 1))), m[i][j]))
            .collect();
        sections.push(("mass matrix M(q), symmetric: upper triangle", entries));
    }
    if want(Part::C) {
        let c = dynamics.coriolis_matrix();
        let entries = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| (format!("C{}", sub(i + 1, Some(j + 1))), c[i][j]))
            .collect();
        sections.push((
            "Coriolis matrix C(q, qd) from Christoffel symbols (Mdot - 2C skew)",
            entries,
        ));
    }
    if want(Part::G) {
        let g = dynamics.gravity_torques();
        let entries = (0..n)
            .map(|i| (format!("g{}", sub(i + 1, None)), g[i]))
            .collect();
        sections.push(("gravity torques g(q)", entries));
    }
    if want(Part::Energy) {
        let t = dynamics.kinetic_energy();
        let v = dynamics.potential_energy();
        sections.push(("energy", vec![("T".to_owned(), t), ("V".to_owned(), v)]));
    }

    if want(Part::Dtau) {
        let (dq, dv) = dynamics.inverse_dynamics_derivatives();
        for (matrix, title, text, tex) in [
            (dq, "dtau/dq", "dtau_dq", "\\partial\\tau/\\partial q"),
            (
                dv,
                "dtau/dqd",
                "dtau_dqd",
                "\\partial\\tau/\\partial\\dot{q}",
            ),
        ] {
            let entries = (0..n)
                .flat_map(|i| (0..n).map(move |j| (i, j)))
                .map(|(i, j)| {
                    (
                        format!("{}{}", name(text, tex), sub(i + 1, Some(j + 1))),
                        matrix[i][j],
                    )
                })
                .collect();
            sections.push((title, entries));
        }
    }

    if want(Part::Reactions) {
        let reactions = dynamics.joint_reactions();
        let links: Vec<String> = dynamics
            .model
            .links
            .iter()
            .map(|l| l.name.clone())
            .collect();
        let mut entries = Vec::new();
        for (link, r) in links.iter().zip(&reactions) {
            for (axis, (f, t)) in ["x", "y", "z"].iter().zip(r.force.iter().zip(&r.torque)) {
                entries.push((format!("f_{link}.{axis}"), *f));
                entries.push((format!("tau_{link}.{axis}"), *t));
            }
        }
        sections.push((
            "joint reactions f_i, tau_i in each link's body frame (3.21), (3.24)",
            entries,
        ));
    }

    let graph = &dynamics.model.graph;
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
    let roots: Vec<Id> = sections
        .iter()
        .flat_map(|(_, entries)| entries.iter().map(|(_, id)| *id))
        .collect();
    let polynomials = Polynomial::from_exprs(graph, &roots)
        .map_err(|e| CliError::Argument(format!("cannot expand the dynamics for printing: {e}")))?;
    let mut polynomials = polynomials.into_iter();
    let comment = if latex { "%" } else { "#" };
    let equals = if latex { " &= " } else { " = " };
    let end = if latex { " \\\\" } else { "" };
    writeln!(
        out,
        "{comment} {} ({} joints: {})",
        source.display_name(),
        n,
        model.joint_names().join(", ")
    )?;
    for (title, entries) in &sections {
        writeln!(out, "\n{comment} {title}")?;
        for (label, _) in entries {
            let p = polynomials.next().expect("one polynomial per entry");
            writeln!(out, "{label}{equals}{}{end}", printer.print(&p))?;
        }
    }
    Ok(())
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
