//! The swing-up's figure, an SVG (or PNG) of three panels drawn by rne-figures: joint angles
//! against time with the upright targets, torques against time with the ±39.4 N·m limits, and
//! the cost per iteration.

use std::path::Path;

use rne_figures::time_series::{Curve, Figure, Panel};
use rne_figures::{render_file, Mark};

use crate::error::Error;
use crate::ilqr::Solution;
use crate::swing_up::{TORQUE_LIMIT, UPRIGHT};

/// Writes the figure of `solution` (a planar elbow swing-up with time step `time_step`) to
/// `path`, as SVG or PNG by the file's extension.
pub fn render_swing_up(
    solution: &Solution<4, 2>,
    time_step: f64,
    path: &Path,
) -> Result<(), Error> {
    render_file(&swing_up_figure(solution, time_step), path).map_err(|e| Error::Plot {
        path: path.to_owned(),
        message: e.to_string(),
    })
}

/// The three panels of the swing-up with time step `h`.
fn swing_up_figure(solution: &Solution<4, 2>, h: f64) -> Figure {
    let steps = solution.trajectory.controls.len();
    let title = format!(
        "iLQR swing-up of the planar elbow: RK4, h = {} ms, N = {steps}, {} iterations, cost {:.4}",
        h * 1e3,
        solution.iterations.len(),
        solution.cost()
    );
    let times: Vec<f64> = (0..solution.trajectory.states.len())
        .map(|k| h * k as f64)
        .collect();
    let mut angles: Vec<Curve> = (0..2)
        .map(|j| {
            let q = solution.trajectory.states.iter().map(|x| x[j]);
            Curve::new(format!("q{}", j + 1), &times, q)
        })
        .collect();
    angles.push(Curve::reference("upright (π/2, 0)", &times, UPRIGHT[0]));
    angles.push(Curve::reference("", &times, UPRIGHT[1]));

    // Each control held over its step: two points per step.
    let mut torques: Vec<Curve> = (0..2)
        .map(|j| Curve {
            label: format!("u{}", j + 1),
            points: solution
                .trajectory
                .controls
                .iter()
                .enumerate()
                .flat_map(|(k, u)| [(h * k as f64, u[j]), (h * (k + 1) as f64, u[j])])
                .collect(),
            style: Mark::Line,
        })
        .collect();
    torques.push(Curve::reference("±39.4 N·m (6.26)", &times, TORQUE_LIMIT));
    torques.push(Curve::reference("", &times, -TORQUE_LIMIT));

    let costs = solution.cost_history();
    let iterations: Vec<f64> = (0..costs.len()).map(|i| i as f64).collect();
    let cost = Curve::new(
        "cost after each iteration",
        &iterations,
        costs.iter().copied(),
    );
    Figure {
        file: "ilqr_swing_up".to_owned(),
        title,
        panels: vec![
            Panel::new("joint angle (rad)", angles),
            Panel::new("torque (N·m)", torques),
            Panel::log("cost J", vec![cost]).with_x_label("iteration"),
        ],
    }
}
