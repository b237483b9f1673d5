//! The workspace of the reference (Pinocchio's `Data`): per-body quantities, allocated once
//! when the [`Reference`](super::Reference) is built and overwritten by every call.

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

use super::model::Model;
use super::spatial::{RigidInertia, Transform};

/// Per-body scratch space, indexed like the model's bodies.
#[derive(Clone, Debug)]
pub(crate) struct Data {
    /// `ᶦX_p(q)`.
    pub transforms: Vec<Transform>,
    /// Spatial velocities `v_i`.
    pub velocities: Vec<Vector6<f64>>,
    /// Spatial accelerations `a_i`.
    pub accelerations: Vec<Vector6<f64>>,
    /// Spatial forces: `f_i` of the RNEA, the bias forces `p_i^A` of the ABA.
    pub forces: Vec<Vector6<f64>>,
    /// Composite inertias `I_i^c` of the CRBA.
    pub composite: Vec<RigidInertia>,
    /// Articulated-body inertias `I_i^A` of the ABA.
    pub articulated: Vec<Matrix6<f64>>,
    /// Velocity-product accelerations `c_i = v_i ×m S_i q̇_i` of the ABA.
    pub velocity_products: Vec<Vector6<f64>>,
    /// `U_i = I_i^A S_i` of the ABA.
    pub u_vectors: Vec<Vector6<f64>>,
    /// `D_i = S_iᵀ U_i` of the ABA.
    pub d: Vec<f64>,
    /// `u_i = τ_i − S_iᵀ p_i^A` of the ABA.
    pub u: Vec<f64>,
    /// Orientation `R_i^0` of each body frame in the base frame.
    pub rotations: Vec<Matrix3<f64>>,
    /// Origin of each body frame in the base frame.
    pub origins: Vec<Vector3<f64>>,
}

impl Data {
    /// A workspace sized for `model`.
    pub fn new(model: &Model) -> Data {
        let n = model.bodies.len();
        let zero_inertia = RigidInertia {
            mass: 0.0,
            first_moment: Vector3::zeros(),
            rotational: Matrix3::zeros(),
        };
        let identity = Transform {
            rotation: Matrix3::identity(),
            translation: Vector3::zeros(),
        };
        Data {
            transforms: vec![identity; n],
            velocities: vec![Vector6::zeros(); n],
            accelerations: vec![Vector6::zeros(); n],
            forces: vec![Vector6::zeros(); n],
            composite: vec![zero_inertia; n],
            articulated: vec![Matrix6::zeros(); n],
            velocity_products: vec![Vector6::zeros(); n],
            u_vectors: vec![Vector6::zeros(); n],
            d: vec![0.0; n],
            u: vec![0.0; n],
            rotations: vec![Matrix3::identity(); n],
            origins: vec![Vector3::zeros(); n],
        }
    }
}
