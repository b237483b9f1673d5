//! The swing-up's figure, an SVG (or PNG) of three panels: joint angles against time with the upright
//! targets, torques against time with the ±39.4 N·m limits, and the cost per iteration.
//!
//! Text is drawn with the reports' font, registered by [`rne_figures::register_font`].

use std::ops::Range;
use std::path::Path;

use plotters::chart::SeriesAnno;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::error::Error;
use crate::ilqr::Solution;
use crate::swing_up::{TORQUE_LIMIT, UPRIGHT};

/// Width of the figure in pixels.
const WIDTH: u32 = 1000;
/// Height of one panel in pixels.
const PANEL_HEIGHT: u32 = 300;
/// Height of the title in pixels.
const TITLE_HEIGHT: u32 = 40;
/// Joint 1's and joint 2's colours (Tableau 10).
const JOINT_COLOURS: [RGBColor; 2] = [RGBColor(31, 119, 180), RGBColor(214, 39, 40)];
/// The colour of references: targets and limits.
const REFERENCE: RGBColor = RGBColor(110, 110, 110);
/// The colour of the cost curve.
const COST_COLOUR: RGBColor = RGBColor(44, 160, 44);

/// Writes the figure of `solution` (a planar elbow swing-up with time step `time_step`) to
/// `path`, as SVG or PNG by the file's extension.
pub fn render_swing_up(
    solution: &Solution<4, 2>,
    time_step: f64,
    path: &Path,
) -> Result<(), Error> {
    let plot_error = |message: String| Error::Plot {
        path: path.to_owned(),
        message,
    };
    rne_figures::register_font().map_err(|e| plot_error(e.to_string()))?;
    let size = (WIDTH, TITLE_HEIGHT + 3 * PANEL_HEIGHT);
    match path.extension().and_then(|e| e.to_str()) {
        Some("svg") => draw(
            solution,
            time_step,
            &SVGBackend::new(path, size).into_drawing_area(),
        )
        .map_err(|e| plot_error(e.to_string())),
        Some("png") => draw(
            solution,
            time_step,
            &BitMapBackend::new(path, size).into_drawing_area(),
        )
        .map_err(|e| plot_error(e.to_string())),
        _ => Err(plot_error("the file name must end in .svg or .png".into())),
    }
}

/// Draws the three panels on `root` and writes the file.
fn draw<DB: DrawingBackend>(
    solution: &Solution<4, 2>,
    h: f64,
    root: &DrawingArea<DB, Shift>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let steps = solution.trajectory.controls.len();
    let title = format!(
        "iLQR swing-up of the planar elbow: RK4, h = {} ms, N = {steps}, {} iterations, cost {:.4}",
        h * 1e3,
        solution.iterations.len(),
        solution.cost()
    );
    let body = root.titled(&title, ("sans-serif", 20))?;
    let panels = body.split_evenly((3, 1));
    let horizon = h * steps as f64;
    let times = |k: usize| h * k as f64;

    let angles: [Vec<(f64, f64)>; 2] = core::array::from_fn(|j| {
        let states = &solution.trajectory.states;
        states
            .iter()
            .enumerate()
            .map(|(k, x)| (times(k), x[j]))
            .collect()
    });
    let (lo, hi) = extent(angles.iter().flatten().map(|p| p.1));
    let mut chart = time_chart(&panels[0], 0.0..horizon, lo..hi, "joint angle (rad)")?;
    for (j, points) in angles.iter().enumerate() {
        let style = JOINT_COLOURS[j].stroke_width(2);
        legend(
            chart.draw_series(LineSeries::new(points.clone(), style))?,
            &format!("q{}", j + 1),
            style,
        );
    }
    for (j, target) in UPRIGHT[..2].iter().enumerate() {
        let line = vec![(0.0, *target), (horizon, *target)];
        let series = chart.draw_series(DashedLineSeries::new(line, 6, 4, REFERENCE.into()))?;
        if j == 0 {
            legend(series, "upright (π/2, 0)", REFERENCE.into());
        }
    }
    labels(&mut chart, SeriesLabelPosition::LowerRight)?;

    let margin = 0.1 * TORQUE_LIMIT;
    let limits = -TORQUE_LIMIT - margin..TORQUE_LIMIT + margin;
    let mut chart = time_chart(&panels[1], 0.0..horizon, limits, "torque (N·m)")?;
    for j in 0..2 {
        let style = JOINT_COLOURS[j].stroke_width(2);
        let held = solution
            .trajectory
            .controls
            .iter()
            .enumerate()
            .flat_map(|(k, u)| [(times(k), u[j]), (times(k + 1), u[j])]);
        legend(
            chart.draw_series(LineSeries::new(held, style))?,
            &format!("u{}", j + 1),
            style,
        );
    }
    for limit in [TORQUE_LIMIT, -TORQUE_LIMIT] {
        let line = vec![(0.0, limit), (horizon, limit)];
        let series = chart.draw_series(DashedLineSeries::new(line, 6, 4, REFERENCE.into()))?;
        if limit > 0.0 {
            legend(series, "±39.4 N·m (6.26)", REFERENCE.into());
        }
    }
    labels(&mut chart, SeriesLabelPosition::UpperRight)?;

    let costs = solution.cost_history();
    let lo = costs.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = costs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let iterations = 0.0..(costs.len() - 1).max(1) as f64;
    let mut chart = ChartBuilder::on(&panels[2])
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(iterations, (lo / 1.5..hi * 1.5).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("iteration")
        .x_label_formatter(&|i| format!("{i:.0}"))
        .y_desc("cost J")
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    let style = COST_COLOUR.stroke_width(2);
    let points = costs.iter().enumerate().map(|(i, c)| (i as f64, *c));
    legend(
        chart.draw_series(LineSeries::new(points, style))?,
        "cost after each iteration",
        style,
    );
    labels(&mut chart, SeriesLabelPosition::UpperRight)?;
    root.present()
}

/// A chart with linear axes: time and a quantity.
type TimeChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A panel's chart against time with linear axes.
fn time_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    x: Range<f64>,
    y: Range<f64>,
    y_label: &str,
) -> Result<TimeChart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x, y)?;
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc(y_label)
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    Ok(chart)
}

/// Gives a drawn series its legend entry.
fn legend<DB: DrawingBackend>(series: &mut SeriesAnno<'_, DB>, label: &str, style: ShapeStyle) {
    series
        .label(label)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], style));
}

/// Draws a chart's legend at `position`.
fn labels<'a, DB: DrawingBackend + 'a, X: Ranged, Y: Ranged>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    position: SeriesLabelPosition,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    chart
        .configure_series_labels()
        .position(position)
        .label_font(("sans-serif", 14))
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(160, 160, 160))
        .draw()
}

/// The range of the values, padded by a tenth of their spread (or by 1 when they are equal).
fn extent(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    let pad = if hi > lo { 0.1 * (hi - lo) } else { 1.0 };
    (lo - pad, hi + pad)
}
