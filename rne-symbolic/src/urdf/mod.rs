//! URDF files read into a [`RobotModel`] (DESIGN §2: "URDF files (`.urdf`) are read too").
//!
//! The XML is parsed by `urdf-rs`; this module maps the result onto the model's body frames
//! (see [`crate::model`]) following the URDF specification (<http://wiki.ros.org/urdf/XML>):
//!
//! - a `<joint>` and its `<child>` link make one model [`Link`](crate::Link), named after the
//!   child link; the joint's `name` is its joint variable's name;
//! - `type` revolute or continuous, prismatic, fixed: [`JointKind`](crate::JointKind)
//!   `Revolute`, `Prismatic`, `Fixed`;
//! - the joint's `<origin xyz rpy>`: `t_i = xyz`, `E_i = Rz(yaw) Ry(pitch) Rx(roll)`;
//! - the joint's `<axis xyz>` (default `1 0 0`): `u_i = axis / ‖axis‖`, in the child's frame;
//! - the child's `<inertial>`: mass `<mass>`, COM `<origin xyz>`, and `<inertia>` turned into
//!   the link frame, `R I Rᵀ` with `R = Rz Ry Rx` of `<origin rpy>`.
//!
//! The URDF child link frame is the joint frame, so it is the body frame B_i: a revolute
//! joint rotates it by `E_i Rot(u_i, q)` about `t_i`, a prismatic one moves it to
//! `t_i + E_i u_i q`, exactly the placements of [`crate::model`]. A link without `<inertial>`
//! is massless.
//!
//! # Rules
//!
//! - **Tree.** Exactly one root link (a link that is no joint's child), every other link the
//!   child of exactly one joint; several children per link are fine. Joints are numbered
//!   depth-first from the root, children in file order (DESIGN §2).
//! - **Base.** The root link and the links attached to it through fixed joints only (a `world`
//!   link and the robot's `base_link`, say) never move: they are the base. Their inertials do
//!   not enter the dynamics and they are not model links; their fixed joints' transforms are
//!   composed into the placement of the joints below them.
//! - **Fixed links.** Every other link behind a fixed joint is kept as a
//!   [`JointKind::Fixed`](crate::JointKind) link;
//!   [`SymbolicDynamics`](crate::SymbolicDynamics) merges it exactly into its moving parent
//!   (mass, COM and inertia), while the numeric reference of `rne-models` keeps it as a body of
//!   its own, which checks the merge.
//! - **Names.** A moving joint's name is its joint variable's name, so it must be usable as one
//!   (as a TOML spec's `q`): letters, digits and `_`, not a word of the expression language, not
//!   printed like another joint's velocity, acceleration or force (`D<q>`, `DD<q>`, `tau_<q>`).
//! - **Gravity** is `[0, 0, −9.81]` in the root frame (URDF has none; z up, as ROS).
//! - **Parameters**: a URDF has none, so [`RobotModel::parameters`] is empty and the
//!   `--symbolic-params` / `parameters: runtime` setting changes nothing.
//! - **Validation**, as for a TOML spec: every number finite, mass ≥ 0, an inertia tensor that is
//!   positive semi-definite and, for a link with mass, satisfies the triangle inequality of its
//!   principal moments (within a relative 1e-9); a joint axis must not be zero.
//!
//! # Errors
//!
//! Each error is a [`SpecError`] naming the file, the joint or link, the field and the line of
//! the element; its [`SpecErrorKind`](crate::spec::SpecErrorKind) is
//! - `Urdf` for XML that urdf-rs cannot read, floating, planar and spherical joints, mimic
//!   joints and joint names that cannot name a joint variable;
//! - `Tree` for a joint naming a missing link, a link with two parents (a closed loop), cycles,
//!   several roots, duplicate names, and a URDF in which nothing moves;
//! - `Kinematics` for a zero axis; `Physics` for non-finite or physically impossible numbers.
//!
//! Nothing is approximated or dropped silently.
//!
//! # Not read
//!
//! What does not enter rigid-body dynamics: `<visual>`, `<collision>`, `<material>`, and a
//! joint's `<limit>`, `<dynamics>` (damping, friction), `<safety_controller>` and
//! `<calibration>`; elements outside `<link>` and `<joint>` (`<transmission>`, `<gazebo>`).

mod assemble;
mod document;
mod inertial;
mod joint;
mod locate;
mod tree;

use crate::spec::SpecError;
use crate::RobotModel;

/// Reads a URDF robot from `text`; `origin` names the file in error messages.
pub fn parse_str(text: &str, origin: &str) -> Result<RobotModel, SpecError> {
    read(text, origin).map_err(|e| locate::element(e, text).locate(origin, text))
}

fn read(text: &str, origin: &str) -> Result<RobotModel, SpecError> {
    let robot = document::read(text)?;
    for link in &robot.links {
        inertial::validate(link).map_err(|e| e.in_link(&link.name))?;
    }
    for j in &robot.joints {
        joint::validate(j).map_err(|e| e.in_joint(&j.name))?;
    }
    let tree = tree::build(&robot)?;
    joint::check_variable_names(&robot, &tree)?;
    assemble::model(&robot, &tree, origin)
}
