//! A URDF `<joint>`: its type mapped onto a [`JointKind`], its numbers checked, and the joint
//! variable names it gives.

use std::collections::HashSet;

use urdf_rs::{Joint, JointType, Robot};

use super::tree::Tree;
use crate::model::JointKind;
use crate::spec::tree::{printed_forms, unusable_variable_name};
use crate::spec::validate::finite;
use crate::spec::{SpecError, SpecErrorKind};

/// The model's joint kind of a supported URDF joint type: continuous is revolute without
/// limits. Floating, planar and spherical joints have more than one variable.
pub(crate) fn kind(joint: &Joint) -> Result<JointKind, SpecError> {
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

/// Checks what a joint says about itself: a supported type, no `<mimic>` (a mimic joint's
/// variable is not free, which the model cannot express), finite `<origin>` numbers and, for a
/// moving joint, a finite, non-zero `<axis>`. The caller names the joint.
pub(crate) fn validate(joint: &Joint) -> Result<(), SpecError> {
    let kind = kind(joint)?;
    if let Some(mimic) = &joint.mimic {
        return Err(SpecError::new(
            SpecErrorKind::Urdf,
            format!(
                "mimic joints are not supported: this joint follows '{}', but every moving joint \
                 must have a free variable of its own",
                mimic.joint
            ),
        )
        .at_field("mimic"));
    }
    finite(&joint.origin.xyz.0, "origin.xyz")?;
    finite(&joint.origin.rpy.0, "origin.rpy")?;
    if kind != JointKind::Fixed {
        let axis = joint.axis.xyz.0;
        finite(&axis, "axis")?;
        if axis.iter().all(|&a| a == 0.0) {
            return Err(
                SpecError::new(SpecErrorKind::Kinematics, "axis must not be zero").at_field("axis"),
            );
        }
    }
    Ok(())
}

/// Checks the names of the moving joints, in joint order, as joint variable names: usable as
/// names, and none printed like another's velocity, acceleration or force.
pub(crate) fn check_variable_names(robot: &Robot, tree: &Tree) -> Result<(), SpecError> {
    let moving: Vec<&Joint> = tree
        .links
        .iter()
        .filter_map(|l| robot.joints.get(l.joint))
        .filter(|j| !matches!(j.joint_type, JointType::Fixed))
        .collect();
    let names: HashSet<&str> = moving.iter().map(|j| j.name.as_str()).collect();
    for joint in &moving {
        let error = |kind: SpecErrorKind, message: String| {
            SpecError::new(kind, message)
                .at_field("name")
                .in_joint(&joint.name)
        };
        if let Some(problem) = unusable_variable_name(&joint.name) {
            return Err(error(SpecErrorKind::Urdf, problem));
        }
        for (what, printed) in printed_forms(&joint.name) {
            if names.contains(printed.as_str()) {
                return Err(error(
                    SpecErrorKind::Tree,
                    format!(
                        "joint variable '{}' clashes with the joint variable '{printed}': its \
                         {what} is printed '{printed}'",
                        joint.name
                    ),
                ));
            }
        }
    }
    Ok(())
}
