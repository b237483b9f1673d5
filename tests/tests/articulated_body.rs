//! The articulated-body forward dynamics on the built-in robots and on random-axis serial
//! chains: equal to the numeric reference and to the factorised (M + LᵀDL) forward dynamics,
//! and linear in cost, within 3× the chain's inverse-dynamics multiplications (issue 15).
//!
//! The 24- and 48-joint counts take a minute in a debug build:
//! `cargo test -p rne-tests --test articulated_body -- --ignored --nocapture`.

mod common;

use rand::Rng;
use rne_codegen_core::{distribute_constants, kernel_program, Kernel, Program};
use rne_models::{RobotSource, BUILTIN_ROBOTS};
use rne_reference::Reference;
use rne_symbolic::spec::LoadOptions;
use rne_symbolic::{read_robot, Description};
use rne_symbolic::{OpCount, RobotModel, Symbol, SymbolicDynamics};

/// How a random chain's joint frames sit in their parents'.
#[derive(Clone, Copy, Debug)]
enum Origins {
    /// Any roll–pitch–yaw.
    Rotated,
    /// No rotation (`rpy = 0`, as `tools/scale/random_chain.py` writes), and every third
    /// joint's axis that of the joint before it, so that some neighbouring axes are parallel.
    Unrotated,
}

/// A serial chain of `joints` joints with random unit axes and random origins (offsets up
/// to 0.2 m), seeded: revolute but for the indices in `prismatic`.
fn random_axis_chain(
    joints: usize,
    seed: u64,
    origins: Origins,
    prismatic: &[usize],
) -> RobotModel {
    let mut rng = common::rng(seed);
    let mut text = format!("name = \"random-axis-{joints}\"\n");
    let mut previous_axis = [0.0, 0.0, 1.0];
    for k in 0..joints {
        let parent = if k == 0 {
            String::new()
        } else {
            format!("parent = \"l{}\"\n", k - 1)
        };
        let random_axis = loop {
            let a: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let norm = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            if norm > 0.2 {
                break a.map(|x| x / norm);
            }
        };
        let xyz: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-0.2..0.2));
        let random_rpy: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-3.1..3.1));
        let (axis, rpy) = match origins {
            Origins::Rotated => (random_axis, random_rpy),
            Origins::Unrotated if k % 3 == 2 => (previous_axis, [0.0; 3]),
            Origins::Unrotated => (random_axis, [0.0; 3]),
        };
        previous_axis = axis;
        let com: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-0.1..0.1));
        let mass = rng.gen_range(0.5..3.0);
        let kind = if prismatic.contains(&k) {
            "prismatic"
        } else {
            "revolute"
        };
        text.push_str(&format!(
            "[[link]]\nname = \"l{k}\"\n{parent}joint = \"{kind}\"\n\
             origin = {{ xyz = {xyz:?}, rpy = {rpy:?} }}\naxis = {axis:?}\n\
             mass = {mass}\ncom = {com:?}\n\
             inertia = {{ xx = 0.01, yy = 0.012, zz = 0.009, xy = 0.001, xz = -0.0005 }}\n"
        ));
    }
    read_robot(
        Description::toml(&text, "random-axis.toml"),
        &LoadOptions::default(),
    )
    .expect("a valid chain")
}

/// The values of forward-dynamics outputs `qdd` of `d`'s graph at the state `(q, q̇, τ)`.
fn accelerations(
    d: &SymbolicDynamics,
    qdd: &[rne_symbolic::Id],
    (q, qd, tau): (&[f64], &[f64], &[f64]),
) -> Vec<f64> {
    d.model.graph.eval::<f64>(qdd, |s| match s {
        Symbol::Position(k) => q[k as usize],
        Symbol::Velocity(k) => qd[k as usize],
        Symbol::Force(k) => tau[k as usize],
        _ => f64::NAN,
    })
}

/// The optimised program's count of some outputs of a kernel's graph (what `rne stats`
/// reports for a kernel).
fn program_count(d: &mut SymbolicDynamics, outputs: &[rne_symbolic::Id]) -> OpCount {
    let outputs = distribute_constants(&mut d.model.graph, outputs);
    Program::lower(&d.model.graph, &outputs).op_count()
}

/// Multiplications of inverse dynamics, forward dynamics by M + LᵀDL and by the ABA.
fn counts(model: &RobotModel) -> (OpCount, OpCount, OpCount) {
    let d = SymbolicDynamics::new(model);
    let id = kernel_program(&d, Kernel::InverseDynamics).op_count();
    let ldlt = kernel_program(&d, Kernel::ForwardDynamics).op_count();
    let mut aba = d.clone();
    let outputs = aba
        .forward_dynamics_articulated()
        .expect("a fixed-base chain");
    (id, ldlt, program_count(&mut aba, &outputs))
}

