//! The configuration manifold of a [`Dynamics<NQ, NV>`] model: q ⊕ v, Pinocchio's
//! `integrate`.
//!
//! On a fixed base q and v live in the same ℝⁿ (NQ = NV) and q ⊕ v = q + v. On a floating base
//! (docs/design.md §4.5) q = [p, quaternion xyzw, joints] has NQ = NV + 1 entries and v = [v_base,
//! ω_base, joint rates] is a body twist of the base followed by joint rates: the joints add, and
//! the base moves by the SE(3) exponential of its twist, (R, p) ↦ (R Exp(ω), p + R V(ω) v_base).
//!
//! SE(3), not SO(3) × ℝ³: the base velocity is a body twist, the left-trivialised velocity of
//! SE(3), so q ⊕ h v with the SE(3) exponential is the exact motion at constant twist (a screw)
//! and the variational integrator's momentum transport is the coadjoint action of the same
//! group element (see [`LieVariational`](crate::LieVariational)); with SO(3) × ℝ³ the
//! translation would be p + h R v_base, which is the exact motion only when ω = 0. It is also
//! what Pinocchio's `integrate` does for a free-flyer, so results compare one to one.

use rne_runtime::Dynamics;

use crate::error::SimError;
use crate::se3::{exp, quaternion_product, rotation, Displacement, Six, Vec3};

/// Where the base lives in q and v: the first 7 entries of q and 6 of v on a floating base,
/// nothing on a fixed one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Layout {
    /// Whether the model has a free-flyer root.
    pub floating: bool,
}

impl Layout {
    /// The layout of `D`, checking that its sizes fit it: NQ = NV on a fixed base,
    /// NQ = NV + 1 ≥ 7 on a floating one.
    pub fn of<const NQ: usize, const NV: usize, D>() -> Result<Layout, SimError>
    where
        D: Dynamics<NQ, NV> + ?Sized,
    {
        let floating = D::FLOATING_BASE;
        let fits = if floating {
            NV >= 6 && NQ == NV + 1
        } else {
            NQ == NV
        };
        if !fits {
            return Err(SimError::InvalidSetting(
                "the model's NQ and NV do not fit its base: NQ = NV on a fixed base, \
                 NQ = NV + 1 >= 7 on a floating one",
            ));
        }
        Ok(Layout { floating })
    }

    /// Entries of v that belong to the base (6 or 0).
    pub fn base_velocities(self) -> usize {
        if self.floating {
            6
        } else {
            0
        }
    }

    /// Entries of q that belong to the base (7 or 0).
    pub fn base_coordinates(self) -> usize {
        if self.floating {
            7
        } else {
            0
        }
    }

    /// q ⊕ v, and on a floating base the displacement exp(ξ) of the base (in the base frame)
    /// that it applied. The quaternion is renormalised, so that rounding does not accumulate
    /// in its norm over many steps.
    pub fn displace<const NQ: usize, const NV: usize>(
        self,
        q: &[f64; NQ],
        v: &[f64; NV],
    ) -> ([f64; NQ], Option<Displacement>) {
        let (nq, nv) = (self.base_coordinates(), self.base_velocities());
        let mut out = *q;
        for (o, dv) in out[nq..].iter_mut().zip(&v[nv..]) {
            *o += dv;
        }
        if !self.floating {
            return (out, None);
        }
        let xi: Six = std::array::from_fn(|i| v[i]);
        let step = exp(&xi);
        let (r, _) = base_placement(q);
        let dp = crate::se3::rotate(&r, &step.translation);
        for i in 0..3 {
            out[i] = q[i] + dp[i];
        }
        let turned = quaternion_product(&[q[3], q[4], q[5], q[6]], &step.quaternion);
        let norm = turned.iter().map(|x| x * x).sum::<f64>().sqrt();
        for (o, c) in out[3..7].iter_mut().zip(turned) {
            *o = c / norm;
        }
        (out, Some(step))
    }
}

/// The base's placement in the world on a floating base: the rotation matrix of q's quaternion
/// (base axes in world coordinates) and the position q[0..3]. Meaningless on a fixed base.
pub(crate) fn base_placement<const NQ: usize>(q: &[f64; NQ]) -> ([[f64; 3]; 3], Vec3) {
    (rotation(&[q[3], q[4], q[5], q[6]]), [q[0], q[1], q[2]])
}

