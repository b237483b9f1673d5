//! The constant part of the reference (Pinocchio's `Model`): one [`Body`] per link of the
//! [`NumericModel`], with its joint, its placement in the parent and its spatial inertia.
//!
//! Fixed joints stay zero-DOF bodies with a constant transform; nothing is merged.

use nalgebra::{Matrix3, Vector3, Vector6};
use rne_symbolic::model::NumericLink;
use rne_symbolic::{JointKind, NumericModel};

use super::error::ReferenceError;
use super::spatial::{spatial, RigidInertia, Transform};

/// How far a joint axis may be from unit length, or a rotation from orthonormal.
const GEOMETRY_TOLERANCE: f64 = 1e-9;

/// The joint that connects a body to its parent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Joint {
    /// Rotation about the axis; the joint variable's index.
    Revolute(usize),
    /// Translation along the axis; the joint variable's index.
    Prismatic(usize),
    /// A rigid attachment.
    Fixed,
}

/// One link's constants.
#[derive(Clone, Debug)]
pub(crate) struct Body {
    /// The parent body (`None`: the base).
    pub parent: Option<usize>,
    /// Its joint.
    pub joint: Joint,
    /// `ᶦX_p` at q = 0: rotation `E_iᵀ`, translation `t_i`.
    rest: Transform,
    /// `u_i×`, for Rodrigues' formula.
    axis_cross: Matrix3<f64>,
    /// `u_i u_iᵀ`, for Rodrigues' formula.
    axis_outer: Matrix3<f64>,
    /// `E_i u_i`, the prismatic axis in the parent frame.
    axis_in_parent: Vector3<f64>,
    /// The joint's motion subspace `S_i` in the body frame: `[u; 0]` (revolute), `[0; u]`
    /// (prismatic), zero (fixed).
    pub motion_subspace: Vector6<f64>,
    /// The spatial inertia about the body origin.
    pub inertia: RigidInertia,
    /// Mass.
    pub mass: f64,
    /// Centre of mass in the body frame.
    pub com: Vector3<f64>,
    /// Inertia about the centre of mass, body axes.
    pub inertia_com: Matrix3<f64>,
}

impl Body {
    /// The joint variable's index, if the joint moves.
    pub fn joint_index(&self) -> Option<usize> {
        match self.joint {
            Joint::Revolute(k) | Joint::Prismatic(k) => Some(k),
            Joint::Fixed => None,
        }
    }

    /// `ᶦX_p(q)`, from the placement `R_i^p = E_i Rot(u_i, q_i)` with origin `t_i` (revolute),
    /// `R_i^p = E_i` with origin `t_i + E_i u_i q_i` (prismatic), or the constant placement.
    /// `Rot(u, q)ᵀ = cos q 1 − sin q u× + (1 − cos q) u uᵀ` (Rodrigues).
    pub fn transform(&self, q: &[f64]) -> Transform {
        match self.joint {
            Joint::Revolute(k) => {
                let (s, c) = q[k].sin_cos();
                let rot_t = Matrix3::from_diagonal_element(c) - self.axis_cross * s
                    + self.axis_outer * (1.0 - c);
                Transform {
                    rotation: rot_t * self.rest.rotation,
                    translation: self.rest.translation,
                }
            }
            Joint::Prismatic(k) => Transform {
                rotation: self.rest.rotation,
                translation: self.rest.translation + self.axis_in_parent * q[k],
            },
            Joint::Fixed => self.rest,
        }
    }
}

/// The reference's constants.
#[derive(Clone, Debug)]
pub(crate) struct Model {
    /// Bodies, parents first (the order of the [`NumericModel`]'s links).
    pub bodies: Vec<Body>,
    /// Gravitational acceleration in the base frame.
    pub gravity: Vector3<f64>,
    /// Joint variable names in joint order.
    pub joint_names: Vec<String>,
}

impl Model {
    /// Checks the [`NumericModel`] invariants the algorithms rely on and builds the bodies:
    /// parents come first; each moving joint has a distinct joint index below `dof` and every
    /// index is used; fixed joints have none; axes are unit vectors; `E_i` is a rotation;
    /// inertias are symmetric.
    pub fn new(model: &NumericModel) -> Result<Model, ReferenceError> {
        let dof = model.dof();
        let mut used = vec![false; dof];
        let mut bodies = Vec::with_capacity(model.links.len());
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
            let joint = match (link.kind, link.joint) {
                (JointKind::Fixed, None) => Joint::Fixed,
                (JointKind::Fixed, Some(k)) => {
                    return Err(invalid(
                        "joint",
                        format!("a fixed joint has joint index {k}"),
                    ))
                }
                (_, None) => {
                    return Err(invalid("joint", "a moving joint has no joint index".into()))
                }
                (kind, Some(k)) => {
                    if k >= dof {
                        return Err(invalid(
                            "joint",
                            format!("joint index {k} is not below the number of joints, {dof}"),
                        ));
                    }
                    if std::mem::replace(&mut used[k], true) {
                        return Err(invalid("joint", format!("joint index {k} is used twice")));
                    }
                    if kind == JointKind::Revolute {
                        Joint::Revolute(k)
                    } else {
                        Joint::Prismatic(k)
                    }
                }
            };
            bodies.push(body(link, joint).map_err(|(field, problem)| invalid(field, problem))?);
        }
        if let Some(k) = used.iter().position(|&u| !u) {
            return Err(ReferenceError::InvalidModel {
                robot: model.name.clone(),
                link: "joint_names".into(),
                field: "joint",
                problem: format!("no link moves joint {k} (`{}`)", model.joint_names[k]),
            });
        }
        Ok(Model {
            bodies,
            gravity: Vector3::from(model.gravity),
            joint_names: model.joint_names.clone(),
        })
    }

    /// Number of joint variables.
    pub fn dof(&self) -> usize {
        self.joint_names.len()
    }
}

fn matrix(rows: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|r, c| rows[r][c])
}

/// Builds one body, or names the field that is wrong and why.
fn body(link: &NumericLink, joint: Joint) -> Result<Body, (&'static str, String)> {
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
    let axis = Vector3::from(link.axis);
    let motion_subspace = match joint {
        Joint::Revolute(_) => spatial(axis, Vector3::zeros()),
        Joint::Prismatic(_) => spatial(Vector3::zeros(), axis),
        Joint::Fixed => Vector6::zeros(),
    };
    if joint != Joint::Fixed && (axis.norm() - 1.0).abs() > GEOMETRY_TOLERANCE {
        return Err(("axis", format!("u = {:?} is not a unit vector", link.axis)));
    }
    let inertia_com = matrix(&link.inertia);
    let asymmetry = (inertia_com - inertia_com.transpose()).abs().max();
    if asymmetry > GEOMETRY_TOLERANCE * inertia_com.abs().max() {
        return Err(("inertia", format!("{:?} is not symmetric", link.inertia)));
    }
    let com = Vector3::from(link.com);
    let translation = Vector3::from(link.translation);
    Ok(Body {
        parent: link.parent,
        joint,
        rest: Transform::from_placement(&rotation, translation),
        axis_cross: axis.cross_matrix(),
        axis_outer: axis * axis.transpose(),
        axis_in_parent: rotation * axis,
        motion_subspace,
        inertia: RigidInertia::from_com(link.mass, com, &inertia_com),
        mass: link.mass,
        com,
        inertia_com,
    })
}
