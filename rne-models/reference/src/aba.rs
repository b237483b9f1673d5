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
//! (`c_i = 0`) pass to the parent, and `a_i = ᶦX_p a_p`. Armature adds to `D_i` (as
//! Pinocchio's ABA does). A free-flyer root (RBDA section 7.3, floating bases) keeps its whole
//! articulated inertia: its acceleration solves the 6×6 system `I_0^A a_0 = f_0 − p_0^A`, with
//! `f_0` the base's generalized force as a spatial force, and the base's generalized
//! acceleration is `a_0 − ⁰X_world a_world`.
//!
//! The ABA assumes one body per joint variable, so a model with couplings (mimic joints) is
//! solved instead from `M(q) q̈ = τ − (C q̇ + g)` with M by the CRBA, the bias by the RNEA and a
//! Cholesky factorisation (Pinocchio's ABA has no mimic joints either).

use nalgebra::{RealField, Vector3, Vector6};

use crate::cholesky;
use crate::data::Data;
use crate::model::{base_index, Model, Motion};
use crate::spatial::{force_cross, spatial};
use crate::{crba, friction, rnea};

/// Writes q̈ into `qdd` for the generalized forces `tau`, less the joint friction when
/// `friction` is set. A singular M (a joint that moves no mass or inertia) gives non-finite entries.
/// Slices have the model's lengths (checked by the caller).
pub(crate) fn forward_dynamics<T: RealField + Copy>(
    model: &Model<T>,
    data: &mut Data<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    friction: bool,
    qdd: &mut [T],
) {
    if model.coupled {
        solve_mass_matrix(model, data, q, v, tau, friction, qdd);
    } else {
        articulated_body(model, data, q, v, tau, friction, qdd);
    }
}

/// `q̈ = M⁻¹ (τ − bias)` by Cholesky, for coupled models.
fn solve_mass_matrix<T: RealField + Copy>(
    model: &Model<T>,
    data: &mut Data<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    friction: bool,
    qdd: &mut [T],
) {
    let n = model.layout.nv();
    let mut mass_matrix = std::mem::take(&mut data.mass_matrix);
    let mut bias = std::mem::take(&mut data.generalized);
    crba::mass_matrix(model, data, q, &mut mass_matrix);
    rnea::inverse_dynamics(model, data, q, Some(v), None, &mut bias);
    if friction {
        friction::add_friction_torques(model, v, &mut bias);
    }
    for ((out, t), b) in qdd.iter_mut().zip(tau).zip(&bias) {
        *out = *t - *b;
    }
    if cholesky::factorize(&mut mass_matrix, n) {
        cholesky::solve(&mass_matrix, n, qdd);
    } else {
        qdd.fill(nalgebra::convert(f64::NAN));
    }
    data.mass_matrix = mass_matrix;
    data.generalized = bias;
}

/// The ABA proper, for models with one body per joint variable.
fn articulated_body<T: RealField + Copy>(
    model: &Model<T>,
    data: &mut Data<T>,
    q: &[T],
    v: &[T],
    tau: &[T],
    friction: bool,
    qdd: &mut [T],
) {
    velocity_pass(model, data, q, v);
    articulated_pass(model, data, v, tau, friction);
    acceleration_pass(model, data, tau, qdd);
}

/// The first forward pass: each body's transform from its parent, velocity v_i, velocity
/// product c_i, rigid inertia as I_i^A and bias force p_i^A = v_i ×* I_i v_i.
fn velocity_pass<T: RealField + Copy>(model: &Model<T>, data: &mut Data<T>, q: &[T], v: &[T]) {
    let layout = &model.layout;
    for (i, body) in model.bodies.iter().enumerate() {
        let x = body.transform(layout, q);
        let parent_v = match body.parent {
            Some(p) => x.apply_motion(&data.velocities[p]),
            None => Vector6::zeros(),
        };
        let joint_velocity = body.joint_motion(layout, v);
        let velocity = parent_v + joint_velocity;
        data.velocity_products[i] = crate::spatial::motion_cross(&velocity, &joint_velocity);
        data.articulated[i] = body.inertia.to_matrix();
        data.forces[i] = force_cross(&velocity, &body.inertia.apply(&velocity));
        data.transforms[i] = x;
        data.velocities[i] = velocity;
    }
}

/// The backward pass: U_i, D_i (armature included) and u_i (less the joint friction when
/// `friction` is set) of each driven body, and its articulated inertia and bias force
/// carried to its parent.
fn articulated_pass<T: RealField + Copy>(
    model: &Model<T>,
    data: &mut Data<T>,
    v: &[T],
    tau: &[T],
    friction: bool,
) {
    let layout = &model.layout;
    for (i, body) in model.bodies.iter().enumerate().rev() {
        let (inertia, bias) = match (body.motion, body.drive) {
            (Motion::Revolute | Motion::Prismatic, Some(drive)) => {
                let s = &body.motion_subspace;
                let u_vector = data.articulated[i] * s;
                let d = s.dot(&u_vector) + body.armature.unwrap_or_else(T::zero);
                let joint_friction = match friction::joint_friction(body, layout, v) {
                    Some((_, torque)) if friction => torque,
                    _ => T::zero(),
                };
                let u =
                    tau[layout.v_joint(drive.variable)] - joint_friction - s.dot(&data.forces[i]);
                data.u_vectors[i] = u_vector;
                data.d[i] = d;
                data.u[i] = u;
                let inertia = data.articulated[i] - u_vector * (u_vector.transpose() / d);
                let bias =
                    data.forces[i] + inertia * data.velocity_products[i] + u_vector * (u / d);
                (inertia, bias)
            }
            _ => (data.articulated[i], data.forces[i]),
        };
        if let Some(p) = body.parent {
            let x = &data.transforms[i];
            data.articulated[p] += x.transpose_apply_matrix(&inertia);
            data.forces[p] += x.transpose_apply_force(&bias);
        }
    }
}

/// The second forward pass: each body's acceleration a_i and its joint's q̈_i into `qdd`
/// (a free-flyer root's by its 6×6 system).
fn acceleration_pass<T: RealField + Copy>(
    model: &Model<T>,
    data: &mut Data<T>,
    tau: &[T],
    qdd: &mut [T],
) {
    let layout = &model.layout;
    let world_acceleration = spatial(Vector3::zeros(), -model.gravity);
    for (i, body) in model.bodies.iter().enumerate() {
        let parent_acceleration = match body.parent {
            Some(p) => data.accelerations[p],
            None => world_acceleration,
        };
        let mut a =
            data.transforms[i].apply_motion(&parent_acceleration) + data.velocity_products[i];
        match (body.motion, body.drive) {
            (Motion::FreeFlyer, _) => {
                let force = Vector6::from_fn(|r, _| tau[base_index(r)]) - data.forces[i];
                let root = match data.articulated[i].cholesky() {
                    Some(factor) => factor.solve(&force),
                    None => Vector6::repeat(nalgebra::convert(f64::NAN)),
                };
                for r in 0..6 {
                    qdd[base_index(r)] = root[r] - a[r];
                }
                a = root;
            }
            (_, Some(drive)) => {
                let acceleration = (data.u[i] - data.u_vectors[i].dot(&a)) / data.d[i];
                a += body.motion_subspace * acceleration;
                qdd[layout.v_joint(drive.variable)] = acceleration;
            }
            _ => {}
        }
        data.accelerations[i] = a;
    }
}
