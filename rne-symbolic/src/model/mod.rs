//! The robot model every front end (TOML spec, URDF) produces and every back end consumes.
//!
//! A model is a tree of rigid links. Link `i` carries a *body frame* B_i whose origin lies on
//! the axis of its joint. Its placement relative to the parent's body frame B_p is
//!
//! ```text
//! R_i^p(q) = E_i · Rot(u_i, q_i)      (revolute)     origin of B_i in B_p: t_i
//! R_i^p    = E_i                      (prismatic)    origin of B_i in B_p: t_i + E_i u_i q_i
//! R_i^p    = E_i                      (fixed)        origin of B_i in B_p: t_i
//! ```
//!
//! with a constant rotation `E_i`, a constant attachment point `t_i` and a unit joint axis
//! `u_i` expressed in B_i. In the thesis's frame convention (chapter 3) B_i has the
//! orientation of frame i and the origin of frame i−1, so `u_i = b_i` of (3.27),
//! `t_c = r_{i−1,i}` for every child `c` of link `i`, and the COM of link i in B_i is
//! `r_{i−1,ci}`. Standard DH, modified DH and URDF origins are mapped onto the same form by
//! the spec reader.
//!
//! All geometric and inertial quantities are expressions in the model's [`ExprGraph`], so a
//! parameter is either a folded number or a symbol, as the caller chose when loading.

mod base;
mod frames;
mod geometry;
mod lock;
mod massless;
mod merge;
mod mimic;
mod numeric;

pub use base::{NothingMoves, StateLayout, FREE_FLYER_NQ, FREE_FLYER_NV};
pub use frames::Frame;
pub use geometry::{
    as_coordinate_axis, axis_angle_rotation, elementary_rotation, rotation_about, rpy_rotation,
    Axis, Transform,
};
pub use lock::LockError;
pub use massless::MasslessJoint;
pub use mimic::MimicError;
pub use numeric::{NumericFriction, NumericLink, NumericModel};

use crate::expr::{ExprGraph, Id, Mat3, Symbol, Vec3};
use crate::spec::SpecWarning;

/// The kind of a joint.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum JointKind {
    /// Rotation about the joint axis by q.
    Revolute,
    /// Translation along the joint axis by q.
    Prismatic,
    /// No motion: the link is rigidly attached to its parent.
    Fixed,
    /// A free-flyer: six degrees of freedom relative to the world, only as the root of a model
    /// with a floating base ([`Base::Floating`]). Its configuration is the position and the
    /// unit quaternion `[x, y, z, qx, qy, qz, qw]` of the body frame in the world, its velocity
    /// `[v, ω]` of the body-frame origin in body-frame axes (Pinocchio's conventions).
    FreeFlyer,
}

/// How the model is attached to the world.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Base {
    /// The root is bolted to the world (the thesis's arms).
    #[default]
    Fixed,
    /// The root body moves freely: a free-flyer joint between the world and the root, in front
    /// of the joint variables (docs/design.md §4.5). Legged robots and humanoids.
    Floating,
}

/// A mimic joint as read from the robot file: its coordinate follows another joint's,
/// `q = multiplier · q_leader + offset` (URDF `<mimic>`, TOML `mimic = {..}`).
#[derive(Clone, Debug, PartialEq)]
pub struct Mimic {
    /// The joint variable followed (a URDF joint name, a TOML `q`).
    pub leader: String,
    /// Multiplier (URDF default 1).
    pub multiplier: Id,
    /// Offset, rad or m (URDF default 0).
    pub offset: Id,
}

/// How a link's joint coordinate depends on the joint variable that drives it, once mimic
/// joints are constrained: `q_link = multiplier · q_variable + offset`, so
/// `q̇_link = multiplier · q̇_variable` and the link's generalised force reaches the variable
/// multiplied by `multiplier` (the chain rule: M ← Jᵀ M J, τ ← Jᵀ τ).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Coupling {
    /// ∂q_link / ∂q_variable.
    pub multiplier: Id,
    /// q_link at q_variable = 0.
    pub offset: Id,
}

/// Joint friction `τ_f = viscous · q̇ + coulomb · sign(q̇) + offset` (docs/design.md §2.1).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Friction {
    /// Viscous coefficient f_v (N·m·s/rad or N·s/m); URDF `damping`.
    pub viscous: Id,
    /// Coulomb coefficient f_c (N·m or N); URDF `friction`.
    pub coulomb: Id,
    /// Constant offset (N·m or N).
    pub offset: Id,
}

