//! The coordinates the articulated-body algorithm works in: each link's body frame turned by
//! a constant rotation `Q_i` whose z axis is the joint axis, `Q_i e_z = u_i`.
//!
//! In these frames every joint is a rotation (or translation) about z: its motion subspace
//! selects one column of the articulated inertia (U = I e, D = an entry, no products), and
//! its rotation `Rot_z(q)` has four zeros and a one, so that moving an inertia through it is
//! cheap. Since `Rot(u, q) = Q Rot_z(q) Qᵀ`, a link's placement in its parent becomes
//! `Q_pᵀ E_i Q_i · Rot_z(q_i)` and the attachment `Q_pᵀ t_i`: constants fold. (RBDA §4.4 makes
//! the same choice with its joint models; DH frames are its special case `Q_i = 1`.)
//! A link whose axis is not constant keeps its body frame (`Q_i = 1`, axis `u_i`).
//!
//! The rotation about the axis is free, and it is chosen as Denavit and Hartenberg choose
//! theirs (Craig's modified convention, *Introduction to Robotics* §3.4): a revolute link's x
//! axis lies along the common normal to its first revolute child's axis. The child's
//! placement is then `Rot_x(α) Rot_z(θ)`, and with `θ` moved into the joint,
//! `Rot_x(α) · Rot_z(q + θ)`: one elementary rotation (a one and four zeros) instead of a
//! dense one, at the cost of the angle sum `cos(q + θ)`, `sin(q + θ)` (four products). Its
//! attachment, `Q_pᵀ t_i`, has no component along the common normal's perpendicular `u_p ×
//! x_p` when the axes are parallel. Axes within 10⁻⁹ of parallel but not parallel keep a
//! dense placement, and the frames' origins stay at the joints: moving them to the normals'
//! feet would save about 5 % more on long chains, but the foot of nearly parallel axes' normal
//! lies far out (docs/performance.md, "Forward dynamics by the articulated-body algorithm").

use nalgebra::{Matrix3, Vector3};

use crate::expr::{transpose, ExprGraph, Id, Mat3, Vec3};
use crate::model::{axis_angle_rotation, JointKind, Link};
use crate::motion::{JointMotion, LinkCoordinate, LinkPlacement};

use super::articulated_inertia::{ArticulatedInertia, Spatial};
use super::inertial_parameters::BodyParameters;

/// One link in its joint frame.
pub(super) struct JointFrame {
    /// Placement of the joint frame in the parent's joint frame.
    pub placement: LinkPlacement,
    /// The rigid-body inertia about the origin, in the joint frame.
    pub inertia: ArticulatedInertia,
    /// The motion subspace S (a unit column in the joint frame) and the joint variable.
    pub subspace: Option<(Spatial, usize)>,
}

/// `Q` with `Q e_z = u` for a constant unit axis `u`, as numbers: `1` for `e_z`, else the
/// columns `x = (e × u)/|e × u|` (e the coordinate axis least aligned with u), `y = u × x`,
/// `u`; exact for the coordinate axes.
fn axis_frame(u: Vector3<f64>) -> Matrix3<f64> {
    if u == Vector3::z() {
        return Matrix3::identity();
    }
    let least = u.iamin();
    let x = Vector3::ith(least, 1.0).cross(&u).normalize();
    Matrix3::from_columns(&[x, u.cross(&x), u])
}

/// The numbers of a revolute link's constant geometry: `E_i`, `t_i` and `u_i`.
#[derive(Clone, Copy)]
struct Geometry {
    rotation: Matrix3<f64>,
    translation: Vector3<f64>,
    axis: Vector3<f64>,
}

impl Geometry {
    /// `None` unless the link is revolute and its placement and axis are constants.
    fn of(g: &ExprGraph, link: &Link) -> Option<Geometry> {
        if link.kind != JointKind::Revolute || link.joint.is_none() {
            return None;
        }
        let r = &link.rotation;
        Some(Geometry {
            rotation: Matrix3::from_rows(&[
                numbers(g, &r[0])?.transpose(),
                numbers(g, &r[1])?.transpose(),
                numbers(g, &r[2])?.transpose(),
            ]),
            translation: numbers(g, &link.translation)?,
            axis: numbers(g, &link.axis)?,
        })
    }
}

