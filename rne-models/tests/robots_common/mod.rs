//! Shared by the `robots_*` tests: seeded states, error measures, and the three evaluations of
//! a robot's dynamics that must agree — the symbolic expressions (`SymbolicDynamics` +
//! `ExprGraph::eval`), the numeric reference (spatial RNEA, CRBA, ABA) and, for a built-in
//! robot, its generated kernels.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rne_codegen::{Dynamics, Kernel};
use rne_interpreted::{evaluate, StateRef};
use rne_models::Visitor;
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{Id, RobotModel, Symbol, SymbolicDynamics};

/// A robot file of `rne-models/robots/`.
pub fn robot_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("robots")
        .join(name)
}

/// A URDF test robot of `tests/fixtures/urdf/` (copies of the URDF edge cases of
/// rne-symbolic's tests).
pub fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/urdf")
        .join(name)
}

pub fn load(path: &Path) -> RobotModel {
    read_robot(Description::file(path), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// The stress cases' seeded values (`rne_stress::states`), included rather than depended on
/// (rne-stress builds every generated robot): the one home of `uniform`, `n` values uniform in
/// `[-bound, bound]`.
#[path = "../../stress/src/states.rs"]
mod states;
pub use states::uniform;

/// A random state: |q| ≤ π, |q̇| ≤ 3, |q̈| ≤ 3.
pub fn state(rng: &mut ChaCha8Rng, n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    (
        uniform(rng, n, std::f64::consts::PI),
        uniform(rng, n, 3.0),
        uniform(rng, n, 3.0),
    )
}

/// Normwise relative error ‖a − b‖∞ / max(‖b‖∞, floor).
pub fn rel_err(a: &[f64], b: &[f64], floor: f64) -> f64 {
    assert_eq!(a.len(), b.len());
    rne_figures::relative_error_floor(a, b, floor)
}

/// One evaluation of everything the kernels compute, at one state.
#[derive(Clone, Debug)]
pub struct Evaluation {
    pub tau: Vec<f64>,
    /// Row-major.
    pub mass_matrix: Vec<f64>,
    pub gravity: Vec<f64>,
    pub bias: Vec<f64>,
    pub qdd: Vec<f64>,
    pub kinetic: f64,
    pub potential: f64,
}

impl Evaluation {
    /// The largest relative difference from `other` (the reference), per quantity.
    pub fn errors(&self, other: &Evaluation) -> [(&'static str, f64); 7] {
        let g_scale = other.gravity.iter().fold(1.0, |m: f64, g| m.max(g.abs()));
        [
            ("tau", rel_err(&self.tau, &other.tau, 1e-3)),
            ("M", rel_err(&self.mass_matrix, &other.mass_matrix, 1e-6)),
            ("g", rel_err(&self.gravity, &other.gravity, 1e-3)),
            ("bias", rel_err(&self.bias, &other.bias, 1e-3)),
            ("qdd", rel_err(&self.qdd, &other.qdd, 1e-3)),
            ("kinetic", rel_err(&[self.kinetic], &[other.kinetic], 1e-6)),
            // V is zero at the base origin: measured against the gravity torques' size.
            (
                "potential",
                (self.potential - other.potential).abs() / g_scale.max(other.potential.abs()),
            ),
        ]
    }
}

/// The symbolic dynamics of a model, evaluated on the expression graph.
pub struct Symbolic {
    dynamics: SymbolicDynamics,
    outputs: Vec<Id>,
}

impl Symbolic {
    pub fn new(model: &RobotModel) -> Symbolic {
        let mut dynamics = SymbolicDynamics::new(model);
        let mut outputs = dynamics.inverse_dynamics();
        outputs.extend(dynamics.mass_matrix().into_iter().flatten());
        outputs.extend(dynamics.gravity_torques());
        outputs.extend(dynamics.bias_torques());
        outputs.extend(dynamics.forward_dynamics());
        outputs.push(dynamics.kinetic_energy());
        outputs.push(dynamics.potential_energy());
        Symbolic { dynamics, outputs }
    }

    pub fn dof(&self) -> usize {
        self.dynamics.dof()
    }

    pub fn eval(&self, q: &[f64], qd: &[f64], qdd: &[f64], tau: &[f64]) -> Evaluation {
        let n = self.dof();
        let values = self
            .dynamics
            .model
            .graph
            .eval::<f64>(&self.outputs, |s| match s {
                Symbol::Position(k) => q[k as usize],
                Symbol::Velocity(k) => qd[k as usize],
                Symbol::Acceleration(k) => qdd[k as usize],
                Symbol::Force(k) => tau[k as usize],
                Symbol::Parameter(_) | Symbol::Lane(_) => f64::NAN,
            });
        let mut at = 0;
        let mut take = |count: usize| {
            at += count;
            values[at - count..at].to_vec()
        };
        Evaluation {
            tau: take(n),
            mass_matrix: take(n * n),
            gravity: take(n),
            bias: take(n),
            qdd: take(n),
            kinetic: take(1)[0],
            potential: take(1)[0],
        }
    }
}

/// The numeric reference's evaluation.
pub fn reference(
    reference: &mut Reference,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    tau: &[f64],
) -> Evaluation {
    Evaluation {
        tau: reference.inverse_dynamics(q, qd, qdd).unwrap().data.into(),
        mass_matrix: reference.mass_matrix(q).unwrap().transpose().data.into(),
        gravity: reference.gravity_torques(q).unwrap().data.into(),
        bias: reference.bias_torques(q, qd).unwrap().data.into(),
        qdd: reference.forward_dynamics(q, qd, tau).unwrap().data.into(),
        kinetic: reference.kinetic_energy(q, qd).unwrap(),
        potential: reference.potential_energy(q).unwrap(),
    }
}

/// A generated `Model`'s evaluation.
pub fn kernels<const N: usize, D: Dynamics<N, N, Scalar = f64>>(
    model: &D,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    tau: &[f64],
) -> Evaluation {
    let state = StateRef { q, qd, qdd, tau };
    let value = |kernel| evaluate(model, kernel, state).unwrap();
    Evaluation {
        tau: value(Kernel::InverseDynamics),
        mass_matrix: value(Kernel::MassMatrix),
        gravity: value(Kernel::GravityTorques),
        bias: value(Kernel::BiasTorques),
        qdd: value(Kernel::ForwardDynamics),
        kinetic: value(Kernel::KineticEnergy)[0],
        potential: value(Kernel::PotentialEnergy)[0],
    }
}

/// The number of joints of a built-in robot's generated `Model`.
pub struct Dof;

impl Visitor for Dof {
    type Output = usize;
    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, _: D) -> usize {
        N
    }
}

/// Asserts that every error of `errors` is at most `tolerance`, naming the robot, the
/// comparison and the state.
pub fn assert_close(
    robot: &str,
    what: &str,
    errors: [(&'static str, f64); 7],
    tolerance: f64,
    q: &[f64],
) {
    for (quantity, error) in errors {
        assert!(
            error <= tolerance,
            "{robot}: {what}: {quantity} relative error {error:e} exceeds {tolerance:e} at q = {q:?}"
        );
    }
}
