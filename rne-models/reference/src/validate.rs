//! The [`NumericModel`] invariants the algorithms rely on, checked once when a
//! [`Reference`](crate::Reference) is built.

use nalgebra::{Matrix3, Vector3};
use rne_symbolic::model::{Base, NumericLink};
use rne_symbolic::{JointKind, NumericModel};

use crate::error::ReferenceError;

/// How far a joint axis may be from unit length, or a rotation from orthonormal.
const GEOMETRY_TOLERANCE: f64 = 1e-9;

/// Checks that parents come first; that a floating base has exactly one free-flyer, link 0,
/// on the world and a fixed base none; that each moving joint has a joint index below `dof`,
/// every index is moved by some link and no two uncoupled links share one; that fixed joints
/// and the free-flyer have no index and no coupling; that axes are unit vectors, `E_i`
/// rotations and inertias symmetric.
pub(crate) fn validate(model: &NumericModel) -> Result<(), ReferenceError> {
    let dof = model.dof();
    let mut used = vec![false; dof];
    let mut driven = vec![false; dof];
    for (i, link) in model.links.iter().enumerate() {
        let invalid = |field: &'static str, problem: String| ReferenceError::InvalidModel {
            robot: model.name.clone(),
            link: link.name.clone(),
            field,
            problem,
        };
        if let Some(p) = link.parent {
            if p >= i {
                return Err(invalid(
                    "parent",
                    format!("parent index {p} does not come before the link (index {i})"),
                ));
            }
        }
        let free_flyer = link.kind == JointKind::FreeFlyer;
        if free_flyer && (model.base != Base::Floating || i != 0 || link.parent.is_some()) {
            return Err(invalid(
                "kind",
                "a free-flyer must be link 0, on the world, of a floating-base model".into(),
            ));
        }
        if i == 0 && model.base == Base::Floating && !free_flyer {
            return Err(invalid(
                "kind",
                "link 0 of a floating-base model must be the free-flyer".into(),
            ));
        }
        match (link.kind, link.joint) {
            (JointKind::Fixed | JointKind::FreeFlyer, Some(k)) => {
                return Err(invalid(
                    "joint",
                    format!("a {:?} joint has joint index {k}", link.kind),
                ))
            }
            (JointKind::Fixed | JointKind::FreeFlyer, None) => {
                if link.coupling.is_some() {
                    return Err(invalid("coupling", "only a moving joint can follow".into()));
                }
            }
            (_, None) => return Err(invalid("joint", "a moving joint has no joint index".into())),
            (_, Some(k)) => {
                if k >= dof {
                    return Err(invalid(
                        "joint",
                        format!("joint index {k} is not below the number of joints, {dof}"),
                    ));
                }
                driven[k] = true;
                if link.coupling.is_none() && std::mem::replace(&mut used[k], true) {
                    return Err(invalid("joint", format!("joint index {k} is used twice")));
                }
                check_axis(link).map_err(|problem| invalid("axis", problem))?;
            }
        }
        check_inertial(link).map_err(|(field, problem)| invalid(field, problem))?;
    }
    if let Some(k) = driven.iter().position(|&d| !d) {
        return Err(ReferenceError::InvalidModel {
            robot: model.name.clone(),
            link: "joint_names".into(),
            field: "joint",
            problem: format!("no link moves joint {k} (`{}`)", model.joint_names[k]),
        });
    }
    Ok(())
}

fn matrix(rows: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|r, c| rows[r][c])
}

fn check_axis(link: &NumericLink) -> Result<(), String> {
    if (Vector3::from(link.axis).norm() - 1.0).abs() > GEOMETRY_TOLERANCE {
        return Err(format!("u = {:?} is not a unit vector", link.axis));
    }
    Ok(())
}

fn check_inertial(link: &NumericLink) -> Result<(), (&'static str, String)> {
    let rotation = matrix(&link.rotation);
    let orthonormality = (rotation.transpose() * rotation - Matrix3::identity())
        .abs()
        .max();
    if orthonormality > GEOMETRY_TOLERANCE || rotation.determinant() < 0.0 {
        return Err((
            "rotation",
            format!("E = {:?} is not a rotation matrix", link.rotation),
        ));
    }
    let inertia = matrix(&link.inertia);
    let asymmetry = (inertia - inertia.transpose()).abs().max();
    if asymmetry > GEOMETRY_TOLERANCE * inertia.abs().max() {
        return Err(("inertia", format!("{:?} is not symmetric", link.inertia)));
    }
    Ok(())
}
