//! Kinetic and potential energy, from body velocities and base-frame centres of mass.
//!
//! ```text
//! T = Σ_i ½ (m_i v_{c,i}·v_{c,i} + ω_iᵀ I_{c,i} ω_i),    v_{c,i} = v_i + ω_i × c_i
//! V = −Σ_i m_i g·p_{c,i},                                p_{c,i} = p_i + R_i^0 c_i
//! ```
//!
//! with `[ω_i; v_i]` the spatial velocity of body i (body frame, at its origin), `c_i` its
//! COM in the body frame and `R_i^0`, `p_i` its placement in the world (base) frame — with a
//! floating base, `p_i` includes the base position. T equals
//! `½ q̇ᵀ M q̇` (the thesis's section 6.1.1) once the rotors' `½ I_a q̇_i²` is added for joints with
//! armature (M carries `I_a` on its diagonal); V is zero when every COM is at the base origin, and
//! `d(T + V)/dt = q̇ᵀ τ`. The sums use the COM form rather than the spatial inertias of the
//! RNEA and CRBA, so comparing them checks those. Bodies that no joint moves (the root of a
//! URDF and the bodies fixed to it) add a constant to V and are left out, as Pinocchio leaves
//! out what is fixed to its universe frame.

use nalgebra::{RealField, Vector6};

use crate::data::Data;
use crate::model::{Model, Motion};
use crate::spatial::{angular, linear};

/// Kinetic energy at (q, q̇). Slices have the model's length (checked by the caller).
pub(crate) fn kinetic_energy<T: RealField + Copy>(
    model: &Model<T>,
    data: &mut Data<T>,
    q: &[T],
    v: &[T],
) -> T {
    let layout = &model.layout;
    let half: T = nalgebra::convert(0.5);
    let mut energy = T::zero();
    for (i, body) in model.bodies.iter().enumerate() {
        let x = body.transform(layout, q);
        let velocity = match body.parent {
            Some(p) => x.apply_motion(&data.velocities[p]),
            None => Vector6::zeros(),
        } + body.joint_motion(layout, v);
        let w = angular(&velocity);
        let com_velocity = linear(&velocity) + w.cross(&body.com);
        energy += half * (body.mass * com_velocity.norm_squared() + w.dot(&(body.inertia_com * w)));
        if let (Some(armature), Some(rate)) = (body.armature, body.rate(layout, v)) {
            energy += half * armature * rate * rate;
        }
        data.velocities[i] = velocity;
    }
    energy
}

/// Potential energy at q. Slices have the model's length (checked by the caller).
pub(crate) fn potential_energy<T: RealField + Copy>(
    model: &Model<T>,
    data: &mut Data<T>,
    q: &[T],
) -> T {
    let mut energy = T::zero();
    let mut moves = vec![false; model.bodies.len()];
    for (i, body) in model.bodies.iter().enumerate() {
        moves[i] = !matches!(body.motion, Motion::Fixed) || body.parent.is_some_and(|p| moves[p]);
        let x = body.transform(&model.layout, q);
        let (rotation, origin) = match body.parent {
            Some(p) => (
                data.rotations[p] * x.rotation.transpose(),
                data.origins[p] + data.rotations[p] * x.translation,
            ),
            None => (x.rotation.transpose(), x.translation),
        };
        if moves[i] {
            let com = origin + rotation * body.com;
            energy -= body.mass * model.gravity.dot(&com);
        }
        data.rotations[i] = rotation;
        data.origins[i] = origin;
    }
    energy
}
