//! Configuration and velocity vectors, with Pinocchio's free-flyer conventions (docs/design.md
//! §4.5).
//!
//! With a floating base, `q = [x, y, z, qx, qy, qz, qw, joints…]` (the base frame's origin in
//! the world and the unit quaternion of its orientation, xyzw) and
//! `v = [v_lin, ω, joint rates…]` (both base velocities in the base frame). On a fixed base q
//! and v hold the joint variables only.
//!
//! Derivatives with respect to q live in the tangent space (NV columns): a perturbation
//! `q ⊕ δ` moves the base by `δ_lin` and `δ_ω` expressed in the base frame, as Pinocchio's
//! `integrate` does with the SE(3) exponential in the local frame.

use nalgebra::{Matrix3, RealField, Vector3};
use rne_symbolic::model::Base;
use rne_symbolic::NumericModel;

/// Where the base and the joint variables sit in q and v.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Layout {
    /// Number of joint variables.
    pub dof: usize,
    /// Whether q and v start with a free-flyer's 7 and 6 entries.
    pub floating: bool,
}

impl Layout {
    /// The layout of `model`.
    pub fn of(model: &NumericModel) -> Layout {
        Layout {
            dof: model.dof(),
            floating: model.base == Base::Floating,
        }
    }

    /// Number of configuration entries, NQ.
    pub fn nq(&self) -> usize {
        self.q_joint(self.dof)
    }

    /// Number of velocity entries, NV.
    pub fn nv(&self) -> usize {
        self.v_joint(self.dof)
    }

    /// Index in q of joint variable `k`.
    pub fn q_joint(&self, k: usize) -> usize {
        if self.floating {
            7 + k
        } else {
            k
        }
    }

    /// Index in v of joint variable `k`.
    pub fn v_joint(&self, k: usize) -> usize {
        if self.floating {
            6 + k
        } else {
            k
        }
    }
}

/// The rotation matrix of a unit quaternion `[x, y, z, w]` (the standard formula; the input is
/// assumed unit, as Pinocchio assumes).
pub(crate) fn quaternion_rotation<T: RealField + Copy>([x, y, z, w]: [T; 4]) -> Matrix3<T> {
    let one = T::one();
    let two = one + one;
    Matrix3::new(
        one - two * (y * y + z * z),
        two * (x * y - z * w),
        two * (x * z + y * w),
        two * (x * y + z * w),
        one - two * (x * x + z * z),
        two * (y * z - x * w),
        two * (x * z - y * w),
        two * (y * z + x * w),
        one - two * (x * x + y * y),
    )
}

/// The base frame's orientation (its axes in world coordinates) and origin in the world, from
/// the first seven entries of a floating-base configuration.
pub(crate) fn base_placement<T: RealField + Copy>(q: &[T]) -> (Matrix3<T>, Vector3<T>) {
    (
        quaternion_rotation([q[3], q[4], q[5], q[6]]),
        Vector3::new(q[0], q[1], q[2]),
    )
}

/// `q ⊕ δ` to first order, written into `out`: `p + R δ_lin`, the quaternion
/// `quat + ½ quat ⊗ [δ_ω; 0]` (tangent to the unit sphere, so the rotation formula stays exact
/// to first order) and `joints + δ_joints`. With dual-number entries in `δ` this gives the
/// exact tangent-space derivative; for `f64` it is a retraction whose error is second order.
/// Slices have the layout's lengths.
pub(crate) fn perturb<T: RealField + Copy>(layout: &Layout, q: &[T], delta: &[T], out: &mut [T]) {
    out.copy_from_slice(q);
    for k in 0..layout.dof {
        out[layout.q_joint(k)] += delta[layout.v_joint(k)];
    }
    if !layout.floating {
        return;
    }
    let (rotation, _) = base_placement(q);
    let linear = rotation * Vector3::new(delta[0], delta[1], delta[2]);
    let w = Vector3::new(delta[3], delta[4], delta[5]);
    let (v, s) = (Vector3::new(q[3], q[4], q[5]), q[6]);
    let half: T = nalgebra::convert(0.5);
    let dv = (w * s + v.cross(&w)) * half;
    for i in 0..3 {
        out[i] += linear[i];
        out[3 + i] += dv[i];
    }
    out[6] -= v.dot(&w) * half;
}

/// `q ⊕ v` for a unit time step (Pinocchio's `integrate`): joints add `v`; the base moves by
/// the SE(3) exponential of the body twist `[v_lin; ω]`,
/// `R' = R Exp(ω)`, `p' = p + R V(ω) v_lin` with `V(ω) = 1 + (1 − cos θ)/θ² ω× +
/// (θ − sin θ)/θ³ ω×²`, `θ = |ω|`. The result's quaternion is normalised.
pub(crate) fn integrate(layout: &Layout, q: &[f64], v: &[f64], out: &mut [f64]) {
    out.copy_from_slice(q);
    for k in 0..layout.dof {
        out[layout.q_joint(k)] += v[layout.v_joint(k)];
    }
    if !layout.floating {
        return;
    }
    let w = Vector3::new(v[3], v[4], v[5]);
    let theta = w.norm();
    let theta2 = theta * theta;
    let (a, b) = if theta < 1e-4 {
        (0.5 - theta2 / 24.0, 1.0 / 6.0 - theta2 / 120.0)
    } else {
        (
            (1.0 - theta.cos()) / theta2,
            (theta - theta.sin()) / (theta2 * theta),
        )
    };
    let wx = w.cross_matrix();
    let left_jacobian = Matrix3::identity() + wx * a + wx * wx * b;
    let (rotation, position) = base_placement(q);
    let moved = position + rotation * left_jacobian * Vector3::new(v[0], v[1], v[2]);
    let (half_sin, half_cos) = (theta / 2.0).sin_cos();
    let axis_scale = if theta < 1e-8 { 0.5 } else { half_sin / theta };
    let (dv, ds) = (w * axis_scale, half_cos);
    let (qv, qs) = (Vector3::new(q[3], q[4], q[5]), q[6]);
    let product_v = dv * qs + qv * ds + qv.cross(&dv);
    let product_s = qs * ds - qv.dot(&dv);
    let norm = (product_v.norm_squared() + product_s * product_s).sqrt();
    out[..3].copy_from_slice(moved.as_slice());
    for i in 0..3 {
        out[3 + i] = product_v[i] / norm;
    }
    out[6] = product_s / norm;
}
