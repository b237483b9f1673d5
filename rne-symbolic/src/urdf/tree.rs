//! The link tree of a URDF: joints resolved to their links, checked to form one tree, the base
//! (the root and the links fixed to it) told apart from the model links, and the model links
//! put in depth-first order from the root with children in file order (DESIGN §2, the
//! invariants of [`RobotModel`](crate::RobotModel)).

use std::collections::{HashMap, HashSet};

use urdf_rs::{JointType, Robot};

use crate::spec::{SpecError, SpecErrorKind};

/// The model links of a URDF, in model order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Tree {
    /// One entry per model link, parents first.
    pub(crate) links: Vec<TreeLink>,
}

/// A model link: a joint and its child link.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct TreeLink {
    /// Index in `Robot::joints` of the joint that attaches the link.
    pub(crate) joint: usize,
    /// Index in `Robot::links` of the link, the joint's child.
    pub(crate) link: usize,
    /// Model index of the parent link; `None` when the joint's parent link is part of the base.
    pub(crate) parent: Option<usize>,
    /// When the joint's parent link is part of the base: the fixed joints (indices in
    /// `Robot::joints`) that lead from the root to it, root first. Empty otherwise.
    pub(crate) base_path: Vec<usize>,
}

/// Where a link of the URDF ended up.
#[derive(Clone, Debug)]
enum Place {
    /// In the base, reached from the root through these fixed joints.
    Base(Vec<usize>),
    /// The model link with this index.
    Model(usize),
}

/// Resolves and orders the links and joints of `robot`.
pub(crate) fn build(robot: &Robot) -> Result<Tree, SpecError> {
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
    let (links, reached) = edges.depth_first(robot, root);
    if let Some(unreached) = reached.iter().position(|&r| !r) {
        return Err(edges.cycle_error(robot, unreached));
    }
    if links.is_empty() {
        return Err(tree_error(
            "the URDF has no revolute, continuous or prismatic joint: nothing moves",
        ));
    }
    Ok(Tree { links })
}

/// Index of each link name; rejects duplicates.
fn link_index(robot: &Robot) -> Result<HashMap<&str, usize>, SpecError> {
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
    fn new(robot: &Robot, index: &HashMap<&str, usize>) -> Result<Edges, SpecError> {
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
            let parent = link(&joint.parent.link, "parent")?;
            let child = link(&joint.child.link, "child")?;
            if let Some(first) = edges.parent_joint[child] {
                return Err(error(
                    format!(
                        "link '{}' is already the child of joint '{}': a link with two parents \
                         closes a loop, which a tree cannot model",
                        joint.child.link, robot.joints[first].name
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
    /// The model links in depth-first order from `root`, children in file order, and which
    /// URDF links were reached. Links of the base (reached through fixed joints only) are not
    /// model links; the joints below them start from the root frame.
    fn depth_first(&self, robot: &Robot, root: usize) -> (Vec<TreeLink>, Vec<bool>) {
        let mut links = Vec::new();
        let mut reached = vec![false; robot.links.len()];
        reached[root] = true;
        let mut stack: Vec<(usize, Place)> = self.children[root]
            .iter()
            .rev()
            .map(|&j| (j, Place::Base(Vec::new())))
            .collect();
        while let Some((j, parent)) = stack.pop() {
            let child = self.ends[j].1;
            reached[child] = true;
            let place = match parent {
                Place::Base(mut path) if robot.joints[j].joint_type == JointType::Fixed => {
                    path.push(j);
                    Place::Base(path)
                }
                parent => {
                    let (parent, base_path) = match parent {
                        Place::Base(path) => (None, path),
                        Place::Model(m) => (Some(m), Vec::new()),
                    };
                    links.push(TreeLink {
                        joint: j,
                        link: child,
                        parent,
                        base_path,
                    });
                    Place::Model(links.len() - 1)
                }
            };
            stack.extend(
                self.children[child]
                    .iter()
                    .rev()
                    .map(|&c| (c, place.clone())),
            );
        }
        (links, reached)
    }

    /// The error for a link that the walk from the root did not reach: following parent
    /// joints from `start` ends on a closed loop of joints, which the error names.
    fn cycle_error(&self, robot: &Robot, start: usize) -> SpecError {
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
