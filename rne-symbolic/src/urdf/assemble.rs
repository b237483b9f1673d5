//! The links of a URDF tree built into the readers' shared `RobotInput`: each joint's origin
//! and axis mapped by the URDF convention (d) of `input::frames` (`Trans(xyz)·Rz(yaw)Ry(pitch)Rx(roll)`,
//! normalised axis), the child link's inertial moved into its frame, `<mimic>` and
//! `<dynamics>` carried over. The root link is a fixed link at the world's origin; a TOML spec
//! that writes the same robot with `origin` and `axis` (and the root as its first, fixed link)
//! gives the same model graph, node for node.

use std::path::Path;

use super::elements::{Inertial, JointType, UrdfJoint, UrdfLink, UrdfRobot};
use super::tree::{Tree, TreeLink};
use crate::expr::{ExprGraph, Id, Mat3, Symbol, SymbolTable, Vec3};
use crate::input::frames::{self, Motion};
use crate::input::inertia::{from_components, to_body};
use crate::input::{Fields, InputLink, RobotInput, MAX_SYMBOLS};
use crate::model::{
    rpy_rotation, Base, Friction, JointKind, JointVariable, Link, Mimic, Transform,
};
use crate::spec::{SpecError, SpecErrorKind};

/// Gravity in the root frame: URDF has none; z points up, as in ROS (and the TOML default).
const GRAVITY: [f64; 3] = [0.0, 0.0, -9.81];

/// Where the parts of a URDF link come from, for messages.
const FIELDS: Fields = Fields {
    rotation: "origin.rpy",
    translation: "origin.xyz",
    axis: "axis",
    mass: "inertial.mass",
    com: "inertial.origin.xyz",
    inertia: "inertial.inertia",
    mimic: "mimic.joint",
    mimic_multiplier: "mimic.multiplier",
    mimic_offset: "mimic.offset",
    viscous: "dynamics.damping",
    coulomb: "dynamics.friction",
    friction_offset: "dynamics",
};

