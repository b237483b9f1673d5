//! The tolerance of each kernel in `rne verify`: the largest normwise relative error against
//! the numeric reference it accepts (docs/design.md §6).
//!
//! The eight dynamics kernels evaluate the recursion once and keep about 15 significant
//! digits; the derivatives, M⁻¹ and the frame kinematics compose it with a differentiation or
//! an inversion, the regressor multiplies every parameter's column out, and the base
//! regressor is checked through Y_b π_b, whose base parameters are combinations of standard
//! ones that cancel digits: each step costs some digits, and the tolerances say how many.

use rne_codegen::Kernel;

/// The tolerance of the eight dynamics kernels (τ, M, C, g, bias, q̈, energies).
pub const DYNAMICS: f64 = 1e-13;
/// The tolerance of the derivatives, M⁻¹, the frame kinematics, friction and the regressor.
pub const DERIVED: f64 = 1e-12;
/// The tolerance of the base regressor and base parameters, compared as Y_b π_b against τ.
pub const BASE: f64 = 1e-11;

/// The largest normwise relative error `rne verify` accepts for `kernel`.
pub fn of(kernel: Kernel) -> f64 {
    if Kernel::DYNAMICS.contains(&kernel) {
        DYNAMICS
    } else if matches!(kernel, Kernel::BaseRegressor | Kernel::BaseParameters) {
        BASE
    } else {
        DERIVED
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kernel_has_a_tolerance_and_the_dynamics_the_tightest() {
        for kernel in Kernel::ALL {
            let t = of(kernel);
            assert!(t.is_finite() && t > 0.0, "{kernel}");
            assert!(t >= DYNAMICS, "{kernel}");
        }
        assert_eq!(of(Kernel::InverseDynamics), DYNAMICS);
        assert_eq!(of(Kernel::FrameJacobians), DERIVED);
        assert_eq!(of(Kernel::BaseParameters), BASE);
    }
}
