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
//! with `v_0 = 0` and `a_0 = [0; −g]`: gravity enters as an upward acceleration of the base,
//! which adds `−m_i g_i` to every body's force as the thesis's force balance (3.21) does. The
//! forward pass is the thesis's (3.26), (3.30) and (3.34)/(3.35) written for the body origin
//! (with the prismatic terms of DESIGN.md §7 included by `S_i = [0; u_i]`); the backward pass is
//! (3.21) and (3.24) with the moment taken about the body origin instead of the COM. Fixed
//! joints are bodies with `S_i = 0` and no torque.

use nalgebra::{Vector3, Vector6};

use super::data::Data;
use super::model::Model;
use super::spatial::{force_cross, motion_cross, spatial};

/// Writes `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)` into `tau`; a missing `qd` or `qdd` stands for zero
/// (so `gravity_torques = RNEA(q, 0, 0)` and `bias_torques = RNEA(q, q̇, 0)`). Slices have the
/// model's length (checked by the caller).
pub(crate) fn inverse_dynamics(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    qd: Option<&[f64]>,
    qdd: Option<&[f64]>,
    tau: &mut [f64],
) {
    let base_acceleration = spatial(Vector3::zeros(), -model.gravity);
    for (i, body) in model.bodies.iter().enumerate() {
        let x = body.transform(q);
        let (mut v, mut a) = match body.parent {
            Some(p) => (
                x.apply_motion(&data.velocities[p]),
                x.apply_motion(&data.accelerations[p]),
            ),
            None => (Vector6::zeros(), x.apply_motion(&base_acceleration)),
        };
        if let Some(k) = body.joint_index() {
            let s = &body.motion_subspace;
            let joint_velocity = s * qd.map_or(0.0, |qd| qd[k]);
            v += joint_velocity;
            a += s * qdd.map_or(0.0, |qdd| qdd[k]) + motion_cross(&v, &joint_velocity);
        }
        data.forces[i] = body.inertia.apply(&a) + force_cross(&v, &body.inertia.apply(&v));
        data.transforms[i] = x;
        data.velocities[i] = v;
        data.accelerations[i] = a;
    }
    for (i, body) in model.bodies.iter().enumerate().rev() {
        let f = data.forces[i];
        if let Some(k) = body.joint_index() {
            tau[k] = body.motion_subspace.dot(&f);
        }
        if let Some(p) = body.parent {
            data.forces[p] += data.transforms[i].transpose_apply_force(&f);
        }
    }
}
