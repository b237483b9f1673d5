//! Joint friction `τ_f = f_v q̇ + f_c sign(q̇) + offset` (docs/design.md §2.1), per revolute or
//! prismatic body, on its own joint rate; a coupled (mimic) body's friction reaches the variable
//! it follows times the multiplier, like every other generalized force of the body.
//!
//! `sign(0) = 0`: at rest the Coulomb term vanishes (the model has no stiction).

use nalgebra::RealField;

use crate::configuration::Layout;
use crate::model::{Body, Model};

/// `sign(x)` with `sign(0) = 0` (and NaN for NaN).
pub(crate) fn sign<T: RealField + Copy>(x: T) -> T {
    if x > T::zero() {
        T::one()
    } else if x < T::zero() {
        -T::one()
    } else {
        x * T::zero()
    }
}

/// The friction torque of `body`'s joint at the generalized velocity `v` and the index in v of
/// the variable it acts on (times the coupling's multiplier), if the joint has friction.
pub(crate) fn joint_friction<T: RealField + Copy>(
    body: &Body<T>,
    layout: &Layout,
    v: &[T],
) -> Option<(usize, T)> {
    let ([viscous, coulomb, offset], drive, rate) =
        (body.friction?, body.drive?, body.rate(layout, v)?);
    Some((
        layout.v_joint(drive.variable),
        drive.multiplier * (viscous * rate + coulomb * sign(rate) + offset),
    ))
}

/// Adds the friction torques at the generalized velocity `v` to `tau`.
pub(crate) fn add_friction_torques<T: RealField + Copy>(model: &Model<T>, v: &[T], tau: &mut [T]) {
    for body in &model.bodies {
        if let Some((k, torque)) = joint_friction(body, &model.layout, v) {
            tau[k] += torque;
        }
    }
}
