//! `parameters: base` through the symbolic programs, for every built-in robot and a floating
//! quadruped: at the base parameters of the spec every kernel equals the constant-parameter
//! kernel (the potential energy up to a constant), the base-parameter kernels cost fewer
//! operations than the runtime-parameter ones, and a change of the standard parameters
//! along a direction the dynamics do not determine changes neither the base parameters nor
//! the torques.

mod common;

use common::{rel_err, rng, uniform};
use rne_codegen_core::{build_kernel, GenerationOptions, Kernel, ParameterMode, Program, Scene};
use rne_models::builtin::{RobotSource, BUILTIN_ROBOTS};
use rne_models::QUADRUPED;
use rne_symbolic::model::Base;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{RobotModel, Symbol, SymbolicDynamics};

/// A state: q (a unit quaternion for a floating base), v, a and u.
struct State {
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    u: Vec<f64>,
}

fn states(dynamics: &SymbolicDynamics, count: usize, seed: u64) -> Vec<State> {
    let layout = dynamics.layout();
    let mut rng = rng(seed);
    (0..count)
        .map(|_| {
            let mut q = Vec::new();
            if layout.floating {
                q.extend(uniform(&mut rng, 3, 1.0));
                let quaternion = uniform(&mut rng, 4, 1.0);
                let norm = quaternion.iter().map(|x| x * x).sum::<f64>().sqrt();
                q.extend(quaternion.iter().map(|x| x / norm));
            }
            q.extend(uniform(&mut rng, layout.ndof, std::f64::consts::PI));
            State {
                q,
                v: uniform(&mut rng, layout.nv(), 3.0),
                a: uniform(&mut rng, layout.nv(), 5.0),
                u: uniform(&mut rng, layout.nv(), 20.0),
            }
        })
        .collect()
}

/// A program's outputs at `s`, parameters at the values `dynamics`' model gives them.
fn run(program: &Program, dynamics: &SymbolicDynamics, s: &State) -> Vec<f64> {
    program.eval(|symbol| match symbol {
        Symbol::Position(k) => s.q[k as usize],
        Symbol::Velocity(k) => s.v[k as usize],
        Symbol::Acceleration(k) => s.a[k as usize],
        Symbol::Force(k) => s.u[k as usize],
        p @ Symbol::Parameter(_) => dynamics.model.parameter_value(p).unwrap_or(f64::NAN),
        Symbol::Lane(_) => f64::NAN,
    })
}

fn applied(model: &RobotModel) -> RobotModel {
    Scene::default().apply(model).expect("a valid scene")
}

fn builtin(name: &str) -> RobotModel {
    applied(
        &RobotSource::resolve(name)
            .load(&LoadOptions::default())
            .expect("built-in robot"),
    )
}

fn quadruped() -> RobotModel {
    let mut model = QUADRUPED
        .load(&LoadOptions::default())
        .expect("the quadruped loads");
    model.set_base(Base::Floating);
    applied(&model)
}

/// Every kernel of `kernels` built both ways agrees at 20 seeded states; the potential
/// energy after removing the constant the base parameters leave open.
fn check(model: &RobotModel, name: &str, kernels: &[Kernel]) {
    let constant = SymbolicDynamics::new(model);
    let (base, _) = constant.in_base_parameters();
    let states = states(&constant, 20, 0xba5e);
    for &kernel in kernels {
        let (a, b) = (
            build_kernel(&constant, kernel).program,
            build_kernel(&base, kernel).program,
        );
        let offset = (kernel == Kernel::PotentialEnergy)
            .then(|| run(&a, &constant, &states[0])[0] - run(&b, &base, &states[0])[0]);
        for s in &states {
            let expected = run(&a, &constant, s);
            let mut got = run(&b, &base, s);
            if let Some(v0) = offset {
                got[0] += v0;
            }
            let e = rel_err(&got, &expected);
            assert!(e < 1e-12, "{name}, {kernel}: relative error {e:e}");
        }
    }
}

#[test]
fn every_builtin_robots_base_parameter_kernels_equal_its_constant_kernels() {
    for robot in BUILTIN_ROBOTS {
        check(&builtin(robot.name), robot.name, &Kernel::DYNAMICS);
    }
    for name in ["planar-elbow", "irb140-3dof", "puma560"] {
        let control = [
            Kernel::InverseDynamicsDerivatives,
            Kernel::ForwardDynamicsDerivatives,
            Kernel::MassMatrixInverse,
        ];
        check(&builtin(name), name, &control);
    }
}

