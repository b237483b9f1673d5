//! Time-series figures and their rendering with plotters, as SVG and PNG.
//!
//! A [`Figure`] is a title over panels stacked vertically, each panel a set of curves against
//! time (or, as [`Panel::with_x_label`] says, another variable such as an iteration count). It
//! knows nothing about robots: the scenarios, identification and the examples build figures
//! from their records.
//!
//! [`render`](crate::render()) writes it as SVG and PNG.

use plotters::coord::Shift;
use plotters::prelude::*;

pub use crate::render::Mark;
use crate::render::{draw_chart, ChartAxis, Draw};

/// Width of a rendered figure in pixels.
const WIDTH: u32 = 1000;
/// Height of one panel in pixels.
const PANEL_HEIGHT: u32 = 300;
/// Height of the figure title in pixels.
const TITLE_HEIGHT: u32 = 44;
/// Curves with more points than this are reduced to the minimum and maximum of
/// `MAX_POINTS / 2` equal-length buckets, which keeps the envelope of the curve (a pixel column
/// holds several buckets at [`WIDTH`]).
const MAX_POINTS: usize = 4000;

/// One curve y(t) of a panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// The legend entry.
    pub label: String,
    /// The samples (t, y).
    pub points: Vec<(f64, f64)>,
    /// How it is drawn.
    pub style: Mark,
}

impl Curve {
    /// A solid curve through `(t[k], y[k])`.
    pub fn new(label: impl Into<String>, t: &[f64], y: impl IntoIterator<Item = f64>) -> Self {
        Self {
            label: label.into(),
            points: t.iter().copied().zip(y).collect(),
            style: Mark::Line,
        }
    }

    /// A reference line at the constant `y` over the times `t`.
    pub fn reference(label: impl Into<String>, t: &[f64], y: f64) -> Self {
        let ends = [t.first(), t.last()];
        Self {
            label: label.into(),
            points: ends.into_iter().flatten().map(|&t| (t, y)).collect(),
            style: Mark::Reference,
        }
    }
}

/// The vertical axis of a panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Linear.
    Linear,
    /// Logarithmic; points with y ≤ 0 are left out.
    Log,
}

/// One chart of a figure: curves against time t (s), or the variable of `x_label`.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// The label of the horizontal axis, with its unit: `t (s)` unless set.
    pub x_label: String,
    /// The label of the vertical axis, with its unit.
    pub y_label: String,
    /// The vertical scale.
    pub scale: Scale,
    /// The curves.
    pub curves: Vec<Curve>,
}

impl Panel {
    /// A linear panel.
    pub fn new(y_label: impl Into<String>, curves: Vec<Curve>) -> Self {
        Self {
            x_label: "t (s)".to_owned(),
            y_label: y_label.into(),
            scale: Scale::Linear,
            curves,
        }
    }

    /// The panel against the variable `x_label` (with its unit) instead of time.
    pub fn with_x_label(self, x_label: impl Into<String>) -> Self {
        Self {
            x_label: x_label.into(),
            ..self
        }
    }

    /// A panel with a logarithmic vertical axis.
    pub fn log(y_label: impl Into<String>, curves: Vec<Curve>) -> Self {
        Self {
            scale: Scale::Log,
            ..Self::new(y_label, curves)
        }
    }
}

/// A titled figure of panels stacked vertically, each with its own horizontal range.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// The file name without extension, e.g. `fig6.4-released-from-zero`.
    pub file: String,
    /// The title, starting with the thesis's figure number.
    pub title: String,
    /// The panels, top to bottom.
    pub panels: Vec<Panel>,
}

impl Draw for Figure {
    fn file(&self) -> &str {
        &self.file
    }

    fn size(&self) -> (u32, u32) {
        (
            WIDTH,
            TITLE_HEIGHT + PANEL_HEIGHT * self.panels.len().max(1) as u32,
        )
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let body = root.titled(&self.title, ("sans-serif", 18).into_font())?;
        let areas = body.split_evenly((self.panels.len().max(1), 1));
        for (panel, area) in self.panels.iter().zip(&areas) {
            draw_panel(panel, area)?;
        }
        Ok(())
    }
}

/// Each curve's label and style with its visible `points`.
fn marked<'b>(
    panel: &'b Panel,
    points: &'b [Vec<(f64, f64)>],
) -> impl Iterator<Item = (&'b str, Mark, &'b [(f64, f64)])> {
    panel
        .curves
        .iter()
        .zip(points)
        .map(|(c, p)| (c.label.as_str(), c.style, p.as_slice()))
}

