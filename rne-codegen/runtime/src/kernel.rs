//! The functions a generated module can contain (DESIGN.md §4), as data: names, the arrays
//! they take and what they return.

use core::fmt;
use core::str::FromStr;

/// One generated function of a module (DESIGN.md §4).
///
/// More kernels (derivatives, kinematics, regressors) will join as further variants, hence
/// `#[non_exhaustive]`.
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
}

impl Input {
    /// The argument name.
    pub fn name(self) -> &'static str {
        match self {
            Input::Q => "q",
            Input::Qd => "qd",
            Input::Qdd => "qdd",
            Input::Tau => "tau",
        }
    }
}

/// What a kernel returns.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Shape {
    /// One scalar.
    Scalar,
    /// `[T; NV]`.
    Vector,
    /// `[[T; NV]; NV]`, row-major.
    Matrix,
}

impl Kernel {
    /// Every kernel, in the order of DESIGN.md §4.
    pub const ALL: [Kernel; 8] = [
        Kernel::InverseDynamics,
        Kernel::MassMatrix,
        Kernel::CoriolisMatrix,
        Kernel::GravityTorques,
        Kernel::BiasTorques,
        Kernel::ForwardDynamics,
        Kernel::KineticEnergy,
        Kernel::PotentialEnergy,
    ];

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
        }
    }

    /// The arrays it takes.
    pub fn inputs(self) -> &'static [Input] {
        match self {
            Kernel::InverseDynamics => &[Input::Q, Input::Qd, Input::Qdd],
            Kernel::MassMatrix | Kernel::GravityTorques | Kernel::PotentialEnergy => &[Input::Q],
            Kernel::CoriolisMatrix | Kernel::BiasTorques | Kernel::KineticEnergy => {
                &[Input::Q, Input::Qd]
            }
            Kernel::ForwardDynamics => &[Input::Q, Input::Qd, Input::Tau],
        }
    }

    /// What it returns.
    pub fn shape(self) -> Shape {
        match self {
            Kernel::MassMatrix | Kernel::CoriolisMatrix => Shape::Matrix,
            Kernel::KineticEnergy | Kernel::PotentialEnergy => Shape::Scalar,
            Kernel::InverseDynamics
            | Kernel::GravityTorques
            | Kernel::BiasTorques
            | Kernel::ForwardDynamics => Shape::Vector,
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
    fn every_kernel_takes_q_first_and_forward_dynamics_takes_torques() {
        for kernel in Kernel::ALL {
            assert_eq!(kernel.inputs()[0], Input::Q, "{kernel}");
        }
        assert_eq!(Kernel::ForwardDynamics.inputs().last(), Some(&Input::Tau));
        assert_eq!(Kernel::MassMatrix.shape(), Shape::Matrix);
        assert_eq!(Kernel::KineticEnergy.shape(), Shape::Scalar);
    }
}
