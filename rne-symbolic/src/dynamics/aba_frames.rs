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

use crate::expr::{transpose, ExprGraph, Mat3, Vec3};
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
fn axis_frame(u: [f64; 3]) -> [[f64; 3]; 3] {
    if u == [0.0, 0.0, 1.0] {
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    }
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let least = (0..3)
        .min_by(|&i, &j| u[i].abs().total_cmp(&u[j].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[least] = 1.0;
    let x = cross(e, u);
    let norm = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    let x = x.map(|v| v / norm);
    let y = cross(u, x);
    std::array::from_fn(|i| [x[i], y[i], u[i]])
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
    let constant_axis = |g: &ExprGraph, link: &Link| -> Option<[f64; 3]> {
        let u = [
            g.as_const(link.axis[0])?,
            g.as_const(link.axis[1])?,
            g.as_const(link.axis[2])?,
        ];
        Some(u)
    };
    // Q_i, and the joint axis in the joint frame.
    let frames: Vec<(Mat3, Vec3)> = links
        .iter()
        .map(|link| {
            let moving = matches!(link.kind, JointKind::Revolute | JointKind::Prismatic);
            match constant_axis(g, link).filter(|_| moving) {
                Some(u) => {
                    let q = axis_frame(u).map(|row| row.map(|x| g.constant(x)));
                    (q, g.const_vec([0.0, 0.0, 1.0]))
                }
                None => (g.identity(), link.axis),
            }
        })
        .collect();
    let identity = g.identity();
    links
        .iter()
        .enumerate()
        .map(|(i, link)| {
            let (q, axis) = frames[i];
            let parent = link.parent.map_or(identity, |p| frames[p].0);
            let parent_t = transpose(&parent);
            let fixed_in_parent = g.mat_mul(&parent_t, &link.rotation);
            let fixed = g.mat_mul(&fixed_in_parent, &q);
            let attachment = g.mat_vec(&parent_t, body[i].attachment);
            let coordinate = LinkCoordinate::of(g, link, motion);
            let joint = match (link.kind, coordinate) {
                (JointKind::Revolute, Some(c)) => {
                    let (cos, sin) = (g.cos(c.q), g.sin(c.q));
                    Some(axis_angle_rotation(g, axis, cos, sin))
                }
                _ => None,
            };
            let q_t = transpose(&q);
            let inertia = match bodies {
                Some(bodies) => {
                    let body = &bodies[i];
                    let first_moment = g.mat_vec(&q_t, body.first_moment);
                    let about = g.similarity(&q_t, &body.inertia);
                    ArticulatedInertia::from_origin(g, body.mass, first_moment, &about)
                }
                None => {
                    let com = g.mat_vec(&q_t, link.com);
                    let inertia = g.similarity(&q_t, &link.inertia);
                    ArticulatedInertia::rigid(g, link.mass, com, &inertia)
                }
            };
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

#[cfg(test)]
mod tests {
    use super::axis_frame;

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
            let q = axis_frame(u);
            for i in 0..3 {
                assert!((q[i][2] - u[i]).abs() < 1e-15, "{u:?}");
                for j in 0..3 {
                    let dot: f64 = (0..3).map(|k| q[k][i] * q[k][j]).sum();
                    assert!(
                        (dot - f64::from(u8::from(i == j))).abs() < 1e-15,
                        "{u:?}: QᵀQ"
                    );
                }
            }
            let det = q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1])
                - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0])
                + q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
            assert!((det - 1.0).abs() < 1e-15, "{u:?}: det {det}");
        }
        let exact = axis_frame([0.0, -1.0, 0.0]);
        assert!(
            exact.iter().flatten().all(|x| [0.0, 1.0, -1.0].contains(x)),
            "{exact:?}"
        );
    }
}
