//! iLQR swings the thesis's planar elbow from hanging to upright under its ±39.4 N·m motor
//! limits, linearising a Runge–Kutta step of the generated forward dynamics with the generated
//! ∂q̈/∂q, ∂q̈/∂q̇ and M⁻¹ (docs/control.md).
//!
//! ```sh
//! cargo run --release -p rne-examples --example ilqr_swing_up -- --repeat 20 --svg docs/figures/ilqr_swing_up.svg
//! cargo run -p rne-examples --example ilqr_swing_up -- --quick     # the short form CI runs
//! ```

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use clap::Parser;
use rne_examples::{render_swing_up, Solution, SwingUp, Timings, TORQUE_LIMIT, UPRIGHT};

/// How far from upright at rest (rad, rad/s) the end of the swing may be before the run fails.
const UPRIGHT_TOLERANCE: f64 = 1e-2;

/// Swing the planar elbow up by iLQR with the generated derivatives.
#[derive(Parser)]
struct Arguments {
    /// The short form: a 50 ms step and at most 40 iterations.
    #[arg(long)]
    quick: bool,
    /// Write the figure (joint angles, torques, cost per iteration) to this .svg (or .png) file.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Solve this many times and report, per iteration, each phase's shortest time: the
    /// optimiser is deterministic, so the runs do the same work and only the machine's noise
    /// differs.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    repeat: u32,
}

fn main() -> ExitCode {
    let arguments = Arguments::parse();
    let problem = if arguments.quick {
        SwingUp::quick()
    } else {
        SwingUp::full()
    };
    let mut runs = Vec::new();
    for _ in 0..arguments.repeat {
        match problem.solve() {
            Ok(solution) => runs.push(solution),
            Err(error) => {
                eprintln!("error: {error}");
                return ExitCode::FAILURE;
            }
        }
    }
    let solution = &runs[0];
    if runs
        .iter()
        .any(|run| run.cost_history() != solution.cost_history())
    {
        eprintln!("error: the repeated runs differ; the optimiser should be deterministic");
        return ExitCode::FAILURE;
    }
    let timings: Vec<Timings> = (0..solution.iterations.len())
        .map(|i| {
            runs.iter()
                .map(|run| run.iterations[i].timings)
                .reduce(Timings::fastest)
                .expect("at least one run")
        })
        .collect();
    report(&problem, solution, &timings, runs.len());
    if let Some(path) = &arguments.svg {
        if let Err(error) = render_swing_up(solution, problem.time_step, path) {
            eprintln!("error: {error}");
            return ExitCode::FAILURE;
        }
        println!("figure: {}", path.display());
    }
    let last = solution.trajectory.states.last().expect("N + 1 states");
    if (0..4).any(|i| (last[i] - UPRIGHT[i]).abs() > UPRIGHT_TOLERANCE) {
        eprintln!("error: the final state {last:?} is not upright within {UPRIGHT_TOLERANCE}");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}

/// Prints the iterations and the summary: cost, final state, saturation, and where the time
/// went (`timings` per iteration, each phase the shortest of `runs` runs).
fn report(problem: &SwingUp, solution: &Solution<4, 2>, timings: &[Timings], runs: usize) {
    print_iterations(problem, solution, timings);
    print_outcome(solution);
    print_time(solution, timings, runs);
}

/// The problem, then each iteration's cost, step, regularisation, predicted reduction and
/// time.
fn print_iterations(problem: &SwingUp, solution: &Solution<4, 2>, timings: &[Timings]) {
    let h = problem.time_step;
    println!(
        "planar elbow swing-up: RK4 h = {} ms, N = {} ({} s), |u| <= {TORQUE_LIMIT} N m",
        h * 1e3,
        problem.steps,
        h * problem.steps as f64
    );
    println!(" iter        cost   step alpha    mu        expected   time (ms)");
    println!("    0  {:>10.4}", solution.initial_cost);
    for (i, (iteration, time)) in solution.iterations.iter().zip(timings).enumerate() {
        let step = iteration
            .step
            .map_or_else(|| "no step".to_owned(), |a| format!("{a:.4}"));
        println!(
            "{:>5}  {:>10.4}  {step:>10}  {:>8.1e}  {:>10.3e}  {:>8.3}",
            i + 1,
            iteration.cost,
            iteration.regularisation,
            iteration.expected_reduction,
            ms(time.total)
        );
    }
}

/// Why the optimiser stopped, the cost, the final state's distance from upright and the
/// torques' saturation.
fn print_outcome(solution: &Solution<4, 2>) {
    let trajectory = &solution.trajectory;
    let last = trajectory.states.last().expect("N + 1 states");
    let error: Vec<f64> = (0..4).map(|i| last[i] - UPRIGHT[i]).collect();
    let at_limit = trajectory
        .controls
        .iter()
        .flat_map(|u| u.iter())
        .filter(|u| u.abs() >= TORQUE_LIMIT * (1.0 - 1e-9))
        .count();
    let peak = trajectory
        .controls
        .iter()
        .flat_map(|u| u.iter())
        .fold(0.0f64, |m, u| m.max(u.abs()));
    let accepted = solution
        .iterations
        .iter()
        .filter(|i| i.step.is_some())
        .count();
    println!("stop: {:?}", solution.stop);
    println!(
        "iterations: {} ({accepted} accepted); cost {:.4} -> {:.6}",
        solution.iterations.len(),
        solution.initial_cost,
        solution.cost()
    );
    println!(
        "final state - upright: q {:+.2e} {:+.2e} rad, qd {:+.2e} {:+.2e} rad/s",
        error[0], error[1], error[2], error[3]
    );
    println!(
        "torque: peak {peak:.2} N m, {at_limit} of {} controls at the limit",
        2 * trajectory.controls.len()
    );
}

/// Where the time went per iteration: the derivative kernels, the rest of the linearisation,
/// the backward and forward passes, and the rest.
fn print_time(solution: &Solution<4, 2>, timings: &[Timings], runs: usize) {
    let t: Timings = timings.iter().copied().sum();
    let count = solution.iterations.len().max(1) as f64;
    let other = t
        .total
        .saturating_sub(t.linearisation + t.backward_pass + t.forward_pass);
    println!(
        "time per iteration: {:.3} ms (total {:.1} ms; each time the shortest of {runs} run{})",
        ms(t.total) / count,
        ms(t.total),
        if runs == 1 { "" } else { "s" }
    );
    println!(
        "  generated derivative kernels: {:>8.1} ms ({:4.1} %), {} calls, {:.0} ns/call",
        ms(t.derivative_kernels),
        share(t.derivative_kernels, t.total),
        t.derivative_kernel_calls,
        t.derivative_kernels.as_secs_f64() * 1e9 / t.derivative_kernel_calls.max(1) as f64
    );
    let chain_rule = t.linearisation.saturating_sub(t.derivative_kernels);
    for (name, time) in [
        ("stage states and chain rule", chain_rule),
        ("backward pass", t.backward_pass),
        ("forward pass (line search)", t.forward_pass),
        ("other", other),
    ] {
        println!(
            "  {name:<29} {:>8.1} ms ({:4.1} %)",
            ms(time),
            share(time, t.total)
        );
    }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn share(part: Duration, whole: Duration) -> f64 {
    100.0 * part.as_secs_f64() / whole.as_secs_f64().max(f64::MIN_POSITIVE)
}