/// The articulated-body accelerations against the numeric reference (its own ABA, which
/// shares no code with the symbolic one) and against M + LᵀDL, on chains whose joint frames
/// are rotated every way and on chains with unrotated frames and parallel neighbouring axes
/// (the DH-like joint frames' two cases), all revolute and with prismatic joints between
/// (which keep their frames, and whose neighbours have no common normal with them).
#[test]
fn articulated_body_accelerations_equal_the_reference_and_the_factorised_ones_on_random_axis_chains(
) {
    let cases: [(Origins, &[usize]); 4] = [
        (Origins::Rotated, &[]),
        (Origins::Unrotated, &[]),
        (Origins::Rotated, &[2, 5]),
        (Origins::Unrotated, &[0, 3]),
    ];
    for (origins, prismatic) in cases {
        let model = random_axis_chain(7, 5, origins, prismatic);
        let mut reference = Reference::new(&model.to_numeric());
        let mut d = SymbolicDynamics::new(&model);
        let factorised = d.forward_dynamics();
        let articulated = d.forward_dynamics_articulated().expect("a chain");
        let mut rng = common::rng(6);
        for _ in 0..50 {
            let (q, qd, tau) = common::state(&mut rng, 7);
            let a = accelerations(&d, &factorised, (&q, &qd, &tau));
            let b = accelerations(&d, &articulated, (&q, &qd, &tau));
            let expected = reference.forward_dynamics(&q, &qd, &tau).expect("a state");
            assert!(
                common::rel_err(&b, expected.as_slice()) < 1e-11,
                "{origins:?}, prismatic {prismatic:?}: ABA {b:?}, reference {expected}"
            );
            assert!(
                common::rel_err(&b, &a) < 1e-11,
                "{origins:?}, prismatic {prismatic:?}: ABA {b:?}, M + LᵀDL {a:?}"
            );
        }
    }
}

/// The articulated-body accelerations of every built-in robot it applies to (fixed base, no
/// mimic coupling: URDF placements, trees such as the Panda's hand and its fingers, prismatic
/// joints) against the numeric reference, though the default kernels of these robots take
/// M + LᵀDL.
#[test]
fn articulated_body_accelerations_equal_the_reference_on_the_builtin_robots() {
    let mut checked = Vec::new();
    for robot in BUILTIN_ROBOTS {
        let model = RobotSource::Builtin(robot)
            .load(&LoadOptions::default())
            .unwrap();
        let mut d = SymbolicDynamics::new(&model);
        let Some(articulated) = d.forward_dynamics_articulated() else {
            continue;
        };
        let mut reference = Reference::new(&model.to_numeric());
        let n = model.joint_names().len();
        let mut rng = common::rng(0x5eed_00ab);
        for _ in 0..200 {
            let (q, qd, tau) = common::state(&mut rng, n);
            let qdd = accelerations(&d, &articulated, (&q, &qd, &tau));
            let expected = reference.forward_dynamics(&q, &qd, &tau).expect("a state");
            assert!(
                common::rel_err(&qdd, expected.as_slice()) < 1e-12,
                "{}: ABA {qdd:?}, reference {expected}",
                robot.name
            );
        }
        checked.push(robot.name);
    }
    println!("ABA against the reference: {checked:?}");
    assert!(
        checked.contains(&"panda") && checked.contains(&"ur5"),
        "the tree with prismatic fingers and an arm with parallel axes among {checked:?}"
    );
}

/// Prints a chain's counts (those of docs/performance.md) and holds its ABA to at most 3×
/// its inverse dynamics' multiplications and under M + LᵀDL's.
fn check_linear_cost(joints: usize, origins: Origins) {
    let (id, ldlt, aba) = counts(&random_axis_chain(joints, joints as u64, origins, &[]));
    println!("{joints} joints, {origins:?}: ID {id:?}\nM + LTDL {ldlt:?}\nABA {aba:?}");
    assert!(
        aba.mul <= 3 * id.mul,
        "{joints} joints, {origins:?}: ABA {} against ID {} multiplications",
        aba.mul,
        id.mul
    );
    assert!(aba.mul < ldlt.mul, "{joints} joints, {origins:?}");
}

#[test]
fn articulated_body_forward_dynamics_costs_at_most_three_inverse_dynamics_on_a_12_joint_chain() {
    check_linear_cost(12, Origins::Rotated);
    check_linear_cost(12, Origins::Unrotated);
}

#[test]
#[ignore = "about a minute in a debug build; prints the counts of docs/performance.md"]
fn articulated_body_forward_dynamics_costs_at_most_three_inverse_dynamics_on_long_chains() {
    for origins in [Origins::Rotated, Origins::Unrotated] {
        check_linear_cost(24, origins);
        check_linear_cost(48, origins);
    }
}
