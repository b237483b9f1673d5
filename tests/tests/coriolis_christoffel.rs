//! The O(N d) recursion of Echeandia and Wensing (2021) gives, for every built-in robot, the
//! Christoffel C of its definition, C_ij = Σ_k ½ (∂M_ij/∂q_k + ∂M_ik/∂q_j − ∂M_jk/∂q_i) q̇_k,
//! entry by entry; so does the generated kernel, whichever of the two it was built from.

mod common;

use common::state;
use rne_codegen::Kernel;
use rne_interpreted::{evaluate, StateRef};
use rne_models::builtin::{RobotSource, BUILTIN_ROBOTS};
use rne_models::Visitor;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{Symbol, SymbolicDynamics};

#[test]
fn every_builtin_coriolis_kernel_is_the_christoffel_matrix_of_its_mass_matrix() {
    for robot in BUILTIN_ROBOTS {
        let model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .unwrap();
        let mut dynamics = SymbolicDynamics::new(&model);
        let christoffel = dynamics.christoffel_coriolis_matrix().concat();
        let recursive = dynamics.recursive_coriolis_matrix().concat();
        let n = dynamics.dof();
        let mut rng = common::rng(0x5eed_00c0);
        for k in 0..200 {
            let (q, qd, _) = state(&mut rng, n);
            let eval = |ids: &[rne_symbolic::Id]| {
                dynamics.model.graph.eval::<f64>(ids, |s| match s {
                    Symbol::Position(i) => q[i as usize],
                    Symbol::Velocity(i) => qd[i as usize],
                    _ => f64::NAN,
                })
            };
            let expected = eval(&christoffel);
            let kernel = robot.visit(CoriolisAt { q: &q, qd: &qd }).unwrap();
            let scale = expected.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for (what, got) in [("recursion", eval(&recursive)), ("kernel", kernel)] {
                for (e, (got, want)) in got.iter().zip(&expected).enumerate() {
                    assert!(
                        (got - want).abs() <= 1e-12 * scale,
                        "{}, {what}: state {k}, C[{}][{}] = {got}, Christoffel {want}",
                        robot.name,
                        e / n,
                        e % n
                    );
                }
            }
        }
    }
}

/// The generated Coriolis kernel of a built-in robot at one state, row-major.
struct CoriolisAt<'a> {
    q: &'a [f64],
    qd: &'a [f64],
}

impl Visitor for CoriolisAt<'_> {
    type Output = Result<Vec<f64>, rne_interpreted::Error>;

    fn visit<const N: usize, D: rne_codegen::Dynamics<N, N, Scalar = f64>>(
        self,
        model: D,
    ) -> Self::Output {
        let state = StateRef {
            q: self.q,
            qd: self.qd,
            qdd: &[],
            tau: &[],
        };
        evaluate(&model, Kernel::CoriolisMatrix, state)
    }
}