#[test]
fn a_floating_quadrupeds_base_parameter_kernels_equal_its_constant_kernels() {
    check(&quadruped(), "quadruped (floating)", &Kernel::DYNAMICS);
}

/// Inverse dynamics with base parameters costs fewer operations than with every standard
/// parameter at run time; the costs of the four modes are printed (`-- --nocapture`) for
/// docs/identification.md. (Against constants it depends: regrouping takes parameters out of
/// the recursion that folding cannot, and the Panda's base-parameter kernel is the cheaper.)
#[test]
fn base_parameter_inverse_dynamics_costs_less_than_runtime_parameters() {
    let cost = |dynamics: &SymbolicDynamics| {
        build_kernel(dynamics, Kernel::InverseDynamics)
            .program
            .op_count()
            .cost()
    };
    for name in ["irb140", "puma560", "panda-arm"] {
        let constant = SymbolicDynamics::new(&builtin(name));
        let (base, _) = constant.in_base_parameters();
        let standard = constant.in_standard_parameters();
        let (constant_cost, base_cost, standard_cost) =
            (cost(&constant), cost(&base), cost(&standard));
        let runtime_cost = rne_codegen_core::generate(
            &RobotSource::resolve(name)
                .load(&LoadOptions {
                    symbolic_parameters: true,
                    ..LoadOptions::default()
                })
                .expect("built-in robot"),
            &Scene::default(),
            &GenerationOptions {
                outputs: vec![Kernel::InverseDynamics],
                parameters: ParameterMode::Runtime,
                ..GenerationOptions::default()
            },
            name,
        )
        .expect("generated")
        .kernels[0]
            .ops
            .cost();
        println!(
            "{name}: inverse_dynamics cost: constant {constant_cost}, runtime {runtime_cost}, \
             standard {standard_cost}, base {base_cost}"
        );
        assert!(
            base_cost < standard_cost,
            "{name}: base {base_cost}, standard {standard_cost}"
        );
        // The spec's named parameters are fewer: the IRB 140 names 45 (masses, box edges and
        // lengths; its inertias follow from them), PUMA 560 and Panda none (runtime = constant).
        assert!(
            runtime_cost <= standard_cost,
            "{name}: runtime {runtime_cost}"
        );
    }
}

/// π + δ with δ₁ = −K δ₂ (random δ₂) has the base parameters of π, and the dynamics written
/// in its standard parameters are those of π: the base-parameter kernels, functions of π_b
/// alone, cannot tell the two robots apart, and neither can the physics.
#[test]
fn standard_parameters_along_the_undetermined_directions_change_nothing() {
    let mut random = rng(0xd1f);
    for robot in BUILTIN_ROBOTS {
        let model = builtin(robot.name);
        let constant = SymbolicDynamics::new(&model);
        let base = constant.base_parameters();
        let mut scratch = constant.clone();
        let ids = scratch.standard_parameters();
        let pi = scratch.model.graph.eval::<f64>(&ids, |_| f64::NAN);
        let delta_dependent = uniform(&mut random, base.dependent.len(), 1.0);
        let mut moved = pi.clone();
        for (&d, x) in base.dependent.iter().zip(&delta_dependent) {
            moved[d] += x;
        }
        for (&i, row) in base.independent.iter().zip(&base.k) {
            moved[i] -= row
                .iter()
                .zip(&delta_dependent)
                .map(|(k, x)| k * x)
                .sum::<f64>();
        }
        let (before, after) = (base.of(&pi), base.of(&moved));
        assert!(
            rel_err(&after, &before) < 1e-12,
            "{}: π_b moved",
            robot.name
        );
        let mut other = constant.clone();
        let g = &mut other.model.graph;
        let standard: Vec<_> = moved.iter().map(|&x| g.constant(x)).collect();
        let other = other.with_standard_parameters(&standard);
        let (a, b) = (
            build_kernel(&constant, Kernel::InverseDynamics).program,
            build_kernel(&other, Kernel::InverseDynamics).program,
        );
        for s in &states(&constant, 10, 0xfeed) {
            let e = rel_err(&run(&b, &other, s), &run(&a, &constant, s));
            assert!(e < 1e-11, "{}: τ moved by {e:e}", robot.name);
        }
    }
}
