//! The independent numeric reference: spatial-vector RNEA, CRBA and ABA on nalgebra.
//!
//! This crate shares no recursion code with the symbolic path of `rne-symbolic`: it reads a
//! [`NumericModel`] (plain `f64` geometry and inertia) and runs Featherstone's algorithms from
//! *Rigid Body Dynamics Algorithms* (RBDA) on six-dimensional spatial vectors. The generated
//! kernels are checked against it.
//!
//! # Conventions
//!
//! Link i's body frame B_i is placed in its parent's body frame by
//! `R_i^p(q) = E_i Rot(u_i, q_i)` with origin `t_i` (revolute), `R_i^p = E_i` with origin
//! `t_i + E_i u_i q_i` (prismatic), or the constant `E_i`, `t_i` (fixed); see
//! [`rne_symbolic::model`]. Spatial vectors are expressed in body coordinates at the body
//! origin, angular part first. Fixed joints are kept as zero-DOF bodies — the symbolic path
//! merges them, and this separate handling is what checks the merge. Gravity `g` (base frame)
//! enters as the base acceleration `a_0 = [0; −g]`.
//!
//! The joint-space equation of motion is the thesis's (3.1):
//! `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)`.
//!
//! A floating base is a free-flyer root body with Pinocchio's conventions (docs/design.md §4.5, see
//! [`Reference::nq`]); a coupled (mimic) link follows the variable it names through
//! `q_link = m q_k + offset` and the chain rule; armature adds to M's diagonal; friction
//! enters inverse and forward dynamics when asked for ([`Reference::with_friction`]). Every
//! algorithm is generic over the scalar (`nalgebra::RealField`), and the derivatives run them
//! on dual numbers ([`num_dual::Dual64`]).
//!
//! | function | algorithm |
//! |---|---|
//! | [`Reference::inverse_dynamics`] | RNEA, RBDA table 5.1 |
//! | [`Reference::gravity_torques`] | RNEA(q, 0, 0) |
//! | [`Reference::bias_torques`] | RNEA(q, q̇, 0) `= C q̇ + g` |
//! | [`Reference::mass_matrix`] | CRBA, RBDA table 6.2 |
//! | [`Reference::forward_dynamics`] | ABA, RBDA table 7.1 (does not form M) |
//! | [`Reference::kinetic_energy`], [`Reference::potential_energy`] | sums over the bodies |
//! | [`Reference::inverse_dynamics_derivatives`], [`Reference::forward_dynamics_derivatives`] | the above on dual numbers |
//! | [`Reference::regressor`], [`Reference::standard_parameters`] | per-body spatial regressor |
//! | [`Reference::frame_placements`], [`Reference::frame_jacobians`], [`Reference::frame_jacobian_dot_qd`] | forward kinematics, RBDA section 4.1 |
//!
//! # Memory
//!
//! [`Reference::new`] allocates the per-body workspace once; the `*_into` methods then write
//! into caller-provided slices without allocating. The other methods allocate only the vector or
//! matrix they return.
//!
//! # Errors and non-finite input
//!
//! Every method checks the lengths of its slices and returns
//! [`ReferenceError::WrongLength`] instead of panicking. Values are not inspected: NaN or
//! infinite inputs propagate to NaN or infinite outputs (all loops run over the model's
//! structure, never over values). A joint that moves neither mass nor inertia makes M singular;
//! [`Reference::forward_dynamics`] then returns non-finite accelerations.

mod aba;
mod cholesky;
mod configuration;
mod crba;
mod data;
mod derivatives;
mod energy;
mod error;
mod friction;
mod kinematics;
mod model;
mod regressor;
mod rnea;
mod spatial;
mod validate;

pub use derivatives::ForwardDynamicsDerivatives;
pub use error::ReferenceError;
pub use kinematics::Placement;

use nalgebra::{DMatrix, DVector};
use num_dual::Dual64;
use rne_symbolic::NumericModel;

use data::Data;
use model::Model;

/// The numeric reference for one robot: the model's constants and a workspace, in the spirit
/// of Pinocchio's `Model` / `Data` split, in `f64` and in dual numbers (for derivatives).
/// Methods take `&mut self` only to reuse the workspace.
#[derive(Clone, Debug)]
pub struct Reference {
    model: Model<f64>,
    data: Data<f64>,
    dual_model: Model<Dual64>,
    dual_data: Data<Dual64>,
    joint_names: Vec<String>,
    link_names: Vec<String>,
    friction: bool,
}

impl Reference {
    /// Builds the reference for `model`.
    ///
    /// # Panics
    ///
    /// If `model` breaks an invariant of [`NumericModel`]; [`Reference::try_new`] returns the
    /// error instead. Models produced by `RobotModel::to_numeric` always satisfy them.
    pub fn new(model: &NumericModel) -> Reference {
        Reference::try_new(model).unwrap_or_else(|error| panic!("{error}"))
    }

