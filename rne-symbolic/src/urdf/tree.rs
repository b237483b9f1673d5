//! The link tree of a URDF: joints resolved to their links, checked to form one tree, and every
//! link put in model order — the root first, then depth-first with children in file order
//! (docs/design.md §2.2, the invariants of [`RobotModel`](crate::RobotModel)).

use std::collections::{HashMap, HashSet};

use super::elements::UrdfRobot;
use crate::spec::{SpecError, SpecErrorKind};

/// The links of a URDF in model order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Tree {
    /// One entry per link, parents first; the root is the first.
    pub(crate) links: Vec<TreeLink>,
}

/// A model link: a URDF link and the joint that attaches it (none for the root).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct TreeLink {
    /// Index in `UrdfRobot::joints` of the joint whose child the link is; `None` for the root.
    pub(crate) joint: Option<usize>,
    /// Index in `UrdfRobot::links` of the link.
    pub(crate) link: usize,
    /// Model index of the parent link; `None` for the root.
    pub(crate) parent: Option<usize>,
}

/// Resolves and orders the links and joints of `robot`.
pub(crate) fn build(robot: &UrdfRobot) -> Result<Tree, SpecError> {
    if robot.links.is_empty() {
        return Err(tree_error("the URDF has no <link>"));
    }
    let edges = Edges::new(robot, &link_index(robot)?)?;
    let roots: Vec<usize> = (0..robot.links.len())
        .filter(|&l| edges.parent_joint[l].is_none())
        .collect();
    let root = match roots.as_slice() {
        [root] => *root,
        [] => return Err(edges.cycle_error(robot, 0)),
        [_, second, ..] => {
            let names: Vec<String> = roots
                .iter()
                .map(|&l| format!("'{}'", robot.links[l].name))
                .collect();
            return Err(tree_error(format!(
                "several root links ({}): every link but one must be the child of a joint",
                names.join(", ")
            ))
            .in_link(&robot.links[*second].name));
        }
    };
    let (links, reached) = edges.depth_first(root);
    if let Some(unreached) = reached.iter().position(|&r| !r) {
        return Err(edges.cycle_error(robot, unreached));
    }
    Ok(Tree { links })
}

/// Index of each link name; rejects duplicates.
fn link_index(robot: &UrdfRobot) -> Result<HashMap<&str, usize>, SpecError> {
    let mut index = HashMap::new();
    for (l, link) in robot.links.iter().enumerate() {
        if index.insert(link.name.as_str(), l).is_some() {
            return Err(tree_error(format!("duplicate link name '{}'", link.name))
                .at_field("name")
                .in_link(&link.name));
        }
    }
    Ok(index)
}

/// The joints resolved to link indices.
struct Edges {
    /// `ends[j]`: the parent and child links of joint j.
    ends: Vec<(usize, usize)>,
    /// `parent_joint[l]`: the joint whose child is link l (`None` for a root).
    parent_joint: Vec<Option<usize>>,
    /// `children[l]`: the joints whose parent is link l, in file order.
    children: Vec<Vec<usize>>,
}

impl Edges {
    /// Resolves every joint's links by name; rejects duplicate joint names, missing links and
    /// a link that is the child of two joints.
    fn new(robot: &UrdfRobot, index: &HashMap<&str, usize>) -> Result<Edges, SpecError> {
        let mut names: HashSet<&str> = HashSet::new();
        let mut edges = Edges {
            ends: Vec::with_capacity(robot.joints.len()),
            parent_joint: vec![None; robot.links.len()],
            children: vec![Vec::new(); robot.links.len()],
        };
        for (j, joint) in robot.joints.iter().enumerate() {
            let error = |message: String, field: &str| {
                tree_error(message).at_field(field).in_joint(&joint.name)
            };
            if !names.insert(&joint.name) {
                return Err(error(
                    format!("duplicate joint name '{}'", joint.name),
                    "name",
                ));
            }
            let link = |name: &str, field: &str| {
                index.get(name).copied().ok_or_else(|| {
                    error(format!("the {field} link '{name}' does not exist"), field)
                })
            };
            let parent = link(&joint.parent, "parent")?;
            let child = link(&joint.child, "child")?;
            if let Some(first) = edges.parent_joint[child] {
                return Err(error(
                    format!(
                        "link '{}' is already the child of joint '{}': a link with two parents \
                         closes a loop, which a tree cannot model",
                        joint.child, robot.joints[first].name
                    ),
                    "child",
                ));
            }
            edges.parent_joint[child] = Some(j);
            edges.children[parent].push(j);
            edges.ends.push((parent, child));
        }
        Ok(edges)
    }
    /// The links in depth-first order from `root`, children in file order, and which URDF
    /// links were reached.
    fn depth_first(&self, root: usize) -> (Vec<TreeLink>, Vec<bool>) {
        let mut links = vec![TreeLink {
            joint: None,
            link: root,
            parent: None,
        }];
        let mut reached = vec![false; self.children.len()];
        reached[root] = true;
        let mut stack: Vec<(usize, usize)> =
            self.children[root].iter().rev().map(|&j| (j, 0)).collect();
        while let Some((j, parent)) = stack.pop() {
            let child = self.ends[j].1;
            reached[child] = true;
            links.push(TreeLink {
                joint: Some(j),
                link: child,
                parent: Some(parent),
            });
            let at = links.len() - 1;
            stack.extend(self.children[child].iter().rev().map(|&c| (c, at)));
        }
        (links, reached)
    }

    /// The error for a link that the walk from the root did not reach: following parent
    /// joints from `start` ends on a closed loop of joints, which the error names.
    fn cycle_error(&self, robot: &UrdfRobot, start: usize) -> SpecError {
        let mut seen: Vec<Option<usize>> = vec![None; robot.links.len()];
        let mut walked: Vec<usize> = Vec::new();
        let mut at = start;
        while let Some(j) = self.parent_joint[at] {
            if let Some(first) = seen[at] {
                let names: Vec<String> = walked[first..]
                    .iter()
                    .map(|&k| format!("'{}'", robot.joints[k].name))
                    .collect();
                return tree_error(format!(
                    "the link is its own ancestor through the joints {}: closed loops are not \
                     supported",
                    names.join(", ")
                ))
                .in_link(&robot.links[at].name);
            }
            seen[at] = Some(walked.len());
            walked.push(j);
            at = self.ends[j].0;
        }
        // Only the root has no parent joint, and a link below the root would have been reached.
        tree_error("the link is not connected to the root").in_link(&robot.links[at].name)
    }
}

fn tree_error(message: impl Into<String>) -> SpecError {
    SpecError::new(SpecErrorKind::Tree, message)
}
