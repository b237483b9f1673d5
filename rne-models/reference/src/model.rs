//! The constant part of the reference (Pinocchio's `Model`): one [`Body`] per link of the
//! [`NumericModel`], with its joint, its placement in the parent and its spatial inertia,
//! over a scalar `T` (`f64`, or dual numbers for derivatives).
//!
//! Fixed joints stay zero-DOF bodies with a constant transform; nothing is merged. The
//! invariants are checked once, in `f64`, by [`validate`](super::validate).

use nalgebra::{Matrix3, RealField, Vector3, Vector6};
use rne_symbolic::NumericModel;

use crate::configuration::{base_placement, Layout};
use crate::spatial::{spatial, RigidInertia, Transform};

/// The joint that connects a body to its parent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Motion {
    /// Rotation about the axis.
    Revolute,
    /// Translation along the axis.
    Prismatic,
    /// A rigid attachment.
    Fixed,
    /// Six degrees of freedom relative to the world: the root of a floating base.
    FreeFlyer,
}

/// How a revolute or prismatic body's joint coordinate comes from the joint variables:
/// `q_body = multiplier · q[variable] + offset` (multiplier 1 and offset 0 unless the body is a
/// coupled mimic follower).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Drive<T> {
    /// The joint variable's index among the joint variables (not counting the base).
    pub variable: usize,
    /// `∂q_body / ∂q[variable]`.
    pub multiplier: T,
    /// `q_body` at `q[variable] = 0`.
    pub offset: T,
}

/// One link's constants.
#[derive(Clone, Debug)]
pub(crate) struct Body<T: RealField + Copy> {
    /// The parent body (`None`: the world).
    pub parent: Option<usize>,
    /// Its joint.
    pub motion: Motion,
    /// The joint variable moving a revolute or prismatic body.
    pub drive: Option<Drive<T>>,
    /// `ᶦX_p` at q = 0: rotation `E_iᵀ`, translation `t_i`.
    rest: Transform<T>,
    /// `u_i×`, for Rodrigues' formula.
    axis_cross: Matrix3<T>,
    /// `u_i u_iᵀ`, for Rodrigues' formula.
    axis_outer: Matrix3<T>,
    /// `E_i u_i`, the prismatic axis in the parent frame.
    axis_in_parent: Vector3<T>,
    /// The joint's motion subspace `S_i` in the body frame: `[u; 0]` (revolute), `[0; u]`
    /// (prismatic), zero (fixed, and the free-flyer, whose `S` is the identity).
    pub motion_subspace: Vector6<T>,
    /// The spatial inertia about the body origin.
    pub inertia: RigidInertia<T>,
    /// Mass.
    pub mass: T,
    /// Centre of mass in the body frame.
    pub com: Vector3<T>,
    /// Inertia about the centre of mass, body axes.
    pub inertia_com: Matrix3<T>,
    /// Joint friction `[viscous, coulomb, offset]`, if any.
    pub friction: Option<[T; 3]>,
    /// Armature, if any.
    pub armature: Option<T>,
}

impl<T: RealField + Copy> Body<T> {
    /// The body's joint coordinate at the configuration `q`, if it has a revolute or prismatic
    /// joint.
    pub fn coordinate(&self, layout: &Layout, q: &[T]) -> Option<T> {
        self.drive
            .map(|d| d.multiplier * q[layout.q_joint(d.variable)] + d.offset)
    }

    /// The body's joint rate `q̇_body = multiplier · q̇[variable]` (or joint acceleration), if it
    /// has a revolute or prismatic joint.
    pub fn rate(&self, layout: &Layout, v: &[T]) -> Option<T> {
        self.drive
            .map(|d| d.multiplier * v[layout.v_joint(d.variable)])
    }

    /// The joint's contribution to the body's spatial velocity (or acceleration) for the
    /// generalized velocity (or acceleration) `v`: `S_i q̇_body` for a revolute or prismatic
    /// joint, the base twist `[ω; v_lin]` (body frame) for the free-flyer, zero when fixed.
    pub fn joint_motion(&self, layout: &Layout, v: &[T]) -> Vector6<T> {
        match (self.motion, self.rate(layout, v)) {
            (Motion::FreeFlyer, _) => spatial(
                Vector3::new(v[3], v[4], v[5]),
                Vector3::new(v[0], v[1], v[2]),
            ),
            (_, Some(rate)) => self.motion_subspace * rate,
            _ => Vector6::zeros(),
        }
    }

    /// Adds the generalized force of the spatial force `f` (body frame) transmitted by the
    /// joint to `tau`: `multiplier · S_iᵀ f` on the body's joint variable (the chain rule of a
    /// coupling), `[f_lin; n]` on the base's six entries for the free-flyer.
    pub fn add_generalized_force(&self, layout: &Layout, f: &Vector6<T>, tau: &mut [T]) {
        if self.motion == Motion::FreeFlyer {
            for r in 0..6 {
                tau[base_index(r)] += f[r];
            }
        } else if let Some(d) = self.drive {
            tau[layout.v_joint(d.variable)] += d.multiplier * self.motion_subspace.dot(f);
        }
    }