/// A vector of constants as numbers; `None` unless every entry is a constant.
fn numbers(g: &ExprGraph, v: &Vec3) -> Option<Vector3<f64>> {
    Some(Vector3::new(
        g.as_const(v[0])?,
        g.as_const(v[1])?,
        g.as_const(v[2])?,
    ))
}

/// `v / |v|`, or `None` for a vector too short to give a direction.
fn direction(v: Vector3<f64>) -> Option<Vector3<f64>> {
    v.try_normalize(1e-9)
}

/// The common normal's direction from the axis `u` through the origin to the axis `w`
/// through `t`: `u × w`, or for parallel axes the part of `t` perpendicular to them; `None`
/// when the axes coincide.
fn common_normal(u: Vector3<f64>, w: Vector3<f64>, t: Vector3<f64>) -> Option<Vector3<f64>> {
    direction(u.cross(&w)).or_else(|| direction(t - u * t.dot(&u)))
}

/// `(cos, sin)` with a cosine or sine within rounding of zero made zero and the other ±1,
/// so that a right angle or none folds in the kernels.
fn snapped(cos: f64, sin: f64) -> (f64, f64) {
    const ROUNDING: f64 = 4.0 * f64::EPSILON;
    if sin.abs() <= ROUNDING {
        (cos.signum(), 0.0)
    } else if cos.abs() <= ROUNDING {
        (0.0, sin.signum())
    } else {
        (cos, sin)
    }
}

/// How a link's joint frame sits in its parent's when the parent's x axis is the common
/// normal to the link's axis: `Rot_x(α)` as `(cos α, sin α)`, the angle `θ` that the joint
/// adds to its variable as `(cos θ, sin θ)`, and whether the axes are parallel (the
/// attachment then has no y component).
#[derive(Clone, Copy)]
struct Normal {
    twist: (f64, f64),
    offset: (f64, f64),
    parallel: bool,
}

/// Every link's `Q_i` as numbers (`None` for a link that keeps its body frame) and, for a
/// link whose parent's x axis was chosen along their common normal, how it sits there.
fn frame_rotations(
    g: &ExprGraph,
    links: &[Link],
) -> (Vec<Option<Matrix3<f64>>>, Vec<Option<Normal>>) {
    let geometry: Vec<Option<Geometry>> = links.iter().map(|link| Geometry::of(g, link)).collect();
    // The first revolute child of each revolute link, with their common normal in the
    // parent's body frame.
    let mut normal_to: Vec<Option<(usize, Vector3<f64>, bool)>> = vec![None; links.len()];
    for (i, link) in links.iter().enumerate() {
        let (Some(p), Some(child)) = (link.parent, geometry[i]) else {
            continue;
        };
        let Some(parent) = geometry[p] else { continue };
        if normal_to[p].is_some() {
            continue;
        }
        let w = child.rotation * child.axis;
        if let Some(n) = common_normal(parent.axis, w, child.translation) {
            let parallel = direction(parent.axis.cross(&w)).is_none();
            normal_to[p] = Some((i, n, parallel));
        }
    }
    let frames: Vec<Option<Matrix3<f64>>> = links
        .iter()
        .enumerate()
        .map(|(i, link)| {
            let moving = matches!(link.kind, JointKind::Revolute | JointKind::Prismatic);
            let u = numbers(g, &link.axis)?;
            moving.then(|| match normal_to[i] {
                Some((_, x, _)) => Matrix3::from_columns(&[x, u.cross(&x), u]),
                None => axis_frame(u),
            })
        })
        .collect();
    let normals = links
        .iter()
        .enumerate()
        .map(|(i, link)| {
            let p = link.parent?;
            let (child, _, parallel) = normal_to[p]?;
            if child != i {
                return None;
            }
            let (parent_frame, frame, geometry) = (frames[p]?, frames[i]?, geometry[i]?);
            // F = Q_pᵀ E_i Q_i = Rot_x(α) Rot_z(θ), whose first row is (cos θ, −sin θ, 0)
            // and third column (0, −sin α, cos α).
            let entry = |r: usize, k: usize| {
                parent_frame
                    .column(r)
                    .dot(&(geometry.rotation * frame.column(k)))
            };
            // Zero by construction, to rounding; nearly parallel axes, whose normal is taken
            // as for parallel ones, keep their dense placement.
            if entry(0, 2).abs() > 4.0 * f64::EPSILON {
                return None;
            }
            Some(Normal {
                twist: snapped(entry(2, 2), -entry(1, 2)),
                offset: snapped(entry(0, 0), -entry(0, 1)),
                parallel,
            })
        })
        .collect();
    (frames, normals)
}