/// q ⊕ v: the configuration reached from q by moving at the constant velocity v for unit time,
/// on the configuration manifold of `model` (Pinocchio's `integrate`; see the module docs).
/// Scale v by h for a step of length h. Only the model's layout (its base, NQ and NV) is read.
///
/// Errors with [`SimError::InvalidSetting`] when NQ and NV do not fit the model's base.
///
/// ```
/// use rne_runtime::{Dynamics, Kernel};
/// /// A free body: only the layout matters here.
/// struct Body;
/// impl Dynamics<7, 6> for Body {
///     type Scalar = f64;
///     const NAME: &'static str = "body";
///     const JOINTS: &'static [&'static str] = &[];
///     const FLOATING_BASE: bool = true;
///     const KERNELS: &'static [Kernel] = &[];
/// }
/// let identity = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
/// // Half a turn about z while moving along x at unit speed: a half circle of radius 1/π.
/// let q = rne_sim::integrate(&Body, &identity, &[1.0, 0.0, 0.0, 0.0, 0.0, std::f64::consts::PI])
///     .unwrap();
/// assert!(q[0].abs() < 1e-15 && (q[1] - 2.0 / std::f64::consts::PI).abs() < 1e-15);
/// assert!((q[5] - 1.0).abs() < 1e-15); // the quaternion [0, 0, 1, 0]: half a turn about z
/// ```
pub fn integrate<const NQ: usize, const NV: usize, D>(
    model: &D,
    q: &[f64; NQ],
    v: &[f64; NV],
) -> Result<[f64; NQ], SimError>
where
    D: Dynamics<NQ, NV> + ?Sized,
{
    let _ = model;
    Ok(Layout::of::<NQ, NV, D>()?.displace(q, v).0)
}

#[cfg(test)]
mod tests {
    use super::*;

    const FLOATING: Layout = Layout { floating: true };

    /// Joints add; the base composes: q ⊕ a ⊕ b = q ⊕ (a + b) for twists along one screw, and
    /// the quaternion stays unit.
    #[test]
    fn floating_displacements_compose_along_a_screw() {
        let q = [0.1, -0.2, 0.3, 0.2, -0.1, 0.3, 0.9, 0.5];
        let norm = q[3..7].iter().map(|x: &f64| x * x).sum::<f64>().sqrt();
        let q: [f64; 8] = std::array::from_fn(|i| {
            if (3..7).contains(&i) {
                q[i] / norm
            } else {
                q[i]
            }
        });
        let twist = [0.3, 0.1, -0.4, 0.5, -0.2, 0.7, 1.5];
        let scaled = |s: f64| twist.map(|c| s * c);
        let (twice, _) = FLOATING.displace(&FLOATING.displace(&q, &scaled(0.3)).0, &scaled(0.3));
        let (once, step) = FLOATING.displace(&q, &scaled(0.6));
        for (a, b) in twice.iter().zip(&once) {
            assert!((a - b).abs() < 1e-15, "{twice:?} vs {once:?}");
        }
        assert!((once[7] - (0.5 + 0.6 * 1.5)).abs() < 1e-15);
        assert!(step.is_some());
        let unit: f64 = once[3..7].iter().map(|x| x * x).sum();
        assert!((unit - 1.0).abs() < 1e-15);
    }

    /// Sizes that do not fit the base are refused.
    #[test]
    fn layouts_must_fit_the_base() {
        struct Fixed;
        impl Dynamics<2, 2> for Fixed {
            type Scalar = f64;
            const NAME: &'static str = "fixed";
            const JOINTS: &'static [&'static str] = &["a", "b"];
            const FLOATING_BASE: bool = false;
            const KERNELS: &'static [rne_runtime::Kernel] = &[];
        }
        struct Wrong;
        impl Dynamics<6, 6> for Wrong {
            type Scalar = f64;
            const NAME: &'static str = "wrong";
            const JOINTS: &'static [&'static str] = &[];
            const FLOATING_BASE: bool = true;
            const KERNELS: &'static [rne_runtime::Kernel] = &[];
        }
        assert_eq!(integrate(&Fixed, &[1.0, 2.0], &[0.5, -1.0]), Ok([1.5, 1.0]));
        assert!(matches!(
            integrate(&Wrong, &[0.0; 6], &[0.0; 6]),
            Err(SimError::InvalidSetting(_))
        ));
    }
}