/// The points of a curve that the scale can show, reduced to at most [`MAX_POINTS`].
fn visible_points(curve: &Curve, scale: Scale) -> Vec<(f64, f64)> {
    let shown: Vec<(f64, f64)> = curve
        .points
        .iter()
        .copied()
        .filter(|&(t, y)| t.is_finite() && y.is_finite() && (scale == Scale::Linear || y > 0.0))
        .collect();
    decimate(&shown, MAX_POINTS)
}

/// Keeps the first minimum and maximum (in time order) of each of `max_points / 2` buckets of
/// equal length, so that the reduced curve has the same envelope as the original.
fn decimate(points: &[(f64, f64)], max_points: usize) -> Vec<(f64, f64)> {
    let buckets = (max_points / 2).max(1);
    if points.len() <= max_points {
        return points.to_vec();
    }
    let per_bucket = points.len().div_ceil(buckets);
    let mut out = Vec::with_capacity(2 * buckets);
    for chunk in points.chunks(per_bucket) {
        let by_y = |a: &&(f64, f64), b: &&(f64, f64)| a.1.total_cmp(&b.1);
        let (Some(lo), Some(hi)) = (chunk.iter().min_by(by_y), chunk.iter().max_by(by_y)) else {
            continue;
        };
        let (first, second) = if lo.0 <= hi.0 { (lo, hi) } else { (hi, lo) };
        out.push(*first);
        if second != first {
            out.push(*second);
        }
    }
    out
}

/// The smallest and largest t and y over `curves`, or `None` if there is no point.
fn bounds(curves: &[Vec<(f64, f64)>]) -> Option<((f64, f64), (f64, f64))> {
    let mut all = curves.iter().flatten();
    let &(t0, y0) = all.next()?;
    Some(
        all.fold(((t0, t0), (y0, y0)), |((ta, tb), (ya, yb)), &(t, y)| {
            ((ta.min(t), tb.max(t)), (ya.min(y), yb.max(y)))
        }),
    )
}

/// Head room above the curves per legend entry, as a fraction of the data range, so that the
/// legend in the upper right corner does not hide them.
const LEGEND_ROOM: f64 = 0.09;

/// Pads a linear range by 5 % below and 5 % plus the legend's room above, or by ±½ (relative
/// for large values) when empty.
fn padded(lo: f64, hi: f64, legend_entries: usize) -> (f64, f64) {
    if hi > lo {
        let span = hi - lo;
        (
            lo - 0.05 * span,
            hi + (0.05 + LEGEND_ROOM * legend_entries as f64) * span,
        )
    } else {
        let pad = lo.abs().max(1.0) * 0.5;
        (lo - pad, hi + pad)
    }
}

/// Tick labels for an axis spanning `span`: fixed-point with enough decimals to tell ticks
/// apart, scientific for very small or very large spans (so that an energy error of 1e-10 J is
/// not printed as `0.0`).
fn tick_format(span: f64) -> impl Fn(&f64) -> String {
    let magnitude = if span > 0.0 && span.is_finite() {
        span.log10().floor()
    } else {
        0.0
    };
    move |v: &f64| {
        if v.abs() < 1e-6 * span {
            "0".to_owned()
        } else if !(-2.0..=4.0).contains(&magnitude) {
            format!("{v:.2e}")
        } else {
            // Truncation is intended: a small non-negative integer.
            let decimals = (1.0 - magnitude).max(0.0) as usize;
            let text = format!("{v:.decimals$}");
            // No "-0.0": a tick at zero is printed without sign.
            if text
                .trim_start_matches('-')
                .chars()
                .all(|c| c == '0' || c == '.')
            {
                text.trim_start_matches('-').to_owned()
            } else {
                text
            }
        }
    }
}

