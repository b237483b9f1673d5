//! The articulated-body algorithm (RBDA table 7.1): forward dynamics
//! `q̈ = M(q)⁻¹ (τ − C(q, q̇) q̇ − g(q))` in O(N), without forming M — the thesis's (6.2).
//!
//! ```text
//! forward,  i = 1..N:  v_i = ᶦX_p v_p + S_i q̇_i,   c_i = v_i ×m S_i q̇_i
//!                      I_i^A = I_i,                 p_i^A = v_i ×* I_i v_i
//! backward, i = N..1:  U_i = I_i^A S_i,   D_i = S_iᵀ U_i,   u_i = τ_i − S_iᵀ p_i^A
//!                      I^a = I_i^A − U_i D_i⁻¹ U_iᵀ
//!                      p^a = p_i^A + I^a c_i + U_i D_i⁻¹ u_i
//!                      I_p^A += ᶦX_pᵀ I^a ᶦX_p,     p_p^A += ᶦX_pᵀ p^a
//! forward,  i = 1..N:  a' = ᶦX_p a_p + c_i          (a_0 = [0; −g])
//!                      q̈_i = (u_i − U_iᵀ a') / D_i,  a_i = a' + S_i q̈_i
//! ```
//!
//! A fixed body has no joint to absorb anything: its whole articulated inertia and bias force
//! (`c_i = 0`) pass to the parent, and `a_i = ᶦX_p a_p`.

use nalgebra::{Vector3, Vector6};

use super::data::Data;
use super::model::Model;
use super::spatial::{force_cross, motion_cross, spatial};

/// Writes q̈ into `qdd`. A singular articulated inertia (`D_i = 0`: a joint that moves no mass
/// or inertia) gives non-finite entries. Slices have the model's length (checked by the caller).
pub(crate) fn forward_dynamics(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    qd: &[f64],
    tau: &[f64],
    qdd: &mut [f64],
) {
    for (i, body) in model.bodies.iter().enumerate() {
        let x = body.transform(q);
        let mut v = match body.parent {
            Some(p) => x.apply_motion(&data.velocities[p]),
            None => Vector6::zeros(),
        };
        data.velocity_products[i] = match body.joint_index() {
            Some(k) => {
                let joint_velocity = body.motion_subspace * qd[k];
                v += joint_velocity;
                motion_cross(&v, &joint_velocity)
            }
            None => Vector6::zeros(),
        };
        data.articulated[i] = body.inertia.to_matrix();
        data.forces[i] = force_cross(&v, &body.inertia.apply(&v));
        data.transforms[i] = x;
        data.velocities[i] = v;
    }
    for (i, body) in model.bodies.iter().enumerate().rev() {
        let (inertia, bias) = match body.joint_index() {
            Some(k) => {
                let s = &body.motion_subspace;
                let u_vector = data.articulated[i] * s;
                let d = s.dot(&u_vector);
                let u = tau[k] - s.dot(&data.forces[i]);
                data.u_vectors[i] = u_vector;
                data.d[i] = d;
                data.u[i] = u;
                let inertia = data.articulated[i] - u_vector * (u_vector.transpose() / d);
                let bias =
                    data.forces[i] + inertia * data.velocity_products[i] + u_vector * (u / d);
                (inertia, bias)
            }
            None => (data.articulated[i], data.forces[i]),
        };
        if let Some(p) = body.parent {
            let x = &data.transforms[i];
            data.articulated[p] += x.transpose_apply_matrix(&inertia);
            data.forces[p] += x.transpose_apply_force(&bias);
        }
    }
    let base_acceleration = spatial(Vector3::zeros(), -model.gravity);
    for (i, body) in model.bodies.iter().enumerate() {
        let parent_acceleration = match body.parent {
            Some(p) => &data.accelerations[p],
            None => &base_acceleration,
        };
        let mut a =
            data.transforms[i].apply_motion(parent_acceleration) + data.velocity_products[i];
        if let Some(k) = body.joint_index() {
            let acceleration = (data.u[i] - data.u_vectors[i].dot(&a)) / data.d[i];
            a += body.motion_subspace * acceleration;
            qdd[k] = acceleration;
        }
        data.accelerations[i] = a;
    }
}
