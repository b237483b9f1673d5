//! Derivatives of inverse and forward dynamics by forward-mode automatic differentiation: the
//! generic RNEA and ABA run on dual numbers ([`Dual64`]), one tangent direction at a time, so
//! each column is exact to rounding (no step size) and shares no formula with the symbolic
//! derivatives it checks.
//!
//! Derivatives with respect to q are taken in the tangent space (NV columns, docs/design.md §4.5):
//! column j is `d/dε f(q ⊕ ε e_j)` at ε = 0, with a floating base moved by `δ_lin` and `δ_ω`
//! in the base frame (Pinocchio's convention for `computeRNEADerivatives` and
//! `computeABADerivatives`). Coulomb friction's `sign(q̇)` has derivative zero.

use nalgebra::{DMatrix, DVector};
use num_dual::Dual64;

use crate::configuration::perturb;
use crate::error::ReferenceError;
use crate::{aba, cholesky, crba, friction, rnea, Reference};

/// The derivatives of forward dynamics at one state, each `nv × nv`.
#[derive(Clone, Debug, PartialEq)]
pub struct ForwardDynamicsDerivatives {
    /// `∂q̈/∂q`, in the tangent space of q.
    pub dqdd_dq: DMatrix<f64>,
    /// `∂q̈/∂q̇`.
    pub dqdd_dqd: DMatrix<f64>,
    /// `∂q̈/∂τ = M(q)⁻¹`.
    pub mass_matrix_inverse: DMatrix<f64>,
}

/// What a dual-number evaluation differentiates by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Direction {
    /// The tangent direction `e_j` of the configuration.
    Configuration(usize),
    /// The j-th entry of the velocity.
    Velocity(usize),
}

/// The arguments of one dual-number evaluation: q moved along the tangent space or v along one
/// entry, the third argument (q̈ or τ) constant.
struct Seeded {
    q: Vec<Dual64>,
    v: Vec<Dual64>,
    third: Vec<Dual64>,
}

impl Reference {
    /// `(∂τ/∂q, ∂τ/∂q̇)` of [`Reference::inverse_dynamics`] at (q, q̇, q̈), each `nv × nv`
    /// (∂τ/∂q̈ is M). Friction is included as in `inverse_dynamics`.
    pub fn inverse_dynamics_derivatives(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<(DMatrix<f64>, DMatrix<f64>), ReferenceError> {
        self.check(&[("q", q)], &[("qd", qd), ("qdd", qdd)])?;
        let n = self.nv();
        let mut tau = vec![Dual64::from_re(0.0); n];
        let (mut dq, mut dv) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        for j in 0..n {
            for (direction, out) in [
                (Direction::Configuration(j), &mut dq),
                (Direction::Velocity(j), &mut dv),
            ] {
                let s = self.seed(q, qd, qdd, direction);
                rnea::inverse_dynamics(
                    &self.dual_model,
                    &mut self.dual_data,
                    &s.q,
                    Some(&s.v),
                    Some(&s.third),
                    &mut tau,
                );
                if self.friction {
                    friction::add_friction_torques(&self.dual_model, &s.v, &mut tau);
                }
                out.set_column(j, &DVector::from_iterator(n, tau.iter().map(|t| t.eps)));
            }
        }
        Ok((dq, dv))
    }

    /// `∂q̈/∂q`, `∂q̈/∂q̇` and `M⁻¹ = ∂q̈/∂τ` of [`Reference::forward_dynamics`] at (q, q̇, τ),
    /// differentiating the ABA itself (the Cholesky solve for a coupled model).
    pub fn forward_dynamics_derivatives(
        &mut self,
        q: &[f64],
        qd: &[f64],
        tau: &[f64],
    ) -> Result<ForwardDynamicsDerivatives, ReferenceError> {
        self.check(&[("q", q)], &[("qd", qd), ("tau", tau)])?;
        let n = self.nv();
        let mut qdd = vec![Dual64::from_re(0.0); n];
        let (mut dq, mut dv) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
        for j in 0..n {
            for (direction, out) in [
                (Direction::Configuration(j), &mut dq),
                (Direction::Velocity(j), &mut dv),
            ] {
                let s = self.seed(q, qd, tau, direction);
                aba::forward_dynamics(
                    &self.dual_model,
                    &mut self.dual_data,
                    &s.q,
                    &s.v,
                    &s.third,
                    self.friction,
                    &mut qdd,
                );
                out.set_column(j, &DVector::from_iterator(n, qdd.iter().map(|a| a.eps)));
            }
        }
        Ok(ForwardDynamicsDerivatives {
            dqdd_dq: dq,
            dqdd_dqd: dv,
            mass_matrix_inverse: self.mass_matrix_inverse(q)?,
        })
    }

    /// `M(q)⁻¹` (`nv × nv`), by Cholesky of the CRBA's M; non-finite when M is singular.
    pub fn mass_matrix_inverse(&mut self, q: &[f64]) -> Result<DMatrix<f64>, ReferenceError> {
        self.check(&[("q", q)], &[])?;
        let n = self.nv();
        let mut factor = vec![0.0; n * n];
        crba::mass_matrix(&self.model, &mut self.data, q, &mut factor);
        let mut inverse = DMatrix::identity(n, n);
        if cholesky::factorize(&mut factor, n) {
            for mut column in inverse.column_iter_mut() {
                cholesky::solve(&factor, n, column.as_mut_slice());
            }
        } else {
            inverse.fill(f64::NAN);
        }
        Ok(inverse)
    }

    /// The dual-number arguments for one direction.
    fn seed(&self, q: &[f64], v: &[f64], third: &[f64], direction: Direction) -> Seeded {
        let constant =
            |x: &[f64]| -> Vec<Dual64> { x.iter().map(|&x| Dual64::from_re(x)).collect() };
        let (mut q_seeded, mut v_seeded) = (constant(q), constant(v));
        match direction {
            Direction::Configuration(j) => {
                let mut delta = vec![Dual64::from_re(0.0); v.len()];
                delta[j] = Dual64::new(0.0, 1.0);
                let base = q_seeded.clone();
                perturb(&self.model.layout, &base, &delta, &mut q_seeded);
            }
            Direction::Velocity(j) => v_seeded[j] = Dual64::new(v[j], 1.0),
        }
        Seeded {
            q: q_seeded,
            v: v_seeded,
            third: constant(third),
        }
    }
}
