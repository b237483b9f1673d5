//! The total momentum of a floating robot in the world frame, from the model's mass matrix.
//!
//! On a floating base (docs/design.md §4.5) the first six rows of M(q) v are the robot's total
//! spatial momentum, [f_b; n_b] = Σᵢ (mᵢ v_cᵢ; cᵢ × mᵢ v_cᵢ + I_cᵢ ωᵢ), in the base axes and about
//! the base origin: row i of M v is Σⱼ Jᵢ,ⱼᵀ hⱼ, the pairing of the bodies' momenta hⱼ with the
//! motion the i-th base velocity gives them, and a unit base velocity moves every body rigidly
//! with the base (Orin, Goswami and Lee, "Centroidal dynamics of a humanoid robot", Autonomous
//! Robots 35, 2013: the base rows of the joint-space inertia matrix transformed to the centre
//! of mass are the centroidal momentum matrix; Featherstone, *Rigid Body Dynamics Algorithms*,
//! 2008, chapter 9 on floating bases). Rotating by the base orientation R and moving the moment
//! point from the base position p to the world origin gives the world-frame momentum
//! [R f_b; R n_b + p × R f_b], which is constant when no external force acts (Newton and
//! Euler): joint torques are internal. The sim crate's test `tests/floating_momentum.rs`
//! checks the claim against the independent reference's body-by-body sum.

use rne_runtime::{Dynamics, Kernel};

use crate::configuration::{base_placement, Layout};
use crate::error::SimError;
use crate::se3::{cross, rotate};

/// A spatial momentum in the world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Momentum {
    /// Linear momentum Σ mᵢ v_cᵢ (kg·m/s), world axes.
    pub linear: [f64; 3],
    /// Angular momentum about the world origin Σ (cᵢ × mᵢ v_cᵢ + I_cᵢ ωᵢ) (kg·m²/s), world axes.
    pub angular: [f64; 3],
}

impl Momentum {
    /// The largest component difference to `other`, linear and angular alike.
    pub fn max_difference(&self, other: &Momentum) -> f64 {
        self.linear
            .iter()
            .chain(&self.angular)
            .zip(other.linear.iter().chain(&other.angular))
            .fold(0.0, |m, (a, b)| m.max((a - b).abs()))
    }
}

/// The total momentum of a floating-base `model` at (q, v), in the world frame with angular
/// momentum about the world origin, from the first six rows of M(q) v (see the module docs).
///
/// Errors: [`SimError::InvalidSetting`] for a fixed-base model (whose momentum is not
/// conserved: the ground takes it) or sizes that do not fit the base;
/// [`SimError::MissingKernel`] without the mass matrix.
pub fn world_momentum<const NQ: usize, const NV: usize, D>(
    model: &D,
    q: &[f64; NQ],
    v: &[f64; NV],
) -> Result<Momentum, SimError>
where
    D: Dynamics<NQ, NV, Scalar = f64> + ?Sized,
{
    if !Layout::of::<NQ, NV, D>()?.floating {
        return Err(SimError::InvalidSetting(
            "total momentum is defined here for floating-base models only",
        ));
    }
    let m = model.mass_matrix(q).ok_or(SimError::MissingKernel {
        kernel: Kernel::MassMatrix,
    })?;
    let body: [f64; 6] = std::array::from_fn(|i| m[i].iter().zip(v).map(|(a, b)| a * b).sum());
    Ok(base_to_world(q, &body))
}

/// [R f; R n + p × R f]: a momentum [f; n] at the base origin in base axes, seen from the world.
pub(crate) fn base_to_world<const NQ: usize>(q: &[f64; NQ], body: &[f64; 6]) -> Momentum {
    let (r, p) = base_placement(q);
    let linear = rotate(&r, &[body[0], body[1], body[2]]);
    let turned = rotate(&r, &[body[3], body[4], body[5]]);
    let shift = cross(&p, &linear);
    Momentum {
        linear,
        angular: std::array::from_fn(|i| turned[i] + shift[i]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point mass at the base origin moving along x, seen from a base at p = (0, 2, 0)
    /// turned a quarter about z: world velocity along y, angular momentum p × L about z is 0
    /// (p ∥ L); moved to p = (1, 0, 0) it is m·1·1 about z.
    #[test]
    fn base_momentum_is_rotated_and_shifted_to_the_world_origin() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let turned = [0.0, 2.0, 0.0, 0.0, 0.0, s, s];
        let body = [3.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let w = base_to_world(&turned, &body);
        let expected = Momentum {
            linear: [0.0, 3.0, 0.0],
            angular: [0.0; 3],
        };
        assert!(w.max_difference(&expected) < 1e-14, "{w:?}");
        let moved = [1.0, 0.0, 0.0, 0.0, 0.0, s, s];
        let w = base_to_world(&moved, &body);
        assert!((w.angular[2] - 3.0).abs() < 1e-14, "{w:?}");
    }
}
