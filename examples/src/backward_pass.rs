//! iLQR's backward pass: the Riccati-like sweep that expands the cost-to-go to second order
//! about the current trajectory (with first-order dynamics, Li & Todorov 2004) and returns
//! control-limited feedforward and feedback gains.

use nalgebra::{SMatrix, SVector};

use crate::box_qp::{solve_box_qp, NotPositiveDefinite};
use crate::cost::QuadraticCost;
use crate::discretisation::Linearisation;

/// Lower and upper control limits, elementwise.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounds<const NU: usize> {
    /// u ≥ lower.
    pub lower: SVector<f64, NU>,
    /// u ≤ upper.
    pub upper: SVector<f64, NU>,
}

impl<const NU: usize> Bounds<NU> {
    /// |u_i| ≤ limit_i.
    pub fn symmetric(limit: [f64; NU]) -> Self {
        let upper = SVector::from(limit);
        Bounds {
            lower: -upper,
            upper,
        }
    }

    /// `u` clamped into the box.
    pub fn clamp(&self, u: &SVector<f64, NU>) -> SVector<f64, NU> {
        u.zip_zip_map(&self.lower, &self.upper, |v, lo, hi| v.max(lo).min(hi))
    }
}

/// The policy u_k = ū_k + α k_k + K_k (x_k − x̄_k) the backward pass proposes, with the
/// terms of its predicted cost change ΔJ(α) = α Σ k_kᵀ Q_u + α² Σ ½ k_kᵀ Q_uu k_k.
#[derive(Clone, Debug)]
pub struct Gains<const NX: usize, const NU: usize> {
    /// Feedforward k_k.
    pub feedforward: Vec<SVector<f64, NU>>,
    /// Feedback K_k.
    pub feedback: Vec<SMatrix<f64, NU, NX>>,
    /// Σ k_kᵀ Q_u: the first-order term of ΔJ.
    pub linear: f64,
    /// Σ ½ k_kᵀ Q_uu k_k: the second-order term of ΔJ.
    pub quadratic: f64,
}

impl<const NX: usize, const NU: usize> Gains<NX, NU> {
    /// The predicted reduction of the cost for the step α, −ΔJ(α).
    pub fn expected_reduction(&self, alpha: f64) -> f64 {
        -(alpha * self.linear + alpha * alpha * self.quadratic)
    }

    /// The size of the feedforward steps relative to the controls, mean_k max_i
    /// |k_{k,i}| / (|ū_{k,i}| + 1): iLQR has converged when it is small.
    pub fn relative_step(&self, controls: &[SVector<f64, NU>]) -> f64 {
        let total: f64 = self
            .feedforward
            .iter()
            .zip(controls)
            .map(|(k, u)| k.zip_map(u, |k, u| k.abs() / (u.abs() + 1.0)).max())
            .sum();
        total / self.feedforward.len().max(1) as f64
    }
}

/// Sweeps k = N−1 … 0 with the value function V(x) ≈ ½ xᵀ V_xx x + V_xᵀ x:
///
/// Q_x = ℓ_x + f_xᵀ V'_x, Q_u = ℓ_u + f_uᵀ V'_x, Q_xx = ℓ_xx + f_xᵀ V'_xx f_x,
/// Q_uu = ℓ_uu + f_uᵀ V'_xx f_u, Q_ux = ℓ_ux + f_uᵀ V'_xx f_x,
///
/// regularised in the state (Tassa, Erez & Todorov 2012, eq. (10)): Q̃_uu and Q̃_ux use
/// V'_xx + μ I, which keeps the new trajectory close to the old one in state rather than in
/// control. The gains solve the box QP min_k ½ kᵀ Q̃_uu k + kᵀ Q_u within the limits (Tassa,
/// Mansard & Todorov 2014), K = −Q̃_uu,ff⁻¹ Q̃_ux,f on the free controls; the value function
/// is updated with the gains actually used (Tassa, Erez & Todorov 2012, eq. (11)):
///
/// V_x = Q_x + Kᵀ Q_uu k + Kᵀ Q_u + Q_uxᵀ k, V_xx = Q_xx + Kᵀ Q_uu K + Kᵀ Q_ux + Q_uxᵀ K.
///
/// `warm_start` holds the previous feedforward gains, the box QP's starting points.
pub fn backward_pass<const NX: usize, const NU: usize>(
    linearisation: &Linearisation<NX, NU>,
    states: &[SVector<f64, NX>],
    controls: &[SVector<f64, NU>],
    cost: &QuadraticCost<NX, NU>,
    bounds: &Bounds<NU>,
    regularisation: f64,
    warm_start: &[SVector<f64, NU>],
) -> Result<Gains<NX, NU>, NotPositiveDefinite> {
    let steps = controls.len();
    let final_state = states.last().expect("a trajectory has its initial state");
    let (mut vx, mut vxx) = cost.final_derivatives(final_state);
    let mut feedforward = vec![SVector::zeros(); steps];
    let mut feedback = vec![SMatrix::zeros(); steps];
    let (mut linear, mut quadratic) = (0.0, 0.0);
    let shift = SMatrix::<f64, NX, NX>::identity() * regularisation;
    for k in (0..steps).rev() {
        let (fx, fu) = (&linearisation.fx[k], &linearisation.fu[k]);
        let l = cost.running_derivatives(&states[k], &controls[k]);
        let qx = l.lx + fx.transpose() * vx;
        let qu = l.lu + fu.transpose() * vx;
        let vxx_fx = vxx * fx;
        let vxx_fu = vxx * fu;
        let qxx = l.lxx + fx.transpose() * vxx_fx;
        let quu = l.luu + fu.transpose() * vxx_fu;
        let qux = l.lux + fu.transpose() * vxx_fx;
        let quu_regularised = quu + fu.transpose() * shift * fu;
        let qux_regularised = qux + fu.transpose() * shift * fx;
        let solution = solve_box_qp(
            &quu_regularised,
            &qu,
            &(bounds.lower - controls[k]),
            &(bounds.upper - controls[k]),
            &warm_start[k],
        )?;
        let kff = solution.x;
        let kfb = solution.feedback(&qux_regularised);
        linear += kff.dot(&qu);
        quadratic += 0.5 * kff.dot(&(quu * kff));
        vx = qx + kfb.transpose() * (quu * kff) + kfb.transpose() * qu + qux.transpose() * kff;
        let v = qxx + kfb.transpose() * quu * kfb + kfb.transpose() * qux + qux.transpose() * kfb;
        vxx = (v + v.transpose()) * 0.5;
        feedforward[k] = kff;
        feedback[k] = kfb;
    }
    Ok(Gains {
        feedforward,
        feedback,
        linear,
        quadratic,
    })
}