/// A named model parameter and its value.
#[derive(Clone, Debug, PartialEq)]
pub struct Parameter {
    /// The name used in spec expressions.
    pub name: String,
    /// The value from the spec.
    pub value: f64,
}

/// One rigid link and the joint that connects it to its parent.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// The link's name.
    pub name: String,
    /// Index of the parent link in [`RobotModel::links`]; `None` for a link on the base.
    pub parent: Option<usize>,
    /// Revolute, prismatic, fixed, or the free-flyer of a floating base.
    pub kind: JointKind,
    /// Index of the joint variable in the model's joint order (`None` for fixed joints and the
    /// free-flyer, whose coordinates come before the joint variables).
    pub joint: Option<usize>,
    /// `E_i`: orientation of the joint frame in the parent's body frame.
    pub rotation: Mat3,
    /// `t_i`: position of the joint in the parent's body frame.
    pub translation: Vec3,
    /// `u_i`: unit joint axis in the body frame (unused for fixed joints).
    pub axis: Vec3,
    /// Mass m_i.
    pub mass: Id,
    /// Centre of mass in the body frame (`r_{i−1,ci}` in the thesis's convention).
    pub com: Vec3,
    /// Inertia tensor about the centre of mass, in body-frame axes (I_i of (3.5)).
    pub inertia: Mat3,
    /// The mimic element as read (`None` for an ordinary joint). While the follower keeps
    /// `joint` as its own variable it is free ("mimic: free", Pinocchio's default); once
    /// constrained ([`RobotModel::constrain_mimic_joints`]) `joint` names the leader's
    /// variable and [`Link::coupling`] says how it follows.
    pub mimic: Option<Mimic>,
    /// `q_link = multiplier · q_joint + offset` for a constrained mimic follower; `None` when
    /// the link's coordinate is its variable itself.
    pub coupling: Option<Coupling>,
    /// Joint friction, when the robot file gives it.
    pub friction: Option<Friction>,
    /// Armature: the rotor inertia reflected through the gear (kg·m² or kg), added to M's
    /// diagonal entry of the joint; `None` when the robot file gives none.
    pub armature: Option<Id>,
}

/// A joint variable of the model.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct JointVariable {
    /// Its name (`q` of a TOML link, the joint name of a URDF).
    pub name: String,
    /// The link it moves.
    pub link: usize,
}

/// A robot: a tree of links with expression-valued geometry and inertia.
///
/// Invariants: a link's parent comes before it in `links`; joints are numbered in
/// depth-first order from the root with children in spec order; `joints[k].link` is the link
/// whose `joint` is `Some(k)`.
#[derive(Clone, Debug)]
pub struct RobotModel {
    /// The robot's name.
    pub name: String,
    /// The graph holding every expression of the model (and, later, of its dynamics).
    pub graph: ExprGraph,
    /// The spec's parameters with their values, in spec order (symbol `Parameter(k)` is
    /// `parameters[k]` when parameters are kept symbolic).
    pub parameters: Vec<Parameter>,
    /// Gravitational acceleration in the base frame (g_0 of (4.10)).
    pub gravity: Vec3,
    /// The links, parents first.
    pub links: Vec<Link>,
    /// The joint variables, in joint order.
    pub joints: Vec<JointVariable>,
    /// Fixed to the world, or floating (a free-flyer root link).
    pub base: Base,
    /// What the reader found slightly wrong in the robot file but accepted (docs/design.md §2.4),
    /// in the order found; empty for a model built by hand.
    pub warnings: Vec<SpecWarning>,
}

impl RobotModel {
    /// Number of joint variables.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// Joint variable names in joint order.
    pub fn joint_names(&self) -> Vec<String> {
        self.joints.iter().map(|j| j.name.clone()).collect()
    }

    /// Indices of the children of `link` (or of the base when `None`), in order.
    pub fn children(&self, link: Option<usize>) -> Vec<usize> {
        (0..self.links.len())
            .filter(|&i| self.links[i].parent == link)
            .collect()
    }

    /// The values of the parameter symbols, for evaluating a model loaded with symbolic
    /// parameters; joint symbols are not covered.
    pub fn parameter_value(&self, symbol: Symbol) -> Option<f64> {
        match symbol {
            Symbol::Parameter(k) => self.parameters.get(k as usize).map(|p| p.value),
            _ => None,
        }
    }

    /// Replaces gravity by a constant vector (the macro's `gravity:` scene setting).
    pub fn set_gravity(&mut self, gravity: [f64; 3]) {
        self.gravity = self.graph.const_vec(gravity);
    }
}
