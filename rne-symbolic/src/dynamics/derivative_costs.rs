//! How the operations of the torque derivatives divide between ∂τ/∂q and ∂τ/∂q̇ and between
//! the ways of building them, on the two arms the derivative targets name: the figures of
//! docs/performance.md ("Derivatives"), printed by
//! `cargo test -p rne-symbolic --release derivative_costs -- --nocapture`, and the facts the
//! choice of sweep in [`SymbolicDynamics::inverse_dynamics_derivatives`] rests on. Costs are
//! [`crate::OpCount::cost`] of the graph before the kernels' optimisation.

use super::derivatives::{self, Sweep};
use super::SymbolicDynamics;
use crate::expr::{Differentiator, ExprGraph, Id, Symbol};

type Matrix = Vec<Vec<Id>>;

/// The ways of building (∂τ/∂q, ∂τ/∂q̇) compared.
#[derive(Clone, Copy, Debug)]
enum Construction {
    /// Both by one forward sweep per symbol.
    Forward,
    /// Both by one reverse sweep per torque.
    Reverse,
    /// ∂τ/∂q alone, by reverse sweeps.
    ReverseQ,
    /// ∂τ/∂q̇ alone, by reverse sweeps.
    ReverseV,
    /// ∂τ/∂q alone, by forward sweeps.
    ForwardQ,
    /// ∂τ/∂q̇ alone, by forward sweeps.
    ForwardV,
    /// ∂τ/∂q̇ alone as 2C (Christoffel C, fixed base: ∂(C(q, q̇) q̇)/∂q̇ = 2C).
    TwiceC,
    /// ∂τ/∂q by forward sweeps and ∂τ/∂q̇ as 2C.
    ForwardQTwiceC,
}

/// The cost of `construction` on `robot` (a fixture of `tests/fixtures/robots/`).
fn cost(robot: &str, construction: Construction) -> usize {
    let model = super::fixture_robot(robot);
    let mut d = SymbolicDynamics::new(&model);
    let tau = d.inverse_dynamics();
    let layout = d.layout();
    let positions: Vec<Symbol> = (0..layout.nv())
        .map(|k| Symbol::Position(k as u16))
        .collect();
    let velocities: Vec<Symbol> = (0..layout.nv())
        .map(|k| Symbol::Velocity(k as u16))
        .collect();
    let twice_c = |d: &mut SymbolicDynamics| -> Matrix {
        let c = d.coriolis_matrix();
        let g = &mut d.model.graph;
        let two = g.constant(2.0);
        c.iter()
            .map(|row| row.iter().map(|&x| g.mul(two, x)).collect())
            .collect()
    };
    let reverse = |g: &mut ExprGraph, wrt: &[Symbol]| -> Matrix {
        tau.iter().map(|&t| g.gradient(t, wrt)).collect()
    };
    let forward = |g: &mut ExprGraph, wrt: &[Symbol]| -> Matrix {
        wrt.iter()
            .map(|&s| {
                let mut differentiator = Differentiator::new(s);
                tau.iter()
                    .map(|&t| differentiator.derivative(g, t))
                    .collect()
            })
            .collect()
    };
    let built: Vec<Matrix> = match construction {
        Construction::Forward | Construction::Reverse => {
            let sweep = match construction {
                Construction::Forward => Sweep::Forward,
                _ => Sweep::Reverse,
            };
            let g = &mut d.model.graph;
            let (dq, dv) = derivatives::state_jacobians(g, &tau, layout, sweep);
            vec![dq, dv]
        }
        Construction::ReverseQ => vec![reverse(&mut d.model.graph, &positions)],
        Construction::ReverseV => vec![reverse(&mut d.model.graph, &velocities)],
        Construction::ForwardQ => vec![forward(&mut d.model.graph, &positions)],
        Construction::ForwardV => vec![forward(&mut d.model.graph, &velocities)],
        Construction::TwiceC => vec![twice_c(&mut d)],
        Construction::ForwardQTwiceC => {
            let c = twice_c(&mut d);
            vec![forward(&mut d.model.graph, &positions), c]
        }
    };
    let outputs: Vec<Id> = built.concat().concat();
    let cost = d.model.graph.op_count(&outputs).cost();
    eprintln!("{robot}: {construction:?} costs {cost}");
    cost
}

