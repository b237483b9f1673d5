//! The functions a generated module can contain (docs/design.md §4), as data: names, the arrays
//! they take and what they return.

use core::fmt;
use core::str::FromStr;

/// One generated function of a module (docs/design.md §4).
///
/// Further kernels may join as variants, hence `#[non_exhaustive]`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[non_exhaustive]
pub enum Kernel {
    /// `inverse_dynamics(q, qd, qdd) -> [T; NV]`: τ = M q̈ + C q̇ + g (3.1).
    InverseDynamics,
    /// `mass_matrix(q) -> [[T; NV]; NV]`: M(q), row-major, symmetric.
    MassMatrix,
    /// `coriolis_matrix(q, qd) -> [[T; NV]; NV]`: the Christoffel C(q, q̇).
    CoriolisMatrix,
    /// `gravity_torques(q) -> [T; NV]`: g(q).
    GravityTorques,
    /// `bias_torques(q, qd) -> [T; NV]`: C(q, q̇) q̇ + g(q).
    BiasTorques,
    /// `forward_dynamics(q, qd, tau) -> [T; NV]`: q̈ = M⁻¹ (τ − C q̇ − g) (6.2).
    ForwardDynamics,
    /// `kinetic_energy(q, qd) -> T`.
    KineticEnergy,
    /// `potential_energy(q) -> T`.
    PotentialEnergy,
    /// `inverse_dynamics_derivatives(q, qd, qdd) -> ([[T; NV]; NV], [[T; NV]; NV])`:
    /// (∂τ/∂q, ∂τ/∂q̇), ∂/∂q in the tangent space; ∂τ/∂q̈ is M.
    InverseDynamicsDerivatives,
    /// `forward_dynamics_derivatives(q, qd, tau) -> (∂q̈/∂q, ∂q̈/∂q̇, M⁻¹)`, three
    /// `[[T; NV]; NV]`.
    ForwardDynamicsDerivatives,
    /// `mass_matrix_inverse(q) -> [[T; NV]; NV]`: M(q)⁻¹, symmetric.
    MassMatrixInverse,
    /// `frame_placements(q) -> [([[T; 3]; 3], [T; 3]); NF]`: rotation and origin of each frame
    /// in the world.
    FramePlacements,
    /// `frame_jacobians(q) -> [[[T; NV]; 6]; NF]`: geometric Jacobians, rows [v; ω] of the
    /// frame origin in world axes.
    FrameJacobians,
    /// `frame_jacobian_dot_qd(q, qd) -> [[T; 6]; NF]`: J̇ q̇ of each frame.
    FrameJacobianDotQd,
    /// `friction_torques(qd) -> [T; NV]`: joint friction f_v q̇ + f_c sign(q̇) + offset.
    FrictionTorques,
    /// `regressor(q, qd, qdd) -> [[T; NP]; NV]`: Y of τ = Y(q, q̇, q̈) π.
    Regressor,
    /// `base_regressor(q, qd, qdd) -> [[T; NB]; NV]`: Y_b of τ = Y_b π_b, full column rank.
    BaseRegressor,
    /// `base_parameters(standard) -> [T; NB]`: π_b as linear combinations of π.
    BaseParameters,
}

/// The state arrays a kernel takes, in order.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Input {
    /// Joint positions `q` (NQ of them).
    Q,
    /// Joint velocities `qd` (NV).
    Qd,
    /// Joint accelerations `qdd` (NV).
    Qdd,
    /// Joint torques `tau` (NV).
    Tau,
    /// Standard parameters `standard` (NP).
    Standard,
}

impl Input {
    /// The argument name.
    pub fn name(self) -> &'static str {
        match self {
            Input::Q => "q",
            Input::Qd => "qd",
            Input::Qdd => "qdd",
            Input::Tau => "tau",
            Input::Standard => "standard",
        }
    }
}

/// What a kernel returns. NV is the size of the velocity, NF the number of frames, NP of
/// standard and NB of base parameters.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Shape {
    /// One scalar.
    Scalar,
    /// `[T; NV]`.
    Vector,
    /// `[[T; NV]; NV]`, row-major.
    Matrix,
    /// A tuple of this many `[[T; NV]; NV]`.
    Matrices(usize),
    /// `[([[T; 3]; 3], [T; 3]); NF]`: a rotation (row-major) and a position per frame.
    Placements,
    /// `[[[T; NV]; 6]; NF]`: a 6 × NV matrix per frame.
    FrameMatrices,
    /// `[[T; 6]; NF]`: a 6-vector per frame.
    FrameVectors,
    /// `[[T; NP]; NV]`: one row per velocity, one column per standard parameter.
    Regressor,
    /// `[[T; NB]; NV]`: one row per velocity, one column per base parameter.
    BaseRegressor,
    /// `[T; NB]`.
    BaseVector,
}