    /// Builds the reference for `model`, or says which invariant it breaks: parents before
    /// children, every joint variable moved by a link and by at most one uncoupled link, none
    /// on fixed joints, a floating base's free-flyer as link 0, unit joint axes, rotation
    /// matrices `E_i`, symmetric inertias.
    pub fn try_new(model: &NumericModel) -> Result<Reference, ReferenceError> {
        validate::validate(model)?;
        let numeric = Model::from_numeric(model);
        let dual_model = Model::from_numeric(model);
        Ok(Reference {
            data: Data::new(&numeric),
            dual_data: Data::new(&dual_model),
            model: numeric,
            dual_model,
            joint_names: model.joint_names.clone(),
            link_names: model.links.iter().map(|l| l.name.clone()).collect(),
            friction: false,
        })
    }

    /// The same reference with joint friction included in [`Reference::inverse_dynamics`],
    /// [`Reference::forward_dynamics`] and their derivatives (`true`), or left out (`false`,
    /// the default, as the macro's `friction: exclude`). Gravity and bias torques never include
    /// it; [`Reference::friction_torques`] gives it alone.
    pub fn with_friction(mut self, include: bool) -> Reference {
        self.friction = include;
        self
    }

    /// Number of joint variables, NDOF (the free-flyer not counted).
    pub fn dof(&self) -> usize {
        self.model.layout.dof
    }

    /// Size of the configuration q: NDOF, or 7 + NDOF with a floating base
    /// (`[x, y, z, qx, qy, qz, qw, joints…]`, the base's position in the world and its unit
    /// quaternion; a quaternion is assumed unit, as Pinocchio assumes).
    pub fn nq(&self) -> usize {
        self.model.layout.nq()
    }

    /// Size of the velocity v (and of q̇, q̈, τ): NDOF, or 6 + NDOF with a floating base
    /// (`[v_lin, ω, joint rates…]`, both base velocities in the base frame; generalized forces
    /// `[force, torque about the base origin, in base axes; joint torques]`).
    pub fn nv(&self) -> usize {
        self.model.layout.nv()
    }

    /// Joint variable names in joint order.
    pub fn joint_names(&self) -> &[String] {
        &self.joint_names
    }

    /// Link (frame) names in model order: the frames of [`Reference::frame_placements`].
    pub fn link_names(&self) -> &[String] {
        &self.link_names
    }

    /// `q ⊕ v`: the configuration reached from `q` by moving with velocity `v` for unit time
    /// (Pinocchio's `integrate`: joints add, the base follows the SE(3) exponential of its body
    /// twist).
    pub fn integrate(&self, q: &[f64], v: &[f64]) -> Result<DVector<f64>, ReferenceError> {
        self.check(&[("q", q)], &[("v", v)])?;
        let mut out = DVector::zeros(self.nq());
        configuration::integrate(&self.model.layout, q, v, out.as_mut_slice());
        Ok(out)
    }