    /// `ᶦX_p(q)`, from the placement `R_i^p = E_i Rot(u_i, q_i)` with origin `t_i` (revolute),
    /// `R_i^p = E_i` with origin `t_i + E_i u_i q_i` (prismatic), the constant placement
    /// (fixed), or the base's placement in the world (free-flyer).
    /// `Rot(u, q)ᵀ = cos q 1 − sin q u× + (1 − cos q) u uᵀ` (Rodrigues).
    pub fn transform(&self, layout: &Layout, q: &[T]) -> Transform<T> {
        match (self.motion, self.coordinate(layout, q)) {
            (Motion::Revolute, Some(angle)) => {
                let (s, c) = angle.sin_cos();
                let rot_t = Matrix3::from_diagonal_element(c) - self.axis_cross * s
                    + self.axis_outer * (T::one() - c);
                Transform {
                    rotation: rot_t * self.rest.rotation,
                    translation: self.rest.translation,
                }
            }
            (Motion::Prismatic, Some(offset)) => Transform {
                rotation: self.rest.rotation,
                translation: self.rest.translation + self.axis_in_parent * offset,
            },
            (Motion::FreeFlyer, _) => {
                let (rotation, position) = base_placement(q);
                Transform::from_placement(&rotation, position)
            }
            _ => self.rest,
        }
    }
}

/// The index in v (or τ) of row `r` of a base spatial vector: spatial vectors put the
/// angular part first, generalized vectors the linear one.
pub(crate) fn base_index(r: usize) -> usize {
    (r + 3) % 6
}

/// The reference's constants.
#[derive(Clone, Debug)]
pub(crate) struct Model<T: RealField + Copy> {
    /// Bodies, parents first (the order of the [`NumericModel`]'s links).
    pub bodies: Vec<Body<T>>,
    /// Gravitational acceleration in the world (base) frame.
    pub gravity: Vector3<T>,
    /// Where the base and the joint variables sit in q and v.
    pub layout: Layout,
    /// Whether some body follows another's joint variable (a mimic coupling), which the ABA
    /// cannot handle.
    pub coupled: bool,
}

impl<T: RealField + Copy> Model<T> {
    /// The bodies of a model that [`validate`](super::validate) accepted, in scalar `T`.
    pub fn from_numeric(model: &NumericModel) -> Model<T> {
        let c = |x: f64| -> T { nalgebra::convert(x) };
        let matrix = |rows: &[[f64; 3]; 3]| Matrix3::from_fn(|r, k| c(rows[r][k]));
        let vector = |v: &[f64; 3]| Vector3::new(c(v[0]), c(v[1]), c(v[2]));
        let bodies = model
            .links
            .iter()
            .map(|link| {
                let motion = match link.kind {
                    rne_symbolic::JointKind::Revolute => Motion::Revolute,
                    rne_symbolic::JointKind::Prismatic => Motion::Prismatic,
                    rne_symbolic::JointKind::Fixed => Motion::Fixed,
                    rne_symbolic::JointKind::FreeFlyer => Motion::FreeFlyer,
                };
                let drive = match motion {
                    Motion::Revolute | Motion::Prismatic => link.joint.map(|variable| {
                        let (multiplier, offset) = link.coupling.unwrap_or((1.0, 0.0));
                        Drive {
                            variable,
                            multiplier: c(multiplier),
                            offset: c(offset),
                        }
                    }),
                    Motion::Fixed | Motion::FreeFlyer => None,
                };
                let rotation = matrix(&link.rotation);
                let axis = vector(&link.axis);
                let motion_subspace = match motion {
                    Motion::Revolute => spatial(axis, Vector3::zeros()),
                    Motion::Prismatic => spatial(Vector3::zeros(), axis),
                    Motion::Fixed | Motion::FreeFlyer => Vector6::zeros(),
                };
                let com = vector(&link.com);
                let inertia_com = matrix(&link.inertia);
                let mass = c(link.mass);
                Body {
                    parent: link.parent,
                    motion,
                    drive,
                    rest: Transform::from_placement(&rotation, vector(&link.translation)),
                    axis_cross: axis.cross_matrix(),
                    axis_outer: axis * axis.transpose(),
                    axis_in_parent: rotation * axis,
                    motion_subspace,
                    inertia: RigidInertia::from_com(mass, com, &inertia_com),
                    mass,
                    com,
                    inertia_com,
                    friction: link
                        .friction
                        .map(|f| [c(f.viscous), c(f.coulomb), c(f.offset)]),
                    armature: link.armature.map(c),
                }
            })
            .collect();
        Model {
            bodies,
            gravity: vector(&model.gravity),
            layout: Layout::of(model),
            coupled: model.links.iter().any(|link| link.coupling.is_some()),
        }
    }
}