impl Kernel {
    /// Every kernel, in the order of docs/design.md §4.
    pub const ALL: [Kernel; 18] = [
        Kernel::InverseDynamics,
        Kernel::MassMatrix,
        Kernel::CoriolisMatrix,
        Kernel::GravityTorques,
        Kernel::BiasTorques,
        Kernel::ForwardDynamics,
        Kernel::KineticEnergy,
        Kernel::PotentialEnergy,
        Kernel::InverseDynamicsDerivatives,
        Kernel::ForwardDynamicsDerivatives,
        Kernel::MassMatrixInverse,
        Kernel::FramePlacements,
        Kernel::FrameJacobians,
        Kernel::FrameJacobianDotQd,
        Kernel::FrictionTorques,
        Kernel::Regressor,
        Kernel::BaseRegressor,
        Kernel::BaseParameters,
    ];

    /// The dynamics of (3.1): what a module generates when `outputs:` is not given.
    pub const DYNAMICS: [Kernel; 8] = [
        Kernel::InverseDynamics,
        Kernel::MassMatrix,
        Kernel::CoriolisMatrix,
        Kernel::GravityTorques,
        Kernel::BiasTorques,
        Kernel::ForwardDynamics,
        Kernel::KineticEnergy,
        Kernel::PotentialEnergy,
    ];

    /// Whether this kernel computes something per frame (NF, the `frames:` setting).
    pub fn is_kinematics(self) -> bool {
        matches!(
            self,
            Kernel::FramePlacements | Kernel::FrameJacobians | Kernel::FrameJacobianDotQd
        )
    }

    /// Whether this kernel solves with M(q): defined only for a robot whose every joint
    /// variable moves some mass (M invertible).
    pub fn inverts_mass_matrix(self) -> bool {
        matches!(
            self,
            Kernel::ForwardDynamics
                | Kernel::ForwardDynamicsDerivatives
                | Kernel::MassMatrixInverse
        )
    }

    /// Whether this kernel is about the standard or base parameters (NP, NB).
    pub fn is_identification(self) -> bool {
        matches!(
            self,
            Kernel::Regressor | Kernel::BaseRegressor | Kernel::BaseParameters
        )
    }

    /// The generated function's name (also the name `outputs:` takes).
    pub fn name(self) -> &'static str {
        match self {
            Kernel::InverseDynamics => "inverse_dynamics",
            Kernel::MassMatrix => "mass_matrix",
            Kernel::CoriolisMatrix => "coriolis_matrix",
            Kernel::GravityTorques => "gravity_torques",
            Kernel::BiasTorques => "bias_torques",
            Kernel::ForwardDynamics => "forward_dynamics",
            Kernel::KineticEnergy => "kinetic_energy",
            Kernel::PotentialEnergy => "potential_energy",
            Kernel::InverseDynamicsDerivatives => "inverse_dynamics_derivatives",
            Kernel::ForwardDynamicsDerivatives => "forward_dynamics_derivatives",
            Kernel::MassMatrixInverse => "mass_matrix_inverse",
            Kernel::FramePlacements => "frame_placements",
            Kernel::FrameJacobians => "frame_jacobians",
            Kernel::FrameJacobianDotQd => "frame_jacobian_dot_qd",
            Kernel::FrictionTorques => "friction_torques",
            Kernel::Regressor => "regressor",
            Kernel::BaseRegressor => "base_regressor",
            Kernel::BaseParameters => "base_parameters",
        }
    }

    /// The arrays it takes.
    pub fn inputs(self) -> &'static [Input] {
        match self {
            Kernel::InverseDynamics
            | Kernel::InverseDynamicsDerivatives
            | Kernel::Regressor
            | Kernel::BaseRegressor => &[Input::Q, Input::Qd, Input::Qdd],
            Kernel::MassMatrix
            | Kernel::GravityTorques
            | Kernel::PotentialEnergy
            | Kernel::MassMatrixInverse
            | Kernel::FramePlacements
            | Kernel::FrameJacobians => &[Input::Q],
            Kernel::CoriolisMatrix
            | Kernel::BiasTorques
            | Kernel::KineticEnergy
            | Kernel::FrameJacobianDotQd => &[Input::Q, Input::Qd],
            Kernel::ForwardDynamics | Kernel::ForwardDynamicsDerivatives => {
                &[Input::Q, Input::Qd, Input::Tau]
            }
            Kernel::FrictionTorques => &[Input::Qd],
            Kernel::BaseParameters => &[Input::Standard],
        }
    }

    /// What it returns.
    pub fn shape(self) -> Shape {
        match self {
            Kernel::MassMatrix | Kernel::CoriolisMatrix | Kernel::MassMatrixInverse => {
                Shape::Matrix
            }
            Kernel::KineticEnergy | Kernel::PotentialEnergy => Shape::Scalar,
            Kernel::InverseDynamics
            | Kernel::GravityTorques
            | Kernel::BiasTorques
            | Kernel::ForwardDynamics
            | Kernel::FrictionTorques => Shape::Vector,
            Kernel::InverseDynamicsDerivatives => Shape::Matrices(2),
            Kernel::ForwardDynamicsDerivatives => Shape::Matrices(3),
            Kernel::FramePlacements => Shape::Placements,
            Kernel::FrameJacobians => Shape::FrameMatrices,
            Kernel::FrameJacobianDotQd => Shape::FrameVectors,
            Kernel::Regressor => Shape::Regressor,
            Kernel::BaseRegressor => Shape::BaseRegressor,
            Kernel::BaseParameters => Shape::BaseVector,
        }
    }

    /// One line of documentation for the generated function.
    pub fn summary(self) -> &'static str {
        match self {
            Kernel::InverseDynamics => "Joint torques τ = M(q) q̈ + C(q, q̇) q̇ + g(q) (thesis (3.1)).",
            Kernel::MassMatrix => "Mass matrix M(q), row-major and symmetric.",
            Kernel::CoriolisMatrix => "Coriolis matrix C(q, q̇) from Christoffel symbols: Ṁ − 2C is skew-symmetric.",
            Kernel::GravityTorques => "Gravity torques g(q).",
            Kernel::BiasTorques => "Bias torques C(q, q̇) q̇ + g(q).",
            Kernel::ForwardDynamics => {
                "Joint accelerations q̈ = M(q)⁻¹ (τ − C(q, q̇) q̇ − g(q)) (thesis (6.2)), by a generated LᵀDL factorisation of M."
            }
            Kernel::KineticEnergy => "Kinetic energy ½ q̇ᵀ M(q) q̇.",
            Kernel::PotentialEnergy => "Potential energy, zero with every centre of mass at the base origin.",
            Kernel::InverseDynamicsDerivatives => {
                "(∂τ/∂q, ∂τ/∂q̇): derivatives of the inverse dynamics, ∂/∂q in the tangent space (for a floating base, q ⊕ δ with δ in the base frame); ∂τ/∂q̈ is M(q)."
            }
            Kernel::ForwardDynamicsDerivatives => {
                "(∂q̈/∂q, ∂q̈/∂q̇, M⁻¹): derivatives of the forward dynamics, ∂q̈/∂x = −M⁻¹ ∂τ/∂x at q̈ = FD(q, q̇, τ); ∂q̈/∂τ is M⁻¹."
            }
            Kernel::MassMatrixInverse => "Inverse mass matrix M(q)⁻¹, row-major and symmetric.",
            Kernel::FramePlacements => "Rotation (row-major) and origin in the world of each frame of `FRAMES`.",
            Kernel::FrameJacobians => "Geometric Jacobian of each frame of `FRAMES`: rows [v; ω] of the frame origin in world axes.",
            Kernel::FrameJacobianDotQd => "J̇ q̇ of each frame of `FRAMES` (world axes): its acceleration is J q̈ + J̇ q̇.",
            Kernel::FrictionTorques => "Joint friction f_v q̇ + f_c sign(q̇) + offset, with sign(0) = 0.",
            Kernel::Regressor => "Joint-torque regressor Y(q, q̇, q̈) of τ = Y π, columns in the order of `PARAMETERS`.",
            Kernel::BaseRegressor => "Base regressor Y_b(q, q̇, q̈) of τ = Y_b π_b (full column rank), columns in the order of `BASE_PARAMETERS`.",
            Kernel::BaseParameters => "The base parameters π_b (`BASE_PARAMETERS`) of standard parameters π (`PARAMETERS`).",
        }
    }
}

