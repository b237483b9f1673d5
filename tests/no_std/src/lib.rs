//! A `#![no_std]` library with generated modules in `f32` and `f64`, from a TOML spec (the
//! thesis's planar elbow) and a URDF (UR5), and code generic over the `Dynamics` trait.
//!
//! It builds for a bare target as it builds here: CI builds it with `-C panic=abort`, and a
//! test checks with `cargo tree` that it links nothing but `rne-codegen` and `rne-runtime`.
#![no_std]
#![deny(missing_docs)]

use rne_codegen::{Dynamics, OrderedReal, Real};

rne_codegen::derive_dynamics! {
    /// The planar elbow in `f64`.
    pub mod elbow {
        robot: "../fixtures/robots/planar-elbow.toml",
    }
}

rne_codegen::derive_dynamics! {
    /// The planar elbow in `f32`, with its parameters read at run time.
    pub mod elbow_f32 {
        robot: "../fixtures/robots/planar-elbow.toml",
        outputs: [inverse_dynamics, forward_dynamics, gravity_torques],
        parameters: runtime,
        scalar: f32,
    }
}

rne_codegen::derive_dynamics! {
    /// The planar elbow in any scalar.
    pub mod elbow_generic {
        robot: "../fixtures/robots/planar-elbow.toml",
        outputs: [mass_matrix, gravity_torques],
        scalar: generic,
    }
}

rne_codegen::derive_dynamics! {
    /// The UR5 (URDF) in `f64`.
    pub mod ur5 {
        robot: "../fixtures/robots/ur5.urdf",
        outputs: [inverse_dynamics, mass_matrix, forward_dynamics],
    }
}

rne_codegen::derive_dynamics! {
    /// The UR5 in `f32`, its wrist joint 3 locked (a string key, as URDF names can be anything).
    pub mod ur5_f32 {
        robot: "../fixtures/robots/ur5.urdf",
        outputs: [gravity_torques, forward_dynamics],
        lock: { "wrist_3_joint": 0.0 },
        scalar: f32,
    }
}

/// One step of a PD controller with gravity compensation,
/// τ = g(q) + kp (q_ref − q) − kd q̇, clamped to ±`limit` (the thesis's motor saturation):
/// written once for every robot and scalar, through the `Dynamics` trait. `None` when the
/// robot's module has no gravity torques.
pub fn pd_with_gravity_compensation<const NQ: usize, const NV: usize, D>(
    robot: &D,
    q: &[D::Scalar; NQ],
    qd: &[D::Scalar; NV],
    q_ref: &[D::Scalar; NQ],
    (kp, kd, limit): (D::Scalar, D::Scalar, D::Scalar),
) -> Option<[D::Scalar; NV]>
where
    D: Dynamics<NQ, NV>,
    // Clamping compares: a scalar, not lanes.
    D::Scalar: OrderedReal,
{
    let g = robot.gravity_torques(q)?;
    let mut tau = g;
    for (i, t) in tau.iter_mut().enumerate() {
        // Fixed base: joint i of q is joint i of q̇.
        let u = *t + kp * (q_ref[i] - q[i]) - kd * qd[i];
        *t = if u > limit {
            limit
        } else if u < -limit {
            -limit
        } else {
            u
        };
    }
    Some(tau)
}

/// Proportional and derivative gains and the torque limit.
fn gains<T: Real>() -> (T, T, T) {
    (T::from_f64(100.0), T::from_f64(10.0), T::from_f64(50.0))
}

/// The torques of [`control_every_robot`]: elbow (f64, f32), UR5 (f64, f32), generic elbow.
pub type Torques = (
    [f64; elbow::NV],
    [f32; elbow_f32::NV],
    [f64; ur5::NV],
    [f32; ur5_f32::NV],
    [f64; elbow_generic::NV],
);

/// The controller on each robot and scalar, so that every instantiation is compiled.
pub fn control_every_robot() -> Torques {
    let elbow = pd_with_gravity_compensation(
        &elbow::Model,
        &[0.1, 0.2],
        &[0.0, 0.0],
        &[0.0, 0.0],
        gains(),
    );
    let elbow_f32 = pd_with_gravity_compensation(
        &elbow_f32::Model::default(),
        &[0.1, 0.2],
        &[0.0, 0.0],
        &[0.0, 0.0],
        gains(),
    );
    let ur5 = pd_with_gravity_compensation(&ur5::Model, &[0.1; 6], &[0.0; 6], &[0.0; 6], gains());
    let ur5_f32 =
        pd_with_gravity_compensation(&ur5_f32::Model, &[0.1; 5], &[0.0; 5], &[0.0; 5], gains());
    let generic = pd_with_gravity_compensation(
        &elbow_generic::Model::<f64>::new(),
        &[0.1, 0.2],
        &[0.0, 0.0],
        &[0.0, 0.0],
        gains(),
    );
    let nan = f64::NAN;
    (
        elbow.unwrap_or([nan; 2]),
        elbow_f32.unwrap_or([f32::NAN; 2]),
        ur5.unwrap_or([nan; 6]),
        ur5_f32.unwrap_or([f32::NAN; 5]),
        generic.unwrap_or([nan; 2]),
    )
}