/// Every link in its joint frame, for the motion's coordinates; the bodies' inertias are the
/// links' unless `bodies` gives them (one per link).
pub(super) fn joint_frames(
    g: &mut ExprGraph,
    links: &[Link],
    motion: &JointMotion,
    bodies: Option<&[BodyParameters]>,
) -> Vec<JointFrame> {
    let body = LinkPlacement::all(g, links, motion);
    let zero = g.zero();
    let (numbers, normals) = frame_rotations(g, links);
    let frames = rotations(g, links, &numbers);
    let identity = g.identity();
    links
        .iter()
        .enumerate()
        .map(|(i, link)| {
            let (q, axis) = frames[i];
            let parent = link.parent.map_or(identity, |p| frames[p].0);
            let parent_t = transpose(&parent);
            let coordinate = LinkCoordinate::of(g, link, motion);
            let attachment = g.mat_vec(&parent_t, body[i].attachment);
            let (fixed, offset, attachment) =
                fixed_placement(g, link, (&parent_t, &q), attachment, normals[i]);
            let joint = match (link.kind, coordinate) {
                (JointKind::Revolute, Some(c)) => Some(joint_rotation(g, axis, c.q, offset)),
                _ => None,
            };
            let inertia = body_inertia(g, link, &q, bodies.map(|bodies| &bodies[i]));
            let subspace = coordinate.and_then(|c| match link.kind {
                JointKind::Revolute => {
                    Some(([axis[0], axis[1], axis[2], zero, zero, zero], c.variable))
                }
                JointKind::Prismatic => {
                    Some(([zero, zero, zero, axis[0], axis[1], axis[2]], c.variable))
                }
                _ => None,
            });
            JointFrame {
                placement: LinkPlacement {
                    fixed,
                    joint,
                    attachment,
                },
                inertia,
                subspace,
            }
        })
        .collect()
}

/// Each link's `Q_i` as expressions (the identity where `numbers` has none), and its joint
/// axis in the joint frame (e_z, or the link's axis where it keeps its body frame).
fn rotations(
    g: &mut ExprGraph,
    links: &[Link],
    numbers: &[Option<Matrix3<f64>>],
) -> Vec<(Mat3, Vec3)> {
    links
        .iter()
        .zip(numbers)
        .map(|(link, q)| match q {
            Some(q) => (
                std::array::from_fn(|r| std::array::from_fn(|c| g.constant(q[(r, c)]))),
                g.const_vec([0.0, 0.0, 1.0]),
            ),
            None => (g.identity(), link.axis),
        })
        .collect()
}

/// The constant part of a link's placement in its parent's joint frame, `Rot_x(α)` when the
/// parent's x axis is the common normal (`normal`) and `Q_pᵀ E_i Q_i` otherwise, with the
/// angle θ the joint then adds to its variable, and the attachment `Q_pᵀ t_i` (`attachment`)
/// with its y component zero for parallel axes.
fn fixed_placement(
    g: &mut ExprGraph,
    link: &Link,
    (parent_t, q): (&Mat3, &Mat3),
    attachment: Vec3,
    normal: Option<Normal>,
) -> (Mat3, Option<(f64, f64)>, Vec3) {
    let mut attachment = attachment;
    let zero = g.zero();
    match normal {
        Some(normal) => {
            let (c, s) = normal.twist;
            let (one, c, s, minus_s) = (g.one(), g.constant(c), g.constant(s), g.constant(-s));
            if normal.parallel {
                attachment[1] = zero;
            }
            (
                [[one, zero, zero], [zero, c, minus_s], [zero, s, c]],
                Some(normal.offset),
                attachment,
            )
        }
        None => {
            let fixed_in_parent = g.mat_mul(parent_t, &link.rotation);
            (g.mat_mul(&fixed_in_parent, q), None, attachment)
        }
    }
}