impl fmt::Display for Kernel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not a kernel's ([`Kernel::from_str`]); its message lists the names.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct UnknownKernel {
    _private: (),
}

impl fmt::Display for UnknownKernel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("expected one of: ")?;
        for (i, kernel) in Kernel::ALL.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            f.write_str(kernel.name())?;
        }
        Ok(())
    }
}

impl core::error::Error for UnknownKernel {}

impl FromStr for Kernel {
    type Err = UnknownKernel;
    /// The kernel of this function name.
    fn from_str(s: &str) -> Result<Kernel, UnknownKernel> {
        Kernel::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or(UnknownKernel { _private: () })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::string::ToString;

    #[test]
    fn names_parse_back_to_their_kernel() {
        for kernel in Kernel::ALL {
            assert_eq!(kernel.name().parse::<Kernel>(), Ok(kernel));
            assert_eq!(kernel.to_string(), kernel.name());
        }
    }

    #[test]
    fn an_unknown_name_is_an_error_listing_every_name() {
        let error = "mass".parse::<Kernel>().unwrap_err().to_string();
        for kernel in Kernel::ALL {
            assert!(error.contains(kernel.name()), "{error}");
        }
    }

    #[test]
    fn state_kernels_take_q_first_and_forward_dynamics_takes_torques() {
        for kernel in Kernel::ALL {
            let first = kernel.inputs()[0];
            match kernel {
                Kernel::FrictionTorques => assert_eq!(first, Input::Qd),
                Kernel::BaseParameters => assert_eq!(first, Input::Standard),
                _ => assert_eq!(first, Input::Q, "{kernel}"),
            }
        }
        assert!(Kernel::DYNAMICS.iter().all(|k| Kernel::ALL.contains(k)));
        assert_eq!(Kernel::ForwardDynamics.inputs().last(), Some(&Input::Tau));
        assert_eq!(Kernel::MassMatrix.shape(), Shape::Matrix);
        assert_eq!(Kernel::KineticEnergy.shape(), Shape::Scalar);
    }
}
