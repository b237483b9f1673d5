//! The `Kinematics` trait: frame placements, Jacobians and J̇q̇ of a generated module's
//! frames (the `frames:` setting), for task-space and operational-space control.

use crate::Dynamics;

/// The kinematics of `NF` frames of a robot with `NQ` configuration and `NV` velocity
/// variables (docs/design.md §4). Implemented by a generated module's `Model` when the module has a
/// kinematics kernel; the methods of the kernels it did not generate return `None`.
///
/// ```
/// use rne_runtime::{Kinematics, Real};
///
/// /// Where frame `f` is, for any robot whose module has frame placements.
/// fn position<const NQ: usize, const NV: usize, const NF: usize, K>(
///     robot: &K,
///     q: &[K::Scalar; NQ],
///     f: usize,
/// ) -> Option<[K::Scalar; 3]>
/// where
///     K: Kinematics<NQ, NV, NF>,
/// {
///     robot.frame_placements(q).map(|placements| placements[f].1)
/// }
/// ```
pub trait Kinematics<const NQ: usize, const NV: usize, const NF: usize>: Dynamics<NQ, NV> {
    /// The frames (link names), in the order of the kernels' outputs.
    const FRAMES: &'static [&'static str];

    /// Rotation (row-major, frame axes in world coordinates) and origin of each frame in the
    /// world.
    #[allow(clippy::type_complexity)]
    fn frame_placements(
        &self,
        q: &[Self::Scalar; NQ],
    ) -> Option<[([[Self::Scalar; 3]; 3], [Self::Scalar; 3]); NF]> {
        let _ = q;
        None
    }

    /// Geometric Jacobian of each frame: rows [v; ω] of the frame origin, world axes.
    fn frame_jacobians(&self, q: &[Self::Scalar; NQ]) -> Option<[[[Self::Scalar; NV]; 6]; NF]> {
        let _ = q;
        None
    }

    /// J̇ q̇ of each frame (world axes): the frame's acceleration is J q̈ + J̇ q̇.
    fn frame_jacobian_dot_qd(
        &self,
        q: &[Self::Scalar; NQ],
        qd: &[Self::Scalar; NV],
    ) -> Option<[[Self::Scalar; 6]; NF]> {
        let _ = (q, qd);
        None
    }
}
