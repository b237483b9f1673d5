//! The workspace of the reference (Pinocchio's `Data`): per-body quantities, allocated once
//! when the [`Reference`](super::Reference) is built and overwritten by every call.

use nalgebra::{Matrix3, Matrix6, RealField, Vector3, Vector6};

use crate::model::Model;
use crate::spatial::{RigidInertia, Transform};

/// Per-body scratch space, indexed like the model's bodies.
#[derive(Clone, Debug)]
pub(crate) struct Data<T: RealField + Copy> {
    /// `ᶦX_p(q)`.
    pub transforms: Vec<Transform<T>>,
    /// Spatial velocities `v_i`.
    pub velocities: Vec<Vector6<T>>,
    /// Spatial accelerations `a_i`.
    pub accelerations: Vec<Vector6<T>>,
    /// Spatial forces: `f_i` of the RNEA, the bias forces `p_i^A` of the ABA.
    pub forces: Vec<Vector6<T>>,
    /// Composite inertias `I_i^c` of the CRBA.
    pub composite: Vec<RigidInertia<T>>,
    /// Articulated-body inertias `I_i^A` of the ABA.
    pub articulated: Vec<Matrix6<T>>,
    /// Velocity-product accelerations `c_i = v_i ×m S_i q̇_i` of the ABA.
    pub velocity_products: Vec<Vector6<T>>,
    /// `U_i = I_i^A S_i` of the ABA.
    pub u_vectors: Vec<Vector6<T>>,
    /// `D_i = S_iᵀ U_i` of the ABA.
    pub d: Vec<T>,
    /// `u_i = τ_i − S_iᵀ p_i^A` of the ABA.
    pub u: Vec<T>,
    /// Orientation `R_i^0` of each body frame in the world (base) frame.
    pub rotations: Vec<Matrix3<T>>,
    /// Origin of each body frame in the base frame.
    pub origins: Vec<Vector3<T>>,
    /// M(q), row-major, for forward dynamics of a coupled model.
    pub mass_matrix: Vec<T>,
    /// A generalized-force vector: the bias torques of forward dynamics of a coupled model.
    pub generalized: Vec<T>,
}

impl<T: RealField + Copy> Data<T> {
    /// A workspace sized for `model`.
    pub fn new(model: &Model<T>) -> Data<T> {
        let n = model.bodies.len();
        let nv = model.layout.nv();
        let zero_inertia = RigidInertia {
            mass: T::zero(),
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
            d: vec![T::zero(); n],
            u: vec![T::zero(); n],
            mass_matrix: vec![T::zero(); nv * nv],
            generalized: vec![T::zero(); nv],
            rotations: vec![Matrix3::identity(); n],
            origins: vec![Vector3::zeros(); n],
        }
    }
}