/// Draws one panel into `area`.
fn draw_panel<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let curves: Vec<Vec<(f64, f64)>> = panel
        .curves
        .iter()
        .map(|c| visible_points(c, panel.scale))
        .collect();
    let ((t0, t1), (y0, y1)) = bounds(&curves).unwrap_or(((0.0, 1.0), (0.0, 1.0)));
    let t1 = if t1 > t0 { t1 } else { t0 + 1.0 };
    let mut builder = ChartBuilder::on(area);
    builder
        .margin(10)
        .margin_right(24)
        .x_label_area_size(40)
        .y_label_area_size(86);
    let t_ticks = tick_format(t1 - t0);
    let x = ChartAxis {
        range: t0..t1,
        title: &panel.x_label,
        ticks: &t_ticks,
    };
    let sets = marked(panel, &curves);
    let legend = SeriesLabelPosition::UpperRight;
    match panel.scale {
        Scale::Linear => {
            let (y0, y1) = padded(y0, y1, panel.curves.len());
            let y_ticks = tick_format(y1 - y0);
            let y = ChartAxis {
                range: y0..y1,
                title: &panel.y_label,
                ticks: &y_ticks,
            };
            draw_chart(&mut builder, x, y, sets, legend)
        }
        Scale::Log => {
            let (y0, y1) = if y1 > y0 {
                let decades = (y1 / y0).log10();
                let room = 0.05 + LEGEND_ROOM * panel.curves.len() as f64;
                (y0, y1 * 10f64.powf(room * decades))
            } else {
                (y0 / 10.0, y1 * 10.0)
            };
            let y = ChartAxis {
                range: (y0..y1).log_scale(),
                title: &panel.y_label,
                ticks: &|y| format!("{y:.0e}"),
            };
            draw_chart(&mut builder, x, y, sets, legend)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Decimation keeps the envelope: the extreme values survive, in time order, within the
    /// point budget.
    #[test]
    fn decimation_keeps_extremes_in_order() {
        let points: Vec<(f64, f64)> = (0..10_000)
            .map(|k| {
                let t = f64::from(k) * 1e-3;
                (t, (40.0 * t).sin() + if k == 5_123 { 3.0 } else { 0.0 })
            })
            .collect();
        let reduced = decimate(&points, 1000);
        assert!(reduced.len() <= 1000, "{}", reduced.len());
        assert!(reduced.windows(2).all(|w| w[0].0 < w[1].0));
        assert!(reduced.contains(&points[5_123]));
        let min = |p: &[(f64, f64)]| p.iter().map(|q| q.1).fold(f64::INFINITY, f64::min);
        assert_eq!(min(&reduced), min(&points));
        assert_eq!(decimate(&points[..10], 1000), points[..10].to_vec());
    }

    /// Log panels drop the points they cannot show; empty ranges are padded.
    #[test]
    fn log_panels_skip_non_positive_values() {
        let c = Curve::new("gap", &[0.0, 1.0, 2.0], [0.0, 1e-6, f64::NAN]);
        assert_eq!(visible_points(&c, Scale::Log), vec![(1.0, 1e-6)]);
        assert_eq!(visible_points(&c, Scale::Linear).len(), 2);
        assert_eq!(padded(2.0, 2.0, 1), (1.0, 3.0));
        assert_eq!(padded(0.0, 10.0, 0), (-0.5, 10.5));
        assert_eq!(tick_format(70.0)(&20.0), "20");
        assert_eq!(tick_format(2.0)(&-0.5), "-0.5");
        assert_eq!(tick_format(2.0)(&-1e-17), "0");
        assert_eq!(tick_format(1e-9)(&-1e-25), "0");
        assert_eq!(tick_format(1e-9)(&-5e-10), "-5.00e-10");
        assert_eq!(
            Curve::reference("limit", &[0.0, 0.5, 3.0], 39.4).points,
            vec![(0.0, 39.4), (3.0, 39.4)]
        );
    }

    /// `render_file` writes one SVG named by the user with each panel's horizontal label, a
    /// band's and a line's legend entries and none for an unlabelled reference; a name that is
    /// neither .svg nor .png is refused by name.
    #[test]
    fn render_file_writes_the_named_svg_with_its_labels_and_refuses_other_names() {
        let t = [0.0, 1.0, 2.0];
        let figure = Figure {
            file: "unused".to_owned(),
            title: "title".to_owned(),
            panels: vec![
                Panel::new(
                    "torque (N·m)",
                    vec![
                        Curve {
                            style: Mark::Band,
                            ..Curve::new("measured", &t, [1.0, 2.0, 1.5])
                        },
                        Curve::new("model", &t, [1.1, 1.9, 1.5]),
                        Curve::reference("limit", &t, 3.0),
                        Curve::reference("", &t, -3.0),
                    ],
                ),
                Panel::log("cost J", vec![Curve::new("cost", &t, [1.0, 0.1, 0.01])])
                    .with_x_label("iteration"),
            ],
        };
        let dir = std::env::temp_dir().join(format!("rne-figures-{}", std::process::id()));
        let path = dir.join("named.svg");
        crate::render_file(&figure, &path).expect("written");
        let svg = std::fs::read_to_string(&path).expect("an SVG");
        for text in ["t (s)", "iteration", "measured", "model", "limit", "cost J"] {
            assert!(svg.contains(text), "the figure lacks {text:?}");
        }
        // Each text element holds its text on a line of its own; the unlabelled reference
        // adds no (empty) legend entry.
        assert_eq!(svg.lines().filter(|l| *l == "limit").count(), 1);
        assert!(!svg.contains(">\n\n</text>"));
        let error = crate::render_file(&figure, &dir.join("named.pdf")).unwrap_err();
        assert!(error.to_string().contains("named.pdf"), "{error}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