/// A revolute joint's rotation `Rot(axis, q + θ)`, θ given as `offset` = (cos θ, sin θ).
fn joint_rotation(g: &mut ExprGraph, axis: Vec3, q: Id, offset: Option<(f64, f64)>) -> Mat3 {
    let (mut cos, mut sin) = (g.cos(q), g.sin(q));
    if let Some((cos_offset, sin_offset)) = offset {
        // cos(q + θ), sin(q + θ).
        let (co, so) = (g.constant(cos_offset), g.constant(sin_offset));
        let (cc, ss) = (g.mul(co, cos), g.mul(so, sin));
        let (sc, cs) = (g.mul(so, cos), g.mul(co, sin));
        (cos, sin) = (g.sub(cc, ss), g.add(sc, cs));
    }
    axis_angle_rotation(g, axis, cos, sin)
}

/// The link's rigid-body inertia about its origin in the joint frame `Q`: the link's own, or
/// `body`'s when given.
fn body_inertia(
    g: &mut ExprGraph,
    link: &Link,
    q: &Mat3,
    body: Option<&BodyParameters>,
) -> ArticulatedInertia {
    let q_t = transpose(q);
    match body {
        Some(body) => {
            let first_moment = g.mat_vec(&q_t, body.first_moment);
            let about = g.similarity(&q_t, &body.inertia);
            ArticulatedInertia::from_origin(g, body.mass, first_moment, &about)
        }
        None => {
            let com = g.mat_vec(&q_t, link.com);
            let inertia = g.similarity(&q_t, &link.inertia);
            ArticulatedInertia::rigid(g, link.mass, com, &inertia)
        }
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Matrix3, Vector3};

    use super::{axis_frame, common_normal, snapped};

    /// The common normal is perpendicular to both axes when they are skew, points from the
    /// first axis to the second when they are parallel, and is missing when they coincide.
    #[test]
    fn common_normals_of_skew_parallel_and_coincident_axes() {
        let s = 1.0 / 2f64.sqrt();
        let v = Vector3::new;
        let skew = common_normal(v(0.0, 0.0, 1.0), v(0.0, s, s), v(0.3, 0.1, 0.2)).unwrap();
        assert_eq!(skew, v(-1.0, 0.0, 0.0));
        let parallel = common_normal(v(0.0, 0.0, 1.0), v(0.0, 0.0, -1.0), v(0.0, 0.4, 0.7));
        assert_eq!(parallel, Some(v(0.0, 1.0, 0.0)));
        assert_eq!(
            common_normal(v(1.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(0.5, 0.0, 0.0)),
            None
        );
    }

    /// Right angles and none fold to exact zeros and ones; other angles are kept.
    #[test]
    fn angles_within_rounding_of_a_right_angle_snap() {
        assert_eq!(snapped(1.0 - f64::EPSILON, 1e-17), (1.0, 0.0));
        assert_eq!(snapped(-6e-17, -1.0), (0.0, -1.0));
        assert_eq!(snapped(0.6, 0.8), (0.6, 0.8));
        assert_eq!(snapped(1.0, 1e-9), (1.0, 1e-9));
    }

    /// Q is a rotation (orthonormal, determinant 1) whose third column is the axis.
    #[test]
    fn axis_frames_are_rotations_taking_z_to_the_axis() {
        let s = 1.0 / 3f64.sqrt();
        for u in [
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.6, 0.0, 0.8],
            [0.36, 0.48, 0.8],
            [s, -s, s],
        ] {
            let u = Vector3::from(u);
            let q = axis_frame(u);
            assert!((q.column(2) - u).amax() < 1e-15, "{u:?}");
            assert!(
                (q.transpose() * q - Matrix3::identity()).amax() < 1e-15,
                "{u:?}: QᵀQ"
            );
            let det = q.determinant();
            assert!((det - 1.0).abs() < 1e-15, "{u:?}: det {det}");
        }
        let exact = axis_frame(Vector3::new(0.0, -1.0, 0.0));
        assert!(
            exact.iter().all(|x| [0.0, 1.0, -1.0].contains(x)),
            "{exact:?}"
        );
    }
}
