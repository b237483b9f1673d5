//! The recursive Newton–Euler algorithm in spatial form (RBDA table 5.1).
//!
//! ```text
//! forward,  i = 1..N:   ᶦX_p = X_J(q_i) X_T
//!                       v_i = ᶦX_p v_p + S_i q̇_i
//!                       a_i = ᶦX_p a_p + S_i q̈_i + v_i ×m S_i q̇_i
//!                       f_i = I_i a_i + v_i ×* I_i v_i
//! backward, i = N..1:   τ_i = S_iᵀ f_i,     f_p += ᶦX_pᵀ f_i
//! ```
//!
//! with `v_0 = 0` and `a_0 = [0; −g]`: gravity enters as an upward acceleration of the world,
//! which adds `−m_i g_i` to every body's force as the thesis's force balance (3.21) does. The
//! forward pass is the thesis's (3.26), (3.30) and (3.34)/(3.35) written for the body origin
//! (with the prismatic terms of docs/design.md §7 included by `S_i = [0; u_i]`); the backward pass
//! is (3.21) and (3.24) with the moment taken about the body origin instead of the COM. Fixed
//! joints are bodies with `S_i = 0` and no torque.
//!
//! A free-flyer root has `S = 1` (RBDA section 4.5, floating bases): its velocity is the base
//! twist, its acceleration `ᶦX_0 a_0 + [ω̇; v̇]` (the time derivative of the body-frame twist,
//! Pinocchio's convention; `v ×m v = 0`), and its generalized force the whole spatial force
//! `f_0` in the base frame. A coupled (mimic) body moves with `q̇_i = m q̇_k` of the variable it
//! follows and passes `m S_iᵀ f_i` to it (the chain rule `τ ← Jᵀ τ`). Armature adds
//! `I_a q̈_i` to the joint's torque.

use nalgebra::{RealField, Vector3, Vector6};

use crate::data::Data;
use crate::model::Model;
use crate::spatial::{force_cross, motion_cross, spatial};

/// Writes `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)` into `tau`; a missing `v` or `a` stands for zero
/// (so `gravity_torques = RNEA(q, 0, 0)` and `bias_torques = RNEA(q, q̇, 0)`). Slices have the
/// model's lengths (checked by the caller).
pub(crate) fn inverse_dynamics<T: RealField + Copy>(
    model: &Model<T>,
    data: &mut Data<T>,
    q: &[T],
    v: Option<&[T]>,
    a: Option<&[T]>,
    tau: &mut [T],
) {
    let world_acceleration = spatial(Vector3::zeros(), -model.gravity);
    motion_pass(model, data, q, v, a, world_acceleration);
    tau.fill(T::zero());
    let layout = &model.layout;
    for (i, body) in model.bodies.iter().enumerate().rev() {
        let f = data.forces[i];
        body.add_generalized_force(layout, &f, tau);
        if let (Some(armature), Some(d), Some(a)) = (body.armature, body.drive, a) {
            let rate = body.rate(layout, a).unwrap_or_else(T::zero);
            tau[layout.v_joint(d.variable)] += d.multiplier * armature * rate;
        }
        if let Some(p) = body.parent {
            data.forces[p] += data.transforms[i].transpose_apply_force(&f);
        }
    }
}

/// The forward pass: every body's transform, spatial velocity, acceleration (the world
/// accelerating at `world_acceleration`) and force `I a + v ×* I v`, into the workspace.
pub(crate) fn motion_pass<T: RealField + Copy>(
    model: &Model<T>,
    data: &mut Data<T>,
    q: &[T],
    v: Option<&[T]>,
    a: Option<&[T]>,
    world_acceleration: Vector6<T>,
) {
    let layout = &model.layout;
    for (i, body) in model.bodies.iter().enumerate() {
        let x = body.transform(layout, q);
        let (parent_v, parent_a) = match body.parent {
            Some(p) => (
                x.apply_motion(&data.velocities[p]),
                x.apply_motion(&data.accelerations[p]),
            ),
            None => (Vector6::zeros(), x.apply_motion(&world_acceleration)),
        };
        let joint_velocity = v.map_or_else(Vector6::zeros, |v| body.joint_motion(layout, v));
        let joint_acceleration = a.map_or_else(Vector6::zeros, |a| body.joint_motion(layout, a));
        let velocity = parent_v + joint_velocity;
        let acceleration = parent_a + joint_acceleration + motion_cross(&velocity, &joint_velocity);
        data.forces[i] = body.inertia.apply(&acceleration)
            + force_cross(&velocity, &body.inertia.apply(&velocity));
        data.transforms[i] = x;
        data.velocities[i] = velocity;
        data.accelerations[i] = acceleration;
    }
}