/// The Panda arm keeps reverse sweeps because nothing else is cheaper: given ∂τ/∂q, they give
/// ∂τ/∂q̇ for a few per cent more, where 2C or forward sweeps would add thousands — though
/// forward sweeps alone build ∂τ/∂q for less.
#[test]
fn reverse_sweeps_are_the_cheapest_panda_arm_derivatives_and_give_dv_almost_free() {
    let robot = "panda-arm.urdf";
    let reverse = cost(robot, Construction::Reverse);
    let reverse_q = cost(robot, Construction::ReverseQ);
    assert!(reverse < reverse_q + reverse_q / 10, "∂τ/∂q̇ beside ∂τ/∂q");
    assert!(
        cost(robot, Construction::ReverseV) > reverse_q / 2,
        "∂τ/∂q̇ alone"
    );
    assert!(
        cost(robot, Construction::TwiceC) > reverse_q / 4,
        "2C alone"
    );
    for other in [Construction::Forward, Construction::ForwardQTwiceC] {
        assert!(reverse < cost(robot, other), "{other:?}");
    }
    assert!(
        cost(robot, Construction::ForwardQ) < reverse_q,
        "forward sweeps build ∂τ/∂q alone for less"
    );
    assert!(
        cost(robot, Construction::ForwardV) > reverse - reverse_q,
        "∂τ/∂q̇ by forward sweeps costs more than beside the reverse ones"
    );
}

/// UR5 keeps forward sweeps: its derivatives are sparse, and they are cheaper than the
/// reverse sweeps; ∂τ/∂q̇ as 2C beside them is printed for comparison.
#[test]
fn forward_sweeps_are_cheaper_than_reverse_ones_for_ur5() {
    let robot = "ur5.urdf";
    cost(robot, Construction::ForwardQTwiceC);
    assert!(cost(robot, Construction::Forward) < cost(robot, Construction::Reverse));
}

/// Forward sweeps bounded by the reverse sweeps' cost give up only when the reverse sweeps
/// are the cheaper, and otherwise cost what the whole forward sweeps cost: the choice is the
/// one the whole would give. On the Panda arm, where the reverse sweeps win, they give up.
#[test]
fn bounded_forward_sweeps_give_up_only_when_the_reverse_ones_are_cheaper() {
    let robots = [
        ("panda-arm", super::fixture_robot("panda-arm.urdf")),
        ("ur5", super::fixture_robot("ur5.urdf")),
        ("legged, floating", super::floating_tests::legged()),
    ];
    for (robot, model) in robots {
        let whole = |sweep| {
            SymbolicDynamics::new(&model)
                .with_derivative_sweep(sweep)
                .inverse_dynamics_derivatives_cost()
        };
        let (forward, reverse) = (whole(Sweep::Forward), whole(Sweep::Reverse));
        let bounded =
            SymbolicDynamics::new(&model).forward_derivatives_cost_within(&mut || Some(reverse));
        eprintln!("{robot}: bounded by {reverse}: {bounded:?} (whole: {forward})");
        match bounded {
            Some(c) => assert_eq!(c, forward, "{robot}"),
            None => assert!(reverse < forward, "{robot} gave up"),
        }
        let unbounded = SymbolicDynamics::new(&model).forward_derivatives_cost_within(&mut || None);
        assert_eq!(unbounded, Some(forward), "{robot}");
        if robot == "panda-arm" {
            assert_eq!(bounded, None, "the Panda arm's forward sweeps stop early");
        }
    }
}
