//! The link tree of a spec: parents resolved, checked for cycles, links ordered depth-first from
//! the base with children in file order, and joint variables named and numbered in that order
//! (the invariants of [`RobotModel`](crate::RobotModel)).

use std::collections::HashMap;

use super::error::{SpecError, SpecErrorKind};
use super::expression::{is_identifier, RESERVED};
use super::schema::LinkSpec;
use crate::input::MAX_SYMBOLS;
use crate::model::{JointKind, JointVariable};

/// The name by which a link names the fixed base as its parent.
pub(crate) const BASE: &str = "base";

/// The model order of a spec's links.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Tree {
    /// Index in the file of each model link, in model order.
    pub(crate) order: Vec<usize>,
    /// Model index of each model link's parent (`None`: the base).
    pub(crate) parent: Vec<Option<usize>>,
    /// Joint index of each model link (`None`: fixed).
    pub(crate) joint: Vec<Option<usize>>,
    /// The joint variables in joint order.
    pub(crate) joints: Vec<JointVariable>,
}

impl Tree {
    /// The joint variable names in joint order.
    pub(crate) fn joint_names(&self) -> Vec<String> {
        self.joints.iter().map(|j| j.name.clone()).collect()
    }
}

/// Orders the links and names their joint variables; `parameters` are the parameter names,
/// which joint variables and their printed derivatives (`D<q>`, `DD<q>`, `tau_<q>`) may not
/// take.
pub(crate) fn build(links: &[LinkSpec<'_>], parameters: &[&str]) -> Result<Tree, SpecError> {
    if links.is_empty() {
        return Err(tree_error("the spec has no [[link]]").at_field("link"));
    }
    let index = link_index(links)?;
    let parent = parents(links, &index)?;
    let order = depth_first(&parent);
    check_cycles(links, &parent, &order)?;
    let mut model_index = vec![0; links.len()];
    for (m, &s) in order.iter().enumerate() {
        if let Some(slot) = model_index.get_mut(s) {
            *slot = m;
        }
    }
    let names = joint_names(links, parameters)?;
    let mut joints = Vec::new();
    let mut joint = Vec::with_capacity(order.len());
    for (m, &s) in order.iter().enumerate() {
        match names.get(s).cloned().flatten() {
            Some(name) => {
                joint.push(Some(joints.len()));
                joints.push(JointVariable { name, link: m });
            }
            None => joint.push(None),
        }
    }
    let parent = order
        .iter()
        .map(|&s| {
            parent
                .get(s)
                .copied()
                .flatten()
                .and_then(|p| model_index.get(p).copied())
        })
        .collect();
    Ok(Tree {
        order,
        parent,
        joint,
        joints,
    })
}

/// File index of each link name; rejects duplicates and the reserved name `base`.
fn link_index<'s>(links: &'s [LinkSpec<'_>]) -> Result<HashMap<&'s str, usize>, SpecError> {
    let mut index = HashMap::new();
    for (i, link) in links.iter().enumerate() {
        let name = link.name.name.as_str();
        if name == BASE {
            return Err(
                tree_error("'base' names the fixed base; choose another link name")
                    .at_field("name")
                    .in_link(name)
                    .at_span(link.name.span.clone()),
            );
        }
        if index.insert(name, i).is_some() {
            return Err(tree_error(format!("duplicate link name '{name}'"))
                .at_field("name")
                .in_link(name)
                .at_span(link.name.span.clone()));
        }
    }
    Ok(index)
}

/// File index of each link's parent: the named one, the base, or by default the previous link.
fn parents(
    links: &[LinkSpec<'_>],
    index: &HashMap<&str, usize>,
) -> Result<Vec<Option<usize>>, SpecError> {
    links
        .iter()
        .enumerate()
        .map(|(i, link)| match &link.parent {
            None => Ok(i.checked_sub(1)),
            Some(parent) if parent.name == BASE => Ok(None),
            Some(parent) => index
                .get(parent.name.as_str())
                .map(|&p| Some(p))
                .ok_or_else(|| {
                    tree_error(format!("unknown parent '{}'", parent.name))
                        .at_field("parent")
                        .in_link(&link.name.name)
                        .at_span(parent.span.clone())
                }),
        })
        .collect()
}

/// Rejects a link that is its own ancestor, naming the first such link in the file. Links
/// that the depth-first walk from the base did not reach lie on or behind a cycle.
fn check_cycles(
    links: &[LinkSpec<'_>],
    parent: &[Option<usize>],
    reached: &[usize],
) -> Result<(), SpecError> {
    let mut unreached = vec![true; links.len()];
    for &r in reached {
        if let Some(u) = unreached.get_mut(r) {
            *u = false;
        }
    }
    for (i, link) in links
        .iter()
        .enumerate()
        .filter(|(i, _)| unreached.get(*i) == Some(&true))
    {
        let mut path = vec![i];
        let mut at = parent.get(i).copied().flatten();
        while let Some(p) = at {
            path.push(p);
            if p == i {
                let names: Vec<&str> = path
                    .iter()
                    .filter_map(|&k| links.get(k))
                    .map(|l| l.name.name.as_str())
                    .collect();
                return Err(tree_error(format!(
                    "link '{}' is its own ancestor: {}",
                    link.name.name,
                    names.join(" -> ")
                ))
                .at_field("parent")
                .in_link(&link.name.name)
                .at_span(link.parent.as_ref().and_then(|p| p.span.clone())));
            }
            if path.len() > links.len() {
                break;
            }
            at = parent.get(p).copied().flatten();
        }
    }
    Ok(())
}

/// File indices in depth-first order from the base, children in file order; links on or
/// behind a cycle are not reached.
fn depth_first(parent: &[Option<usize>]) -> Vec<usize> {
    // children[0]: the base's; children[i + 1]: link i's; each in file order.
    let mut children = vec![Vec::new(); parent.len() + 1];
    for (c, p) in parent.iter().enumerate() {
        if let Some(list) = children.get_mut(p.map_or(0, |p| p + 1)) {
            list.push(c);
        }
    }
    let mut order = Vec::with_capacity(parent.len());
    let mut stack: Vec<usize> = children
        .first()
        .into_iter()
        .flatten()
        .rev()
        .copied()
        .collect();
    while let Some(link) = stack.pop() {
        order.push(link);
        stack.extend(children.get(link + 1).into_iter().flatten().rev());
    }
    order
}

/// The joint variable name of each link (file order; `None` for fixed joints): `q` or the
/// default `q<k>`, k counting movable joints in the file. Names must be identifiers, unique,
/// and distinct from parameters, also in their printed derivatives.
fn joint_names(
    links: &[LinkSpec<'_>],
    parameters: &[&str],
) -> Result<Vec<Option<String>>, SpecError> {
    let mut names = Vec::with_capacity(links.len());
    let mut owner: HashMap<String, String> = parameters
        .iter()
        .map(|&p| (p.to_owned(), format!("the parameter '{p}'")))
        .collect();
    for link in links {
        if link.kind == JointKind::Fixed {
            names.push(None);
            continue;
        }
        let default = format!("q{}", names.iter().flatten().count() + 1);
        let (name, span) = match &link.q {
            Some(q) => (q.name.clone(), q.span.clone()),
            None => (default, None),
        };
        let error = |kind: SpecErrorKind, message: String| {
            SpecError::new(kind, message)
                .at_field("q")
                .in_link(&link.name.name)
                .at_span(span.clone())
        };
        if let Some(problem) = unusable_variable_name(&name) {
            return Err(error(SpecErrorKind::Format, problem));
        }
        if let Some(other) = owner.get(&name) {
            let message = if other.starts_with("joint variable") {
                format!("duplicate joint variable '{name}': already {other}")
            } else {
                format!("joint variable '{name}' clashes with {other}")
            };
            return Err(error(SpecErrorKind::Tree, message));
        }
        owner.insert(
            name.clone(),
            format!("joint variable '{name}' of link '{}'", link.name.name),
        );
        names.push(Some(name));
    }
    if names.iter().flatten().count() > MAX_SYMBOLS {
        return Err(tree_error(format!("more than {MAX_SYMBOLS} joints")));
    }
    for (link, name) in links.iter().zip(&names) {
        let Some(name) = name else { continue };
        for (what, printed) in printed_forms(name) {
            if let Some(other) = owner.get(&printed) {
                return Err(tree_error(format!(
                    "joint variable '{name}' clashes with {other}: its {what} is printed '{printed}'"
                ))
                .at_field("q")
                .in_link(&link.name.name)
                .at_span(link.q.as_ref().and_then(|q| q.span.clone())));
            }
        }
    }
    Ok(names)
}

/// Why `name` cannot name a joint variable, if it cannot: it must be an identifier (letters,
/// digits and `_`) and not a word of the expression language.
fn unusable_variable_name(name: &str) -> Option<String> {
    (!is_identifier(name) || RESERVED.contains(&name)).then(|| {
        format!(
            "joint variable '{name}' is not a name (letters, digits and _, not {})",
            RESERVED.join(", ")
        )
    })
}

/// How a joint variable's velocity, acceleration and force are printed (`D<q>`, `DD<q>`,
/// `tau_<q>`, as the thesis's Maple code), each with what it is.
fn printed_forms(name: &str) -> [(&'static str, String); 3] {
    [
        ("velocity", format!("D{name}")),
        ("acceleration", format!("DD{name}")),
        ("force", format!("tau_{name}")),
    ]
}

fn tree_error(message: impl Into<String>) -> SpecError {
    SpecError::new(SpecErrorKind::Tree, message)
}
