//! The report's figures: errors on a logarithmic vertical axis against a logarithmic or linear
//! horizontal one, as scattered points, lines and dashed reference lines (such as ε·cond),
//! written as SVG and PNG by [`render`](crate::render()).

use plotters::coord::Shift;
use plotters::prelude::*;

pub use crate::render::Mark;
use crate::render::{draw_chart, ChartAxis, Draw};

/// Size of a rendered figure in pixels.
const SIZE: (u32, u32) = (960, 600);

/// One labelled set of points.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The legend entry.
    pub label: String,
    /// The points (x, y).
    pub points: Vec<(f64, f64)>,
    /// How they are drawn.
    pub mark: Mark,
}

impl Series {
    /// A series of `points` drawn with `mark`.
    pub fn new(label: impl Into<String>, mark: Mark, points: Vec<(f64, f64)>) -> Series {
        Series {
            label: label.into(),
            points,
            mark,
        }
    }
}

/// The horizontal axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// Linear.
    Linear,
    /// Logarithmic; points with x ≤ 0 are left out.
    Log,
}

/// A figure with a logarithmic vertical axis: points with y ≤ 0 or non-finite coordinates
/// are left out. Labels should avoid combining characters (q̈) and subscripts, which the
/// embedded font lacks.
#[derive(Clone, Debug, PartialEq)]
pub struct LogPlot {
    /// The file name without extension, `stress-...`.
    pub file: String,
    /// The title.
    pub title: String,
    /// The horizontal axis label, with its unit.
    pub x_label: String,
    /// The vertical axis label, with its unit.
    pub y_label: String,
    /// The horizontal scale.
    pub x_axis: Axis,
    /// The series, drawn in order.
    pub series: Vec<Series>,
}

impl LogPlot {
    /// Each series' label and mark with its `visible` points.
    fn marked<'b>(
        &'b self,
        visible: &'b [Vec<(f64, f64)>],
    ) -> impl Iterator<Item = (&'b str, Mark, &'b [(f64, f64)])> {
        self.series
            .iter()
            .zip(visible)
            .map(|(s, points)| (s.label.as_str(), s.mark, points.as_slice()))
    }

    /// The points of each series that the axes can show.
    fn visible(&self) -> Vec<Vec<(f64, f64)>> {
        self.series
            .iter()
            .map(|s| {
                s.points
                    .iter()
                    .copied()
                    .filter(|&(x, y)| {
                        x.is_finite()
                            && y.is_finite()
                            && y > 0.0
                            && (self.x_axis == Axis::Linear || x > 0.0)
                    })
                    .collect()
            })
            .collect()
    }
}

impl Draw for LogPlot {
    fn file(&self) -> &str {
        &self.file
    }

    fn size(&self) -> (u32, u32) {
        SIZE
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let visible = self.visible();
        let ((x0, x1), (y0, y1)) = bounds(&visible);
        let mut builder = ChartBuilder::on(root);
        builder
            .caption(&self.title, ("sans-serif", 22))
            .margin(14)
            .margin_right(28)
            .x_label_area_size(48)
            .y_label_area_size(90);
        // Decades padded by a quarter on each side.
        let (y0, y1) = (y0 / 10f64.powf(0.25), y1 * 10f64.powf(0.25));
        let y = ChartAxis {
            range: (y0..y1).log_scale(),
            title: &self.y_label,
            ticks: &|y| format!("{y:.0e}"),
        };
        let sets = self.marked(&visible);
        let legend = SeriesLabelPosition::UpperLeft;
        match self.x_axis {
            Axis::Log => {
                let x = (x0 / 10f64.powf(0.1))..(x1 * 10f64.powf(0.1));
                let x = ChartAxis {
                    range: x.log_scale(),
                    title: &self.x_label,
                    ticks: &|x| format!("{x:.0e}"),
                };
                draw_chart(&mut builder, x, y, sets, legend)
            }
            Axis::Linear => {
                let pad = 0.03 * (x1 - x0);
                let x = ChartAxis {
                    range: (x0 - pad)..(x1 + pad),
                    title: &self.x_label,
                    ticks: &|x| format!("{x:.0}"),
                };
                draw_chart(&mut builder, x, y, sets, legend)
            }
        }
    }
}

/// The smallest and largest x and y over the visible points (a unit box if there are none, a
/// decade around a single value).
fn bounds(visible: &[Vec<(f64, f64)>]) -> ((f64, f64), (f64, f64)) {
    let mut points = visible.iter().flatten();
    let Some(&(x, y)) = points.next() else {
        return ((1.0, 10.0), (1.0, 10.0));
    };
    let ((x0, x1), (y0, y1)) = points.fold(((x, x), (y, y)), |((a, b), (c, d)), &(x, y)| {
        ((a.min(x), b.max(x)), (c.min(y), d.max(y)))
    });
    let widen = |lo: f64, hi: f64| {
        if hi > lo {
            (lo, hi)
        } else {
            (lo / 10f64.sqrt(), hi * 10f64.sqrt())
        }
    };
    (widen(x0, x1), widen(y0, y1))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points a log axis cannot show are left out; bounds widen a single value to a decade.
    #[test]
    fn visible_points_and_bounds() {
        let plot = LogPlot {
            file: "t".into(),
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            x_axis: Axis::Log,
            series: vec![Series::new(
                "s",
                Mark::Points,
                vec![(1.0, 1e-16), (0.0, 1.0), (2.0, 0.0), (3.0, f64::NAN)],
            )],
        };
        let visible = plot.visible();
        assert_eq!(visible, vec![vec![(1.0, 1e-16)]]);
        let ((x0, x1), _) = bounds(&visible);
        assert!(x0 < 1.0 && x1 > 1.0);
    }
}
