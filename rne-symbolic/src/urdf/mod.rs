//! URDF files read into a [`RobotModel`] (docs/design.md §2.2: "URDF files are read as robots
//! publish them").
//!
//! The XML is read with quick-xml (`document`), taking only what rigid-body dynamics needs;
//! this module maps it onto the shared input model of [`crate::input`] and the model's body
//! frames (see [`crate::model`]) following the URDF specification
//! (<http://wiki.ros.org/urdf/XML>):
//!
//! - every `<link>` is a model [`Link`](crate::Link): the root as a fixed link at the world's
//!   origin (`parent: None`), every other link together with the `<joint>` whose child it is;
//!   a moving joint's `name` is its joint variable's name;
//! - `type` revolute or continuous, prismatic, fixed: [`JointKind`](crate::JointKind)
//!   `Revolute`, `Prismatic`, `Fixed`;
//! - the joint's `<origin xyz rpy>`: `t_i = xyz`, `E_i = Rz(yaw) Ry(pitch) Rx(roll)`;
//! - the joint's `<axis xyz>` (default `1 0 0`): `u_i = axis / ‖axis‖`, in the child's frame;
//! - `<mimic joint multiplier offset>` (defaults 1 and 0): [`Link::mimic`](crate::Link::mimic),
//!   the follower keeping its own variable until the model's mimic joints are constrained; on a
//!   fixed joint, which has no coordinate, it is ignored (as urdfdom and Pinocchio do);
//! - `<dynamics damping friction>` (defaults 0): [`Link::friction`](crate::Link::friction) with
//!   viscous = damping, Coulomb = friction, offset 0; no `<dynamics>`, no friction;
//! - the child's `<inertial>`: mass `<mass>`, COM `<origin xyz>`, and `<inertia>` turned into
//!   the link frame, `R I Rᵀ` with `R = Rz Ry Rx` of `<origin rpy>`. A link without
//!   `<inertial>` is massless.
//!
//! The URDF child link frame is the joint frame, so it is the body frame B_i: a revolute
//! joint rotates it by `E_i Rot(u_i, q)` about `t_i`, a prismatic one moves it to
//! `t_i + E_i u_i q`, exactly the placements of [`crate::model`].
//!
//! # Rules
//!
//! - **Tree.** Exactly one root link (a link that is no joint's child), every other link the
//!   child of exactly one joint; several children per link are fine. Links are ordered
//!   depth-first from the root, children in file order, and joints numbered in that order
//!   (docs/design.md §2.2).
//! - **Fixed links.** The root and every link behind a fixed joint are kept as
//!   [`JointKind::Fixed`](crate::JointKind) links, so kinematics frames (a tool flange) and a
//!   floating base's body have them;
//!   [`RobotModel::merge_fixed_links`](crate::RobotModel::merge_fixed_links) drops the links
//!   fixed to the world and merges the others exactly into their moving parent for the dynamics.
//! - **Names.** Joint and link names are any string URDF allows (`8`, `FL-hip`, `joint.1`,
//!   unicode) and are kept verbatim in the model and every message.
//! - **Gravity** is `[0, 0, −9.81]` in the root frame (URDF has none; z up, as ROS).
//! - **Parameters**: a URDF has none, so [`RobotModel::parameters`] is empty and the
//!   `--symbolic-params` / `parameters: runtime` setting changes nothing.
//! - **Validation** is the shared one of [`crate::input`]: errors for non-finite numbers,
//!   negative mass, negative damping or friction, a zero axis, a clearly negative principal
//!   moment, a mimic joint that follows a missing joint or loops; warnings for a broken
//!   triangle inequality, a negligible negative principal moment and a massless moving subtree.
//!
//! # Errors
//!
//! Each error is a [`SpecError`] naming the file, the joint or link, the field and the line of
//! the `<joint>` or `<link>` element; its [`SpecErrorKind`](crate::spec::SpecErrorKind) is
//! - `Urdf` for malformed XML, a missing element or attribute the dynamics reads, a malformed
//!   number, an unknown joint type, and floating, planar and spherical joints;
//! - `Tree` for a joint naming a missing link, a link with two parents (a closed loop), cycles,
//!   several roots, duplicate names, and mimic joints whose leader is missing or that follow
//!   each other in a loop;
//! - `Kinematics` for a zero axis; `Physics` for non-finite or physically impossible numbers.
//!
//! A URDF in which no joint moves reads as a model without joint variables: on a floating
//! base it is a 6-DOF rigid body, on a fixed base nothing moves, which
//! [`RobotModel::check_moves`](crate::RobotModel::check_moves) reports once the base is known.
//!
//! # Not read
//!
//! Everything else: `<visual>`, `<collision>`, `<geometry>`, `<material>`, `<texture>`, a
//! joint's `<limit>`, `<safety_controller>` and `<calibration>`, `<transmission>`, `<gazebo>`,
//! sensors, unknown elements and attributes, xacro leftovers (`xacro:` elements and
//! attributes, `${..}` in attributes not read), comments, processing instructions and DOCTYPE.
//! None of it can make a load fail.

