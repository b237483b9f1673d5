//! The functions a generated module can contain (DESIGN.md §4).

use std::fmt;
use std::str::FromStr;

use rne_symbolic::{Id, SymbolicDynamics};

/// One generated function.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kernel {
    /// `inverse_dynamics(q, qd, qdd) -> [T; N]`: τ = M q̈ + C q̇ + g (3.1).
    InverseDynamics,
    /// `mass_matrix(q) -> [[T; N]; N]`: M(q), row-major, symmetric.
    MassMatrix,
    /// `coriolis_matrix(q, qd) -> [[T; N]; N]`: the Christoffel C(q, q̇).
    CoriolisMatrix,
    /// `gravity_torques(q) -> [T; N]`: g(q).
    GravityTorques,
    /// `bias_torques(q, qd) -> [T; N]`: C(q, q̇) q̇ + g(q).
    BiasTorques,
    /// `forward_dynamics(q, qd, tau) -> [T; N]`: q̈ = M⁻¹ (τ − C q̇ − g) (6.2).
    ForwardDynamics,
    /// `kinetic_energy(q, qd) -> T`.
    KineticEnergy,
    /// `potential_energy(q) -> T`.
    PotentialEnergy,
}

/// The state arrays a kernel takes, in order.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Input {
    /// Joint positions `q`.
    Q,
    /// Joint velocities `qd`.
    Qd,
    /// Joint accelerations `qdd`.
    Qdd,
    /// Joint torques `tau`.
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
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Shape {
    /// One scalar.
    Scalar,
    /// `[T; N]`.
    Vector,
    /// `[[T; N]; N]`, row-major.
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

    /// The function's name.
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
            _ => Shape::Vector,
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

    /// Builds the kernel's outputs (flattened row-major for matrices) into the dynamics' graph.
    pub fn build(self, dynamics: &mut SymbolicDynamics) -> Vec<Id> {
        match self {
            Kernel::InverseDynamics => dynamics.inverse_dynamics(),
            Kernel::MassMatrix => dynamics.mass_matrix().concat(),
            Kernel::CoriolisMatrix => dynamics.coriolis_matrix().concat(),
            Kernel::GravityTorques => dynamics.gravity_torques(),
            Kernel::BiasTorques => dynamics.bias_torques(),
            Kernel::ForwardDynamics => dynamics.forward_dynamics(),
            Kernel::KineticEnergy => vec![dynamics.kinetic_energy()],
            Kernel::PotentialEnergy => vec![dynamics.potential_energy()],
        }
    }
}

impl fmt::Display for Kernel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not a kernel.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown output `{0}`; expected one of: inverse_dynamics, mass_matrix, coriolis_matrix, gravity_torques, bias_torques, forward_dynamics, kinetic_energy, potential_energy")]
pub struct UnknownKernel(pub String);

impl FromStr for Kernel {
    type Err = UnknownKernel;
    fn from_str(s: &str) -> Result<Kernel, UnknownKernel> {
        Kernel::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| UnknownKernel(s.to_owned()))
    }
}
