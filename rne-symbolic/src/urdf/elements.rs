//! The part of a URDF the dynamics reads, as plain data with the byte range of each `<link>`
//! and `<joint>` element (for the line of a message).

use std::ops::Range;

/// `<robot>`: its links and joints in file order.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct UrdfRobot {
    /// The `name` attribute (`None` when absent).
    pub(crate) name: Option<String>,
    pub(crate) links: Vec<UrdfLink>,
    pub(crate) joints: Vec<UrdfJoint>,
}

/// `<link name>` and its `<inertial>`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct UrdfLink {
    pub(crate) name: String,
    /// The opening tag.
    pub(crate) span: Range<usize>,
    /// `None` for a link without `<inertial>`: massless.
    pub(crate) inertial: Option<Inertial>,
}

/// `<inertial>`: `<origin xyz rpy>` of the inertial frame in the link frame, `<mass value>`,
/// `<inertia ixx ixy ixz iyy iyz izz>` about the COM in the inertial frame's axes.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Inertial {
    pub(crate) xyz: [f64; 3],
    pub(crate) rpy: [f64; 3],
    pub(crate) mass: f64,
    /// `[[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]`.
    pub(crate) inertia: [[f64; 3]; 3],
}

/// The `type` of a `<joint>`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum JointType {
    Revolute,
    Continuous,
    Prismatic,
    Fixed,
    Floating,
    Planar,
    Spherical,
}

impl JointType {
    /// The type named `name`, as URDF spells it.
    pub(crate) fn from_name(name: &str) -> Option<JointType> {
        Some(match name {
            "revolute" => JointType::Revolute,
            "continuous" => JointType::Continuous,
            "prismatic" => JointType::Prismatic,
            "fixed" => JointType::Fixed,
            "floating" => JointType::Floating,
            "planar" => JointType::Planar,
            "spherical" => JointType::Spherical,
            _ => return None,
        })
    }
}

/// `<joint name type>` with what the dynamics reads of it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct UrdfJoint {
    pub(crate) name: String,
    /// The opening tag.
    pub(crate) span: Range<usize>,
    pub(crate) joint_type: JointType,
    /// `<parent link>`.
    pub(crate) parent: String,
    /// `<child link>`.
    pub(crate) child: String,
    /// `<origin xyz>` (default zero).
    pub(crate) xyz: [f64; 3],
    /// `<origin rpy>` (default zero).
    pub(crate) rpy: [f64; 3],
    /// `<axis xyz>` (default `1 0 0`).
    pub(crate) axis: [f64; 3],
    /// `<mimic joint multiplier offset>`.
    pub(crate) mimic: Option<UrdfMimic>,
    /// `<dynamics damping friction>`.
    pub(crate) dynamics: Option<Dynamics>,
}

/// `<mimic>`: `q = multiplier · q_joint + offset`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct UrdfMimic {
    pub(crate) joint: String,
    /// Default 1.
    pub(crate) multiplier: f64,
    /// Default 0.
    pub(crate) offset: f64,
}

/// `<dynamics>`: viscous (`damping`) and Coulomb (`friction`) coefficients, default 0.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct Dynamics {
    pub(crate) damping: f64,
    pub(crate) friction: f64,
}
