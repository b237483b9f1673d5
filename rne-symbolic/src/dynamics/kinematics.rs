//! Forward kinematics of frames for control (docs/design.md §4.3): placements in the world,
//! geometric Jacobians and J̇ q̇, with Pinocchio's LOCAL_WORLD_ALIGNED convention: rows [v; ω] of
//! the frame origin, in world axes, so that the task acceleration is J q̈ + J̇ q̇.

use crate::expr::{ExprGraph, Id, Mat3, Vec3};
use crate::model::Frame;

/// A body's pose in the world and the frame carried by it: the frame's orientation and
/// origin in the world.
pub(super) fn frame_pose(
    g: &mut ExprGraph,
    body: Option<(Mat3, Vec3)>,
    frame: &Frame,
) -> (Mat3, Vec3) {
    match body {
        Some((rotation, origin)) => {
            let r = g.mat_mul(&rotation, &frame.rotation);
            let moved = g.mat_vec(&rotation, frame.translation);
            (r, g.vadd(origin, moved))
        }
        None => (frame.rotation, frame.translation),
    }
}

/// The velocity [v; ω] of a frame's origin in world axes, from its body's angular velocity
/// ω_b and origin velocity v_b (body axes) and the body's orientation R:
/// `v = R (v_b + ω_b × r)`, `ω = R ω_b`, with r the frame origin in the body.
pub(super) fn frame_velocity(
    g: &mut ExprGraph,
    rotation: &Mat3,
    (omega, v): (Vec3, Vec3),
    frame: &Frame,
) -> [Id; 6] {
    let transport = g.cross(omega, frame.translation);
    let v_origin = g.vadd(v, transport);
    let linear = g.mat_vec(rotation, v_origin);
    let angular = g.mat_vec(rotation, omega);
    [
        linear[0], linear[1], linear[2], angular[0], angular[1], angular[2],
    ]
}

/// The classical acceleration [a; α] of a frame's origin in world axes, from its body's
/// Newton–Euler motion (ω, α and the classical acceleration a of the body origin, body axes):
/// `a_f = R (a + α × r + ω × (ω × r))`, `α_f = R α`.
pub(super) fn frame_acceleration(
    g: &mut ExprGraph,
    rotation: &Mat3,
    (omega, alpha, accel): (Vec3, Vec3, Vec3),
    frame: &Frame,
) -> [Id; 6] {
    let r = frame.translation;
    let tangential = g.cross(alpha, r);
    let spin = g.cross(omega, r);
    let centripetal = g.cross(omega, spin);
    let a = g.vadd(accel, tangential);
    let a = g.vadd(a, centripetal);
    let linear = g.mat_vec(rotation, a);
    let angular = g.mat_vec(rotation, alpha);
    [
        linear[0], linear[1], linear[2], angular[0], angular[1], angular[2],
    ]
}
