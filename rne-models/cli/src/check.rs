//! `rne check MODEL`: reads and validates a robot and reports what was read — links as the
//! file names them, joint variables and degrees of freedom under the model options, total
//! mass, base, mimic joints, friction — and the warnings. Exit status
//! 0 with warnings (non-zero with `--strict`), non-zero on an error.

use std::io::Write;

use clap::Args;
use rne_symbolic::{JointKind, RobotModel};

use super::model::ModelOptions;
use super::CliError;
use rne_models::RobotSource;

/// Arguments of `rne check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// A built-in robot name or a path to a .toml spec or .urdf file.
    pub model: String,
    /// Model options.
    #[command(flatten)]
    pub options: ModelOptions,
    /// Print one JSON object instead of a report.
    #[arg(long)]
    pub json: bool,
}

/// One link as the report lists it.
struct LinkReport {
    name: String,
    parent: String,
    kind: &'static str,
    joint: Option<String>,
    mass: f64,
    mimic: Option<String>,
    friction: bool,
}

/// Reads the robot and prints the report.
pub fn run(args: &CheckArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let source = RobotSource::resolve(&args.model);
    let read = args.options.read(&source, false)?;
    let links = link_reports(&read);
    let model = args.options.apply(&source, read)?;
    let layout = model.state_layout();
    let total_mass: f64 = links.iter().map(|l| l.mass).sum();
    let base = match model.base {
        rne_symbolic::model::Base::Fixed => "fixed",
        rne_symbolic::model::Base::Floating => "floating",
    };
    let mimic: Vec<&LinkReport> = links.iter().filter(|l| l.mimic.is_some()).collect();
    if args.json {
        let report = serde_json::json!({
            "model": source.display_name(),
            "name": model.name,
            "dof": model.dof(),
            "nq": layout.nq(),
            "nv": layout.nv(),
            "joints": model.joint_names(),
            "links": links.iter().map(|l| serde_json::json!({
                "name": l.name, "parent": l.parent, "kind": l.kind, "joint": l.joint,
                "mass": l.mass, "mimic": l.mimic, "friction": l.friction,
            })).collect::<Vec<_>>(),
            "total_mass": total_mass,
            "base": base,
            "mimic": mimic.iter().map(|l| l.joint.clone()).collect::<Vec<_>>(),
            "warnings": model.warnings.iter().map(ToString::to_string).collect::<Vec<_>>(),
        });
        writeln!(out, "{report}")?;
        return Ok(());
    }
    writeln!(out, "model: {} ({})", model.name, source.display_name())?;
    writeln!(out, "base: {base}")?;
    writeln!(out, "degrees of freedom: {}", model.dof())?;
    writeln!(out, "state: NQ = {}, NV = {}", layout.nq(), layout.nv())?;
    writeln!(out, "total mass: {total_mass} kg")?;
    writeln!(out, "links ({}):", links.len())?;
    for l in &links {
        let joint = l
            .joint
            .as_deref()
            .map_or(String::new(), |j| format!(" '{j}'"));
        let mut notes = Vec::new();
        if let Some(leader) = &l.mimic {
            notes.push(format!("mimics '{leader}'"));
        }
        if l.friction {
            notes.push("friction".to_owned());
        }
        let notes = if notes.is_empty() {
            String::new()
        } else {
            format!(", {}", notes.join(", "))
        };
        writeln!(
            out,
            "  {} <- {}: {}{joint}, mass {}{notes}",
            l.name, l.parent, l.kind, l.mass
        )?;
    }
    writeln!(out, "mimic joints: {}", mimic.len())?;
    writeln!(out, "warnings: {}", model.warnings.len())?;
    for warning in &model.warnings {
        writeln!(out, "  {warning}")?;
    }
    Ok(())
}

fn link_reports(model: &RobotModel) -> Vec<LinkReport> {
    let numeric = model.to_numeric();
    model
        .links
        .iter()
        .zip(&numeric.links)
        .map(|(link, values)| LinkReport {
            name: link.name.clone(),
            parent: link
                .parent
                .and_then(|p| model.links.get(p))
                .map_or_else(|| "world".to_owned(), |p| p.name.clone()),
            kind: match link.kind {
                JointKind::Revolute => "revolute",
                JointKind::Prismatic => "prismatic",
                JointKind::Fixed => "fixed",
                JointKind::FreeFlyer => "free-flyer",
            },
            joint: link
                .joint
                .and_then(|k| model.joints.get(k))
                .map(|j| j.name.clone()),
            mass: values.mass,
            mimic: link.mimic.as_ref().map(|m| m.leader.clone()),
            friction: link.friction.is_some(),
        })
        .collect()
}
