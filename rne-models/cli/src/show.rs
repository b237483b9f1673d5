//! `rne show MODEL`: the dynamics printed for people, in the thesis's notation.

use std::io::Write;

use clap::{Args, ValueEnum};
use rne_symbolic::canonical::{Polynomial, PrintFormat, Printer};
use rne_symbolic::{Id, SymbolicDynamics};

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
    /// Everything but the reactions.
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
    let source = RobotSource::resolve(&args.model);
    let model = args.options.load(&source, args.symbolic_params)?;
    let mut dynamics = SymbolicDynamics::new(&model);
    let n = dynamics.dof();
    let want = |p: Part| args.what == p || (args.what == Part::All && p != Part::Reactions);
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
