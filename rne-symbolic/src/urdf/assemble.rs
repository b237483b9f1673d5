//! The model links of a URDF tree built into a [`RobotModel`]: each joint's origin and axis
//! mapped by the URDF convention (d) of the TOML reader (`Trans(xyz)·Rz(yaw)Ry(pitch)Rx(roll)`,
//! normalised axis), the child link's inertial moved into its frame, and the result copied into
//! the model's graph as the TOML reader copies its own; so a URDF and the same robot written as
//! a TOML spec with `origin` and `axis` give the same model graph, node for node.

use std::path::Path;

use urdf_rs::{Joint, Robot};

use super::inertial;
use super::joint;
use super::tree::{Tree, TreeLink};
use crate::expr::{ExprGraph, Symbol, SymbolTable};
use crate::model::{JointKind, JointVariable, Link, Transform};
use crate::spec::frames::{self, Motion};
use crate::spec::tree::MAX_SYMBOLS;
use crate::spec::{copy_model, SpecError, SpecErrorKind};
use crate::RobotModel;

/// Gravity in the root frame: URDF has none; z points up, as in ROS (and the TOML default).
const GRAVITY: [f64; 3] = [0.0, 0.0, -9.81];

/// Builds the model of `robot` whose links `tree` ordered; `origin` (the file) names a robot
/// whose `<robot>` has no name.
pub(crate) fn model(robot: &Robot, tree: &Tree, origin: &str) -> Result<RobotModel, SpecError> {
    // The kind of each model link and the index of its joint variable.
    let mut motions: Vec<(JointKind, Option<usize>)> = Vec::with_capacity(tree.links.len());
    let mut joints = Vec::new();
    for (m, link) in tree.links.iter().enumerate() {
        let urdf_joint = &robot.joints[link.joint];
        let kind = joint::kind(urdf_joint).map_err(|e| e.in_joint(&urdf_joint.name))?;
        let variable = (kind != JointKind::Fixed).then_some(joints.len());
        if variable.is_some() {
            joints.push(JointVariable {
                name: urdf_joint.name.clone(),
                link: m,
            });
        }
        motions.push((kind, variable));
    }
    if joints.len() > MAX_SYMBOLS {
        return Err(SpecError::new(
            SpecErrorKind::Tree,
            format!("more than {MAX_SYMBOLS} moving joints"),
        ));
    }
    let names: Vec<String> = joints.iter().map(|j| j.name.clone()).collect();
    let mut scratch = ExprGraph::new(SymbolTable::with_joints(names.clone()));
    let links = tree
        .links
        .iter()
        .zip(motions)
        .map(|(link, (kind, variable))| model_link(&mut scratch, robot, link, kind, variable))
        .collect::<Result<Vec<Link>, SpecError>>()?;
    let gravity = scratch.const_vec(GRAVITY);
    // Copied as the TOML reader copies its model, so that the same robot gives the same graph.
    let graph = ExprGraph::new(SymbolTable::with_joints(names));
    let (graph, gravity, links) = copy_model(
        &scratch,
        graph,
        |g: &mut ExprGraph, s| g.symbol(s),
        gravity,
        links,
    );
    Ok(RobotModel {
        name: robot_name(robot, origin),
        graph,
        parameters: Vec::new(),
        gravity,
        links,
        joints,
        base: crate::model::Base::Fixed,
    })
}

/// One model link: placed by its joint's origin (after the base's fixed joints, for a joint on
/// the base), moving about or along the joint's normalised axis, with the child's inertial.
fn model_link(
    g: &mut ExprGraph,
    robot: &Robot,
    link: &TreeLink,
    kind: JointKind,
    variable: Option<usize>,
) -> Result<Link, SpecError> {
    let urdf_joint = &robot.joints[link.joint];
    let motion = match (kind, variable) {
        (JointKind::Revolute, Some(k)) => Motion::Revolute(Symbol::Position(k as u16)),
        (JointKind::Prismatic, Some(k)) => Motion::Prismatic(Symbol::Position(k as u16)),
        _ => Motion::Fixed,
    };
    let mut placement = Transform::identity(g);
    for &fixed in &link.base_path {
        let origin = origin_frames(g, &robot.joints[fixed], Motion::Fixed)?;
        placement = placement.then(g, &origin.pre);
    }
    let frames = origin_frames(g, urdf_joint, motion)?;
    let placement = placement.then(g, &frames.pre);
    let child = &robot.links[link.link];
    let (mass, com, inertia) = inertial::in_link_frame(g, child);
    Ok(Link {
        name: child.name.clone(),
        parent: link.parent,
        kind,
        joint: variable,
        rotation: placement.rotation,
        translation: placement.translation,
        axis: frames.axis,
        mass,
        com,
        inertia,
        mimic: None,
        coupling: None,
        friction: None,
        armature: None,
    })
}

/// The joint's `<origin>` and `<axis>` in convention (d) of the TOML reader.
fn origin_frames(
    g: &mut ExprGraph,
    joint: &Joint,
    motion: Motion,
) -> Result<frames::JointFrames, SpecError> {
    let xyz = g.const_vec(joint.origin.xyz.0);
    let rpy = g.const_vec(joint.origin.rpy.0);
    let axis = g.const_vec(joint.axis.xyz.0);
    frames::urdf(g, motion, xyz, rpy, axis).map_err(|e| e.in_joint(&joint.name))
}

/// The `<robot name>`, or the file's stem when it is empty.
fn robot_name(robot: &Robot, origin: &str) -> String {
    if !robot.name.is_empty() {
        return robot.name.clone();
    }
    Path::new(origin)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("robot")
        .to_owned()
}
