//! Shared test helpers: seeded random states and error measures.

#![allow(dead_code)]

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rne_codegen::{Dynamics, Kernel};
use rne_interpreted::{evaluate, Error as EvalError, Interpreted, StateRef};
use rne_models::{BuiltinRobot, Visitor};

/// A deterministic random generator for one test.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// The stress cases' seeded values (`rne_stress::states`), included rather than depended on
/// (rne-stress builds every generated robot): the one home of `uniform`, `n` values uniform in
/// `[-bound, bound]`.
#[path = "../../../rne-models/stress/src/states.rs"]
mod states;
pub use states::uniform;

/// A random state: |q| ≤ π, |q̇| ≤ 10, |q̈| ≤ 10.
pub fn state(rng: &mut ChaCha8Rng, n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    (
        uniform(rng, n, std::f64::consts::PI),
        uniform(rng, n, 10.0),
        uniform(rng, n, 10.0),
    )
}

/// Normwise relative error ‖a − b‖∞ / ‖b‖∞ (absolute error when b is zero), of vectors of the
/// same length: the report's measure ([`rne_figures::relative_error`]).
pub fn rel_err(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "compared vectors differ in length");
    rne_figures::relative_error(a, b)
}

/// ‖a − b‖∞ / max(‖b‖∞, floor): relative error, absolute below `floor` (for quantities that
/// can vanish, where the reference holds only rounding noise).
pub fn rel_err_floor(a: &[f64], b: &[f64], floor: f64) -> f64 {
    rne_figures::relative_error_floor(a, b, floor)
}

/// Flattens a row-major matrix.
pub fn flat(m: &[Vec<f64>]) -> Vec<f64> {
    m.concat()
}

/// `m v`.
pub fn mat_vec(m: &[Vec<f64>], v: &[f64]) -> Vec<f64> {
    m.iter()
        .map(|row| row.iter().zip(v).map(|(a, b)| a * b).sum())
        .collect()
}

/// The worst error seen, and where.
#[derive(Default, Debug)]
pub struct Worst {
    pub error: f64,
    pub sample: usize,
}

impl Worst {
    pub fn record(&mut self, error: f64, sample: usize) {
        if error > self.error || error.is_nan() {
            self.error = error;
            self.sample = sample;
        }
    }
}

/// A row-major matrix of `n` columns as rows.
pub fn rows(values: Vec<f64>, n: usize) -> Vec<Vec<f64>> {
    values.chunks(n.max(1)).map(<[f64]>::to_vec).collect()
}

/// One kernel at one state, flattened.
type Evaluate<'a> = dyn Fn(Kernel, StateRef<'_>) -> Result<Vec<f64>, EvalError> + 'a;

/// A robot's kernels as these tests call them: over slices, matrices as rows, through
/// `rne_interpreted::evaluate` on a built-in robot's generated `Model` ([`with_generated`]) or
/// `Interpreted::evaluate` on the programs ([`SliceModel::programs`]).
pub struct SliceModel<'a> {
    eval: &'a Evaluate<'a>,
    joints: Vec<String>,
}

/// Runs `f` on the slice view of `robot`'s generated `Model`.
pub fn with_generated<R>(robot: &BuiltinRobot, f: impl FnOnce(&SliceModel<'_>) -> R) -> R {
    /// The visit that builds the view.
    struct View<F>(F);
    impl<R, F: FnOnce(&SliceModel<'_>) -> R> Visitor for View<F> {
        type Output = R;
        fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) -> R {
            let eval = |kernel: Kernel, state: StateRef<'_>| evaluate(&model, kernel, state);
            (self.0)(&SliceModel {
                eval: &eval,
                joints: D::JOINTS.iter().map(|j| j.to_string()).collect(),
            })
        }
    }
    robot.visit(View(f))
}

impl<'a> SliceModel<'a> {
    /// Runs `f` on the slice view of `programs`.
    pub fn programs<R>(programs: &Interpreted, f: impl FnOnce(&SliceModel<'_>) -> R) -> R {
        let eval = |kernel: Kernel, state: StateRef<'_>| programs.evaluate(kernel, state);
        f(&SliceModel {
            eval: &eval,
            joints: programs.joints(),
        })
    }

    fn call(
        &self,
        kernel: Kernel,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        tau: &[f64],
    ) -> Result<Vec<f64>, EvalError> {
        (self.eval)(kernel, StateRef { q, qd, qdd, tau })
    }

    fn rows(&self, values: Vec<f64>) -> Vec<Vec<f64>> {
        values
            .chunks(self.dof().max(1))
            .map(<[f64]>::to_vec)
            .collect()
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// Joint names.
    pub fn joints(&self) -> Vec<String> {
        self.joints.clone()
    }

    /// τ(q, q̇, q̈).
    pub fn inverse_dynamics(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
    ) -> Result<Vec<f64>, EvalError> {
        self.call(Kernel::InverseDynamics, q, qd, qdd, &[])
    }

    /// M(q), by rows.
    pub fn mass_matrix(&self, q: &[f64]) -> Result<Vec<Vec<f64>>, EvalError> {
        Ok(self.rows(self.call(Kernel::MassMatrix, q, &[], &[], &[])?))
    }

    /// C(q, q̇), by rows.
    pub fn coriolis_matrix(&self, q: &[f64], qd: &[f64]) -> Result<Vec<Vec<f64>>, EvalError> {
        Ok(self.rows(self.call(Kernel::CoriolisMatrix, q, qd, &[], &[])?))
    }

    /// g(q).
    pub fn gravity_torques(&self, q: &[f64]) -> Result<Vec<f64>, EvalError> {
        self.call(Kernel::GravityTorques, q, &[], &[], &[])
    }

    /// C(q, q̇) q̇ + g(q).
    pub fn bias_torques(&self, q: &[f64], qd: &[f64]) -> Result<Vec<f64>, EvalError> {
        self.call(Kernel::BiasTorques, q, qd, &[], &[])
    }

    /// q̈(q, q̇, τ).
    pub fn forward_dynamics(
        &self,
        q: &[f64],
        qd: &[f64],
        tau: &[f64],
    ) -> Result<Vec<f64>, EvalError> {
        self.call(Kernel::ForwardDynamics, q, qd, &[], tau)
    }

    /// Kinetic energy.
    pub fn kinetic_energy(&self, q: &[f64], qd: &[f64]) -> Result<f64, EvalError> {
        Ok(self.call(Kernel::KineticEnergy, q, qd, &[], &[])?[0])
    }

    /// Potential energy.
    pub fn potential_energy(&self, q: &[f64]) -> Result<f64, EvalError> {
        Ok(self.call(Kernel::PotentialEnergy, q, &[], &[], &[])?[0])
    }
}