mod assemble;
mod document;
mod elements;
mod tree;

use std::collections::HashMap;
use std::ops::Range;

use crate::input::{self, LoadOptions};
use crate::spec::location::Lines;

/// What reading a MuJoCo model (MJCF: a `.xml` file, root element `<mujoco>`) says: rne reads
/// URDF and its own TOML specs only.
pub(crate) const MJCF_UNSUPPORTED: &str =
    "MJCF (a MuJoCo <mujoco> model) is not supported yet: rne reads \
     URDF (.urdf) and its TOML robot specs (.toml); a URDF of the robot (most MuJoCo Menagerie \
     robots have one upstream) can be read instead";
use crate::spec::{SpecError, SpecWarning};
use crate::RobotModel;

use self::elements::UrdfRobot;

/// Reads a URDF robot from `text`; `origin` names the file in error and warning messages.
/// [`LoadOptions::strict`] and [`LoadOptions::free_mimic`] matter: a URDF has no parameters.
pub(crate) fn parse_str(
    text: &str,
    origin: &str,
    options: &LoadOptions,
) -> Result<RobotModel, SpecError> {
    let robot = document::read(text).map_err(|e| e.locate(origin, text))?;
    let mut model = read(&robot, origin, options).map_err(|e| {
        let span = Elements::new(&robot).span(e.joint(), e.link());
        e.at_span(span).locate(origin, text)
    })?;
    let (elements, lines) = (Elements::new(&robot), Lines::new(text));
    model.warnings = std::mem::take(&mut model.warnings)
        .into_iter()
        .map(|w: SpecWarning| {
            let span = elements.span(w.joint(), w.link());
            w.at_span(span).locate_in(origin, &lines)
        })
        .collect();
    input::enforce(model, options.strict)
}

fn read(robot: &UrdfRobot, origin: &str, options: &LoadOptions) -> Result<RobotModel, SpecError> {
    let tree = tree::build(robot)?;
    let input = assemble::input(robot, &tree, origin, options.exact_right_angles)?;
    let options = LoadOptions {
        symbolic_parameters: false,
        ..*options
    };
    input::assemble(input, &options)
}

/// The opening tag of the first `<joint>` and of the first `<link>` of each name: found once
/// for all the findings of a file.
struct Elements<'r> {
    joints: HashMap<&'r str, &'r Range<usize>>,
    links: HashMap<&'r str, &'r Range<usize>>,
}

impl<'r> Elements<'r> {
    fn new(robot: &'r UrdfRobot) -> Elements<'r> {
        let mut joints = HashMap::new();
        for joint in &robot.joints {
            joints.entry(joint.name.as_str()).or_insert(&joint.span);
        }
        let mut links = HashMap::new();
        for link in &robot.links {
            links.entry(link.name.as_str()).or_insert(&link.span);
        }
        Elements { joints, links }
    }

    /// The opening tag of the first `<joint>` named `joint`, else of the first `<link>` named
    /// `link`.
    fn span(&self, joint: Option<&str>, link: Option<&str>) -> Option<Range<usize>> {
        let joint = joint.and_then(|name| self.joints.get(name));
        let link = link.and_then(|name| self.links.get(name));
        joint.or(link).map(|span| (*span).clone())
    }
}