/// Builds the input of `robot` whose links `tree` ordered; `origin` (the file) names a robot
/// whose `<robot>` has no name.
pub(crate) fn input(
    robot: &UrdfRobot,
    tree: &Tree,
    origin: &str,
    exact_right_angles: bool,
) -> Result<RobotInput, SpecError> {
    // The kind of each model link and the index of its joint variable.
    let mut motions: Vec<(JointKind, Option<usize>)> = Vec::with_capacity(tree.links.len());
    let mut joints = Vec::new();
    for (m, link) in tree.links.iter().enumerate() {
        let kind = match link.joint.map(|j| &robot.joints[j]) {
            None => JointKind::Fixed,
            Some(joint) => kind(joint).map_err(|e| e.in_joint(&joint.name))?,
        };
        let variable = (kind != JointKind::Fixed).then_some(joints.len());
        if let (Some(_), Some(joint)) = (variable, link.joint) {
            joints.push(JointVariable {
                name: robot.joints[joint].name.clone(),
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
    let mut graph = ExprGraph::new(SymbolTable::with_joints(names));
    graph.set_exact_right_angles(exact_right_angles);
    let gravity = graph.const_vec(GRAVITY);
    let links = tree
        .links
        .iter()
        .zip(motions)
        .map(|(link, (kind, variable))| input_link(&mut graph, robot, link, kind, variable))
        .collect::<Result<Vec<InputLink>, SpecError>>()?;
    Ok(RobotInput {
        name: robot_name(robot, origin),
        graph,
        parameters: Vec::new(),
        gravity,
        links,
        joints,
        base: Base::Fixed,
    })
}

/// The model's joint kind of a URDF joint type: continuous is revolute without limits.
/// Floating, planar and spherical joints have more than one variable.
fn kind(joint: &UrdfJoint) -> Result<JointKind, SpecError> {
    let unsupported = match joint.joint_type {
        JointType::Revolute | JointType::Continuous => return Ok(JointKind::Revolute),
        JointType::Prismatic => return Ok(JointKind::Prismatic),
        JointType::Fixed => return Ok(JointKind::Fixed),
        JointType::Floating => "floating",
        JointType::Planar => "planar",
        JointType::Spherical => "spherical",
    };
    Err(SpecError::new(
        SpecErrorKind::Urdf,
        format!(
            "{unsupported} joints are not supported: every joint must be revolute, continuous, \
             prismatic or fixed"
        ),
    )
    .at_field("type"))
}

/// One model link: placed by its joint's origin (the root at the world's origin), moving about
/// or along the joint's normalised axis, with the link's inertial.
fn input_link(
    g: &mut ExprGraph,
    robot: &UrdfRobot,
    link: &TreeLink,
    kind: JointKind,
    variable: Option<usize>,
) -> Result<InputLink, SpecError> {
    let joint = link.joint.map(|j| &robot.joints[j]);
    let motion = match (kind, variable) {
        (JointKind::Revolute, Some(k)) => Motion::Revolute(Symbol::Position(k as u16)),
        (JointKind::Prismatic, Some(k)) => Motion::Prismatic(Symbol::Position(k as u16)),
        _ => Motion::Fixed,
    };
    let (xyz, rpy, axis) = joint.map_or(([0.0; 3], [0.0; 3], [1.0, 0.0, 0.0]), |j| {
        (j.xyz, j.rpy, j.axis)
    });
    let xyz = g.const_vec(xyz);
    let rpy = g.const_vec(rpy);
    let axis = g.const_vec(axis);
    let frames = frames::urdf(g, motion, xyz, rpy, axis).map_err(|e| match joint {
        Some(j) => e.in_joint(&j.name),
        None => e,
    })?;
    let child = &robot.links[link.link];
    let (mass, com, inertia) = in_link_frame(g, child);
    // A fixed joint has no coordinate: its `<mimic>` says nothing about the motion and is
    // ignored, as Pinocchio and urdfdom do (Talos's grippers carry such elements).
    let mimic = joint
        .filter(|_| kind != JointKind::Fixed)
        .and_then(|j| j.mimic.as_ref())
        .map(|m| Mimic {
            leader: m.joint.clone(),
            multiplier: g.constant(m.multiplier),
            offset: g.constant(m.offset),
        });
    let friction = joint.and_then(|j| j.dynamics).map(|d| Friction {
        viscous: g.constant(d.damping),
        coulomb: g.constant(d.friction),
        offset: g.zero(),
    });
    Ok(InputLink {
        link: Link {
            name: child.name.clone(),
            parent: link.parent,
            kind,
            joint: variable,
            rotation: frames.pre.rotation,
            translation: frames.pre.translation,
            axis: frames.axis,
            mass,
            com,
            inertia,
            mimic,
            coupling: None,
            friction,
            armature: None,
        },
        joint_element: joint.map(|j| j.name.clone()),
        frames,
        fields: FIELDS,
        declared_inertia: None,
        box_edges: None,
        triangle_inequality: true,
    })
}

/// Mass, COM and inertia about the COM of `link` in its own frame, as constants of `g`: the
/// `<inertial>` places an inertial frame by its `<origin xyz rpy>` in the link frame, so the COM
/// is `xyz` and the tensor `R I Rᵀ` with `R = Rz(yaw) Ry(pitch) Rx(roll)` ((3.5)–(3.6)). A link
/// without `<inertial>` is massless: it is read as an inertial of zeros.
fn in_link_frame(g: &mut ExprGraph, link: &UrdfLink) -> (Id, Vec3, Mat3) {
    let massless = Inertial {
        xyz: [0.0; 3],
        rpy: [0.0; 3],
        mass: 0.0,
        inertia: [[0.0; 3]; 3],
    };
    let inertial = link.inertial.as_ref().unwrap_or(&massless);
    let mass = g.constant(inertial.mass);
    let xyz = g.const_vec(inertial.xyz);
    let rpy = g.const_vec(inertial.rpy);
    let place = Transform::translation(g, xyz);
    let rotation = rpy_rotation(g, rpy);
    let orient = Transform::rotation(g, rotation);
    let frame = place.then(g, &orient);
    let i = &inertial.inertia;
    let diagonal = g.const_vec([i[0][0], i[1][1], i[2][2]]);
    let products = g.const_vec([i[0][1], i[0][2], i[1][2]]);
    let at_com = g.zero_vec();
    let (com, inertia) = to_body(g, &frame, at_com, &from_components(diagonal, products));
    (mass, com, inertia)
}

/// The `<robot name>`, or the file's stem when it is absent or empty.
fn robot_name(robot: &UrdfRobot, origin: &str) -> String {
    if let Some(name) = robot.name.as_ref().filter(|n| !n.is_empty()) {
        return name.clone();
    }
    Path::new(origin)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("robot")
        .to_owned()
}
