//! The optimiser on the swing-up: its short form (the one CI runs) lowers the cost at every
//! accepted iteration and ends upright within the torque limits; the trajectory it returns is
//! the rollout of its controls; bad problems are errors; the figure is written.

use nalgebra::SVector;
use rne_examples::{
    render_swing_up, solve, Bounds, Discretisation, Error, Options, Problem, Solution, Stop,
    SwingUp, HANGING, TORQUE_LIMIT, UPRIGHT,
};

/// Property: iLQR accepts a step only when the cost falls, so the cost history is
/// non-increasing and falls strictly at each accepted iteration; after the short run the
/// cost is below 1 % of the hanging start's and the final state is upright at rest (within
/// 10⁻³ rad and rad/s); every torque is within ±39.4 N·m and the limit is reached (the arm
/// cannot be lifted without saturating: holding it horizontal takes 88.3 N·m).
#[test]
fn the_quick_swing_up_lowers_the_cost_monotonically_and_ends_upright() {
    let problem = SwingUp::quick();
    let solution = problem.solve().unwrap();
    let costs = solution.cost_history();
    assert_eq!(costs.len(), solution.iterations.len() + 1);
    for (iteration, pair) in solution.iterations.iter().zip(costs.windows(2)) {
        match iteration.step {
            Some(_) => assert!(
                pair[1] < pair[0],
                "an accepted step raised the cost: {pair:?}"
            ),
            None => assert_eq!(pair[1], pair[0], "a rejected step changed the cost"),
        }
    }
    assert!(
        solution.cost() < 0.01 * solution.initial_cost,
        "{} from {}",
        solution.cost(),
        solution.initial_cost
    );
    let last = solution.trajectory.states.last().unwrap();
    for i in 0..4 {
        assert!(
            (last[i] - UPRIGHT[i]).abs() < 1e-3,
            "final state {last} is not upright"
        );
    }
    let torques: Vec<f64> = solution
        .trajectory
        .controls
        .iter()
        .flat_map(|u| u.iter().copied())
        .collect();
    assert!(torques.iter().all(|u| u.abs() <= TORQUE_LIMIT));
    assert!(torques.iter().any(|u| u.abs() == TORQUE_LIMIT));
    assert_eq!(solution.trajectory.states[0], SVector::from(HANGING));
    let timings = solution.total_timings();
    assert!(timings.derivative_kernels <= timings.linearisation);
    assert!(timings.derivative_kernel_calls >= 4 * problem.steps);
}

/// Property: the returned states are the rollout of the returned controls from hanging, so
/// the cost reported is the cost of a trajectory the robot can follow.
#[test]
fn the_returned_trajectory_is_the_rollout_of_its_controls() {
    let problem = SwingUp {
        options: Options {
            max_iterations: 5,
            ..Options::default()
        },
        ..SwingUp::quick()
    };
    let solution = problem.solve().unwrap();
    let dynamics = problem.dynamics().unwrap();
    let trajectory = &solution.trajectory;
    let mut x = SVector::from(HANGING);
    for (k, u) in trajectory.controls.iter().enumerate() {
        x = dynamics.step(&x, u);
        assert_eq!(x, trajectory.states[k + 1], "step {k}");
    }
    let cost = problem
        .cost()
        .total(&trajectory.states, &trajectory.controls);
    assert_eq!(cost, solution.cost());
    assert_eq!(solution.stop, Stop::IterationLimit);
}

#[test]
fn bad_problems_are_errors() {
    let swing_up = SwingUp::quick();
    let dynamics = swing_up.dynamics().unwrap();
    let cost = swing_up.cost();
    let problem = |bounds| Problem {
        dynamics: &dynamics,
        cost: &cost,
        bounds,
        initial_state: HANGING.into(),
    };
    let options = Options::default();
    let controls = vec![SVector::zeros(); 10];
    let good = problem(Bounds::symmetric([TORQUE_LIMIT; 2]));
    assert!(matches!(
        solve(&good, &[], &options),
        Err(Error::EmptyHorizon)
    ));
    let crossed = problem(Bounds::symmetric([TORQUE_LIMIT, -1.0]));
    let error = solve(&crossed, &controls, &options).unwrap_err();
    assert!(matches!(error, Error::InvalidBounds { control: 1, .. }));
    assert!(error.to_string().starts_with("control 1: bounds [1, -1]"));
    let mut far = problem(Bounds::symmetric([TORQUE_LIMIT; 2]));
    far.initial_state[2] = f64::NAN;
    assert!(matches!(
        solve(&far, &controls, &options),
        Err(Error::NonFiniteInitialState)
    ));
    let no_line_search = Options {
        line_search: Vec::new(),
        ..Options::default()
    };
    assert!(matches!(
        solve(&good, &controls, &no_line_search),
        Err(Error::InvalidOptions)
    ));
}

fn short_solution() -> (SwingUp, Solution<4, 2>) {
    let problem = SwingUp {
        options: Options {
            max_iterations: 3,
            ..Options::default()
        },
        ..SwingUp::quick()
    };
    let solution = problem.solve().unwrap();
    (problem, solution)
}

/// The figure is an SVG with the three panels' axes and the saturation lines' legend; a file
/// name that is neither .svg nor .png is an error naming the file.
#[test]
fn the_figure_is_written_as_svg() {
    let (problem, solution) = short_solution();
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join("ilqr_swing_up_test.svg");
    render_swing_up(&solution, problem.time_step, &path).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.starts_with("<svg"));
    for text in [
        "joint angle (rad)",
        "torque (N·m)",
        "cost J",
        "±39.4 N·m (6.26)",
        "u2",
    ] {
        assert!(svg.contains(text), "the figure lacks {text:?}");
    }
    let error = render_swing_up(&solution, problem.time_step, &dir.join("figure.pdf")).unwrap_err();
    assert!(error.to_string().contains("figure.pdf"), "{error}");
}
