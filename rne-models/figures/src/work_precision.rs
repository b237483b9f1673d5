//! Work-precision charts: cost against error on logarithmic axes, rendered with plotters as SVG
//! and PNG.
//!
//! A [`Chart`] is a title over panels side by side; a panel holds [`Series`] of points, each
//! point with an optional horizontal and vertical range drawn as a bar (an interquartile range
//! of times, or the span from the median to the largest error). Values that a logarithmic axis
//! cannot show (zero, negative, not finite) are drawn at the panel's floor and the panel's note
//! says so. [`render`](crate::render()) writes a chart as SVG and PNG.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::render::{draw_legend, Draw, PALETTE};

/// Width of one panel in pixels.
const PANEL_WIDTH: u32 = 900;
/// Height of the chart in pixels.
const HEIGHT: u32 = 620;
/// Height of the chart title in pixels.
const TITLE_HEIGHT: u32 = 40;

/// The shape of a point.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Marker {
    /// A filled circle.
    Circle,
    /// A filled square.
    Square,
    /// A filled triangle.
    Triangle,
    /// A cross.
    Cross,
}

/// One point.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Point {
    /// Horizontal value.
    pub x: f64,
    /// Vertical value.
    pub y: f64,
    /// Horizontal bar (low, high), if any.
    pub x_bar: Option<(f64, f64)>,
    /// Vertical bar (low, high), if any.
    pub y_bar: Option<(f64, f64)>,
    /// Its shape.
    pub marker: Marker,
}

/// Points of one colour, under one legend entry.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The legend entry.
    pub label: String,
    /// Index into [`crate::PALETTE`].
    pub colour: usize,
    /// The points.
    pub points: Vec<Point>,
    /// Whether a line joins the points, in order.
    pub joined: bool,
}

/// One log-log panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// The horizontal axis label.
    pub x_label: String,
    /// The vertical axis label.
    pub y_label: String,
    /// The series.
    pub series: Vec<Series>,
    /// Legend entries for the markers (grey, after the series): shape and meaning.
    pub marker_legend: Vec<(Marker, String)>,
    /// Vertical values below this are drawn at it.
    pub y_floor: f64,
}

/// A titled row of panels.
#[derive(Clone, Debug, PartialEq)]
pub struct Chart {
    /// The file name without extension.
    pub file: String,
    /// The title.
    pub title: String,
    /// The panels, left to right.
    pub panels: Vec<Panel>,
}

impl Draw for Chart {
    fn file(&self) -> &str {
        &self.file
    }

    fn size(&self) -> (u32, u32) {
        (PANEL_WIDTH * self.panels.len().max(1) as u32, HEIGHT)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (title, body) = root.split_vertically(TITLE_HEIGHT);
        title.titled(&self.title, ("sans-serif", 22).into_font())?;
        let areas = body.split_evenly((1, self.panels.len().max(1)));
        for (panel, area) in self.panels.iter().zip(&areas) {
            draw_panel(panel, area)?;
        }
        Ok(())
    }
}

/// `v` if a log axis can show it above `floor`, else `floor`.
fn clamp(v: f64, floor: f64) -> f64 {
    if v.is_finite() && v > floor {
        v
    } else {
        floor
    }
}

/// A decade-aligned range around the positive finite values of `values` (or around
/// `fallback` when there is none).
fn log_range(values: impl Iterator<Item = f64>, fallback: f64) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    let (lo, hi) = if hi > 0.0 {
        (lo, hi)
    } else {
        (fallback, fallback)
    };
    (
        10f64.powf((lo.log10() - 0.15).floor()),
        10f64.powf((hi.log10() + 0.15).ceil()),
    )
}

/// A label for a log axis: plain below 10⁵ and at or above 1, else in scientific notation.
fn log_label(v: &f64) -> String {
    if (1.0..1e5).contains(v) {
        format!("{v:.0}")
    } else {
        format!("{v:.0e}")
    }
}

/// Draws one panel into `area`.
fn draw_panel<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let floor = panel.y_floor;
    let points = || panel.series.iter().flat_map(|s| s.points.iter());
    let x_range = log_range(
        points()
            .flat_map(|p| [Some(p.x), p.x_bar.map(|b| b.0), p.x_bar.map(|b| b.1)])
            .flatten(),
        1.0,
    );
    let y_range = log_range(
        points()
            .flat_map(|p| [Some(p.y), p.y_bar.map(|b| b.0), p.y_bar.map(|b| b.1)])
            .flatten()
            .map(|y| clamp(y, floor)),
        floor,
    );
    let mut chart = ChartBuilder::on(area)
        .margin(14)
        .margin_right(24)
        .x_label_area_size(44)
        .y_label_area_size(78)
        .build_cartesian_2d(
            (x_range.0..x_range.1).log_scale(),
            (y_range.0..y_range.1).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .x_label_formatter(&log_label)
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;
    for series in &panel.series {
        draw_series(&mut chart, series, floor)?;
    }
    let grey = RGBColor(90, 90, 90);
    for (marker, meaning) in &panel.marker_legend {
        let marker = *marker;
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
            .label(meaning.as_str())
            .legend(move |(x, y)| marker_element((x + 8, y), marker, grey.filled()));
    }
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight)
}

/// Draws `series` into `chart`: each point's bars, the line joining the points when the
/// series is joined, the markers, and its legend entry; values below `floor` at it.
fn draw_series<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>,
    series: &Series,
    floor: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let colour = PALETTE[series.colour % PALETTE.len()];
    let bar = colour.mix(0.6).stroke_width(1);
    for p in &series.points {
        let y = clamp(p.y, floor);
        if let Some((lo, hi)) = p.x_bar {
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(lo, y), (hi, y)],
                bar,
            )))?;
        }
        if let Some((lo, hi)) = p.y_bar {
            let (lo, hi) = (clamp(lo, floor), clamp(hi, floor));
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(p.x, lo), (p.x, hi)],
                bar,
            )))?;
        }
    }
    if series.joined {
        let line: Vec<(f64, f64)> = series
            .points
            .iter()
            .map(|p| (p.x, clamp(p.y, floor)))
            .collect();
        chart.draw_series(std::iter::once(PathElement::new(
            line,
            colour.stroke_width(2),
        )))?;
    }
    for p in &series.points {
        draw_marker(chart, p.marker, (p.x, clamp(p.y, floor)), colour.filled())?;
    }
    chart
        .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
        .label(series.label.as_str())
        .legend(move |(x, y)| Circle::new((x + 8, y), 5, colour.filled()));
    Ok(())
}

/// A marker of pixel size 5 at the backend coordinate `at`.
fn marker_element<DB: DrawingBackend>(
    at: (i32, i32),
    marker: Marker,
    style: ShapeStyle,
) -> DynElement<'static, DB, (i32, i32)> {
    match marker {
        Marker::Circle => Circle::new(at, 5, style).into_dyn(),
        Marker::Square => {
            Rectangle::new([(at.0 - 4, at.1 - 4), (at.0 + 4, at.1 + 4)], style).into_dyn()
        }
        Marker::Triangle => TriangleMarker::new(at, 6, style).into_dyn(),
        Marker::Cross => Cross::new(at, 5, style.stroke_width(2)).into_dyn(),
    }
}

/// Draws one marker at the data point `at`.
fn draw_marker<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>,
    marker: Marker,
    at: (f64, f64),
    style: ShapeStyle,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    chart.draw_series(std::iter::once(
        EmptyElement::at(at) + marker_element::<DB>((0, 0), marker, style),
    ))?;
    Ok(())
}
