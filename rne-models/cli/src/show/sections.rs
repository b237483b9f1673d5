//! The parts of the dynamics `rne show` prints, built in the symbolic engine: each a titled
//! list of named entries and their expressions.

use rne_symbolic::canonical::mathml;
use rne_symbolic::{Id, SymbolicDynamics};

use super::entries::{EntryKey, Section};
use super::Part;

/// The sections `what` asks for, in print order.
pub fn build(dynamics: &mut SymbolicDynamics, what: Part) -> Vec<Section> {
    let want =
        |p: Part| what == p || (what == Part::All && !matches!(p, Part::Reactions | Part::Dtau));
    let n = dynamics.layout().nv();
    let mut sections = Vec::new();
    if want(Part::Tau) {
        let tau = dynamics.inverse_dynamics();
        sections.push(vector(
            "joint torques, M(q) qdd + C(q, qd) qd + g(q) = tau (3.1)",
            "tau",
            &tau,
        ));
    }
    if want(Part::M) {
        let m = dynamics.mass_matrix();
        let entries = (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .map(|(i, j)| (EntryKey::new("M", &[i + 1, j + 1]), m[i][j]))
            .collect();
        sections.push(section(
            "mass matrix M(q), symmetric: upper triangle",
            entries,
        ));
    }
    if want(Part::C) {
        let c = dynamics.coriolis_matrix();
        sections.push(matrix(
            "Coriolis matrix C(q, qd) from Christoffel symbols (Mdot - 2C skew)",
            "C",
            &c,
        ));
    }
    if want(Part::G) {
        let g = dynamics.gravity_torques();
        sections.push(vector("gravity torques g(q)", "g", &g));
    }
    if want(Part::Energy) {
        let t = dynamics.kinetic_energy();
        let v = dynamics.potential_energy();
        let entries = vec![(EntryKey::new("T", &[]), t), (EntryKey::new("V", &[]), v)];
        sections.push(section("energy", entries));
    }
    if want(Part::Dtau) {
        let (dq, dv) = dynamics.inverse_dynamics_derivatives();
        sections.push(matrix("dtau/dq", "dtau_dq", &dq));
        sections.push(matrix("dtau/dqd", "dtau_dqd", &dv));
    }
    if want(Part::Reactions) {
        sections.push(reactions(dynamics));
    }
    sections
}

fn section(title: &str, entries: Vec<(EntryKey, Id)>) -> Section {
    Section {
        title: title.to_owned(),
        entries,
    }
}

fn vector(title: &str, name: &str, v: &[Id]) -> Section {
    let entries = v
        .iter()
        .enumerate()
        .map(|(i, &x)| (EntryKey::new(name, &[i + 1]), x))
        .collect();
    section(title, entries)
}

fn matrix(title: &str, name: &str, m: &[Vec<Id>]) -> Section {
    let entries = m
        .iter()
        .enumerate()
        .flat_map(|(i, row)| {
            row.iter()
                .enumerate()
                .map(move |(j, &x)| (EntryKey::new(name, &[i + 1, j + 1]), x))
        })
        .collect();
    section(title, entries)
}

fn reactions(dynamics: &mut SymbolicDynamics) -> Section {
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
            entries.push((EntryKey::new(&format!("f_{link}.{axis}"), &[]), *f));
            entries.push((EntryKey::new(&format!("tau_{link}.{axis}"), &[]), *t));
        }
    }
    section(
        "joint reactions f_i, tau_i in each link's body frame (3.21), (3.24)",
        entries,
    )
}

/// How an entry is labelled in print: `tau1`, `M[1,2]`, `g1` in text (the thesis's `τ₁`, `g₁`
/// with the index run on), `\tau_{1}`, `M_{12}` in LaTeX.
pub fn label(key: &EntryKey, latex: bool) -> String {
    let name = match (latex, key.name.as_str()) {
        (true, "tau") => "\\tau",
        (true, "dtau_dq") => "\\partial\\tau/\\partial q",
        (true, "dtau_dqd") => "\\partial\\tau/\\partial\\dot{q}",
        (_, name) => name,
    };
    match (latex, key.index.as_slice()) {
        (_, []) => name.to_owned(),
        (false, [i]) => format!("{name}{i}"),
        (false, [i, j]) => format!("{name}[{i},{j}]"),
        (true, [i]) => format!("{name}_{{{i}}}"),
        (true, [i, j]) => format!("{name}_{{{i}{j}}}"),
        (_, index) => format!("{name}{index:?}"),
    }
}

/// The label in MathML: `M` with subscript `1,2`, `τ₁`, `∂τ/∂q` with subscript, `T`, a
/// reaction `f` or `τ` with its link and axis as subscript.
pub fn mathml_label(key: &EntryKey) -> String {
    let name = match key.name.as_str() {
        "tau" => mathml::mi("τ"),
        "dtau_dq" => mathml::mi("∂τ/∂q"),
        "dtau_dqd" => format!("{}{}", mathml::mi("∂τ/∂"), mathml::mi("q̇")),
        name => match name.split_once('_') {
            Some(("tau", link)) => mathml::msub(&mathml::mi("τ"), &mathml::mi(link)),
            Some((letter, link)) => mathml::msub(&mathml::mi(letter), &mathml::mi(link)),
            None => mathml::mi(name),
        },
    };
    let index: Vec<String> = key
        .index
        .iter()
        .map(|i| mathml::mn(&i.to_string()))
        .collect();
    match index.as_slice() {
        [] => name,
        index => mathml::msub(&name, &index.join(&mathml::mo(","))),
    }
}
