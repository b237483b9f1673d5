//! The quadratic tracking cost of a finite-horizon optimal control problem and its
//! derivatives, which iLQR's backward pass expands to second order.

use nalgebra::{SMatrix, SVector};

/// J = Σ_{k<N} h ½ [(x_k − x*)ᵀ Q (x_k − x*) + u_kᵀ R u_k] + ½ (x_N − x*)ᵀ Q_f (x_N − x*).
///
/// The running cost is scaled by the time step h, so that one problem discretised with
/// different steps has comparable costs (a Riemann sum of ∫ ℓ dt).
#[derive(Clone, Debug, PartialEq)]
pub struct QuadraticCost<const NX: usize, const NU: usize> {
    /// The target state x*.
    pub target: SVector<f64, NX>,
    /// State weight Q of the running cost, per second.
    pub state: SMatrix<f64, NX, NX>,
    /// Control weight R of the running cost, per second.
    pub control: SMatrix<f64, NU, NU>,
    /// Terminal state weight Q_f.
    pub terminal: SMatrix<f64, NX, NX>,
    /// The time step h that scales the running cost.
    pub step: f64,
}

/// First and second derivatives of the running cost at one (x, u).
#[derive(Clone, Debug, PartialEq)]
pub struct RunningDerivatives<const NX: usize, const NU: usize> {
    /// ∂ℓ/∂x.
    pub lx: SVector<f64, NX>,
    /// ∂ℓ/∂u.
    pub lu: SVector<f64, NU>,
    /// ∂²ℓ/∂x².
    pub lxx: SMatrix<f64, NX, NX>,
    /// ∂²ℓ/∂u².
    pub luu: SMatrix<f64, NU, NU>,
    /// ∂²ℓ/∂u∂x.
    pub lux: SMatrix<f64, NU, NX>,
}

impl<const NX: usize, const NU: usize> QuadraticCost<NX, NU> {
    /// The cost with diagonal weights.
    pub fn diagonal(
        target: [f64; NX],
        state: [f64; NX],
        control: [f64; NU],
        terminal: [f64; NX],
        step: f64,
    ) -> Self {
        QuadraticCost {
            target: target.into(),
            state: SMatrix::from_diagonal(&state.into()),
            control: SMatrix::from_diagonal(&control.into()),
            terminal: SMatrix::from_diagonal(&terminal.into()),
            step,
        }
    }

    /// ℓ(x, u), the running cost of one step.
    pub fn running(&self, x: &SVector<f64, NX>, u: &SVector<f64, NU>) -> f64 {
        let e = x - self.target;
        0.5 * self.step
            * ((e.transpose() * self.state * e)[0] + (u.transpose() * self.control * u)[0])
    }

    /// ℓ_f(x_N), the terminal cost.
    pub fn final_cost(&self, x: &SVector<f64, NX>) -> f64 {
        let e = x - self.target;
        0.5 * (e.transpose() * self.terminal * e)[0]
    }

    /// J of a trajectory of N + 1 states and N controls.
    pub fn total(&self, states: &[SVector<f64, NX>], controls: &[SVector<f64, NU>]) -> f64 {
        let running: f64 = states
            .iter()
            .zip(controls)
            .map(|(x, u)| self.running(x, u))
            .sum();
        running + states.last().map_or(0.0, |x| self.final_cost(x))
    }

    /// The derivatives of ℓ at (x, u).
    pub fn running_derivatives(
        &self,
        x: &SVector<f64, NX>,
        u: &SVector<f64, NU>,
    ) -> RunningDerivatives<NX, NU> {
        let q = self.state * self.step;
        let r = self.control * self.step;
        RunningDerivatives {
            lx: q * (x - self.target),
            lu: r * u,
            lxx: q,
            luu: r,
            lux: SMatrix::zeros(),
        }
    }

    /// (∂ℓ_f/∂x, ∂²ℓ_f/∂x²) at x_N.
    pub fn final_derivatives(
        &self,
        x: &SVector<f64, NX>,
    ) -> (SVector<f64, NX>, SMatrix<f64, NX, NX>) {
        (self.terminal * (x - self.target), self.terminal)
    }
}