    /// Inverse dynamics by the RNEA: `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)`.
    pub fn inverse_dynamics(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<DVector<f64>, ReferenceError> {
        let mut tau = DVector::zeros(self.nv());
        self.inverse_dynamics_into(q, qd, qdd, tau.as_mut_slice())?;
        Ok(tau)
    }

    /// [`Reference::inverse_dynamics`] into `tau`.
    pub fn inverse_dynamics_into(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        tau: &mut [f64],
    ) -> Result<(), ReferenceError> {
        self.check(&[("q", q)], &[("qd", qd), ("qdd", qdd), ("tau", &*tau)])?;
        rnea::inverse_dynamics(&self.model, &mut self.data, q, Some(qd), Some(qdd), tau);
        if self.friction {
            friction::add_friction_torques(&self.model, qd, tau);
        }
        Ok(())
    }

    /// The joint-space inertia matrix M(q) by the CRBA, symmetric, `nv × nv`, armature
    /// included.
    pub fn mass_matrix(&mut self, q: &[f64]) -> Result<DMatrix<f64>, ReferenceError> {
        let n = self.nv();
        let mut m = DMatrix::zeros(n, n);
        self.mass_matrix_into(q, m.as_mut_slice())?;
        Ok(m)
    }

    /// [`Reference::mass_matrix`] into `out`, `nv²` entries, row-major (M is symmetric, so
    /// the order does not matter; `[[f64; N]; N]::as_flattened_mut` fits).
    pub fn mass_matrix_into(&mut self, q: &[f64], out: &mut [f64]) -> Result<(), ReferenceError> {
        self.check(&[("q", q)], &[])?;
        let n = self.nv();
        if out.len() != n * n {
            return Err(ReferenceError::WrongLength {
                argument: "out",
                expected: n * n,
                found: out.len(),
            });
        }
        crba::mass_matrix(&self.model, &mut self.data, q, out);
        Ok(())
    }

    /// The gravity torques `g(q)` = RNEA(q, 0, 0).
    pub fn gravity_torques(&mut self, q: &[f64]) -> Result<DVector<f64>, ReferenceError> {
        let mut g = DVector::zeros(self.nv());
        self.gravity_torques_into(q, g.as_mut_slice())?;
        Ok(g)
    }

    /// [`Reference::gravity_torques`] into `out`.
    pub fn gravity_torques_into(
        &mut self,
        q: &[f64],
        out: &mut [f64],
    ) -> Result<(), ReferenceError> {
        self.check(&[("q", q)], &[("out", &*out)])?;
        rnea::inverse_dynamics(&self.model, &mut self.data, q, None, None, out);
        Ok(())
    }

    /// The bias torques `C(q, q̇) q̇ + g(q)` = RNEA(q, q̇, 0).
    pub fn bias_torques(&mut self, q: &[f64], qd: &[f64]) -> Result<DVector<f64>, ReferenceError> {
        let mut bias = DVector::zeros(self.nv());
        self.bias_torques_into(q, qd, bias.as_mut_slice())?;
        Ok(bias)
    }

    /// [`Reference::bias_torques`] into `out`.
    pub fn bias_torques_into(
        &mut self,
        q: &[f64],
        qd: &[f64],
        out: &mut [f64],
    ) -> Result<(), ReferenceError> {
        self.check(&[("q", q)], &[("qd", qd), ("out", &*out)])?;
        rnea::inverse_dynamics(&self.model, &mut self.data, q, Some(qd), None, out);
        Ok(())
    }

    /// Forward dynamics by the ABA: `q̈ = M(q)⁻¹ (τ − C(q, q̇) q̇ − g(q))` (with a 6×6 solve at a
    /// free-flyer root; by Cholesky of M for a model with couplings, which the ABA cannot do).
    pub fn forward_dynamics(
        &mut self,
        q: &[f64],
        qd: &[f64],
        tau: &[f64],
    ) -> Result<DVector<f64>, ReferenceError> {
        let mut qdd = DVector::zeros(self.nv());
        self.forward_dynamics_into(q, qd, tau, qdd.as_mut_slice())?;
        Ok(qdd)
    }

    /// [`Reference::forward_dynamics`] into `qdd`.
    pub fn forward_dynamics_into(
        &mut self,
        q: &[f64],
        qd: &[f64],
        tau: &[f64],
        qdd: &mut [f64],
    ) -> Result<(), ReferenceError> {
        self.check(&[("q", q)], &[("qd", qd), ("tau", tau), ("qdd", &*qdd)])?;
        aba::forward_dynamics(&self.model, &mut self.data, q, qd, tau, self.friction, qdd);
        Ok(())
    }

    /// Kinetic energy `T = Σ ½ (m v_c·v_c + ωᵀ I_c ω) + Σ ½ I_a q̇_i² = ½ q̇ᵀ M(q) q̇` (the
    /// second sum over joints with armature: the rotors).
    pub fn kinetic_energy(&mut self, q: &[f64], qd: &[f64]) -> Result<f64, ReferenceError> {
        self.check(&[("q", q)], &[("qd", qd)])?;
        Ok(energy::kinetic_energy(&self.model, &mut self.data, q, qd))
    }

    /// Potential energy `V = −Σ m g·p_c`, with `p_c` each centre of mass in the base frame
    /// (zero when every COM is at the base origin).
    pub fn potential_energy(&mut self, q: &[f64]) -> Result<f64, ReferenceError> {
        self.check(&[("q", q)], &[])?;
        Ok(energy::potential_energy(&self.model, &mut self.data, q))
    }

    /// Joint friction `f_v q̇ + f_c sign(q̇) + offset` of every joint with friction (zero
    /// elsewhere, and on the base), `sign(0) = 0`.
    pub fn friction_torques(&self, qd: &[f64]) -> Result<DVector<f64>, ReferenceError> {
        self.check(&[], &[("qd", qd)])?;
        let mut tau = DVector::zeros(self.nv());
        friction::add_friction_torques(&self.model, qd, tau.as_mut_slice());
        Ok(tau)
    }

    /// Checks that the configuration-like slices have `nq` entries and the velocity-like ones
    /// `nv`.
    fn check(
        &self,
        configurations: &[(&'static str, &[f64])],
        velocities: &[(&'static str, &[f64])],
    ) -> Result<(), ReferenceError> {
        let sized = |slices: &[(&'static str, &[f64])], expected: usize| match slices
            .iter()
            .find(|(_, s)| s.len() != expected)
        {
            Some(&(argument, s)) => Err(ReferenceError::WrongLength {
                argument,
                expected,
                found: s.len(),
            }),
            None => Ok(()),
        };
        sized(configurations, self.nq())?;
        sized(velocities, self.nv())
    }
}
