//! Rendering a figure as SVG and PNG with plotters, with one font and one palette.
//!
//! Text needs a font even for the SVG backend (plotters measures labels to lay out the
//! chart), and the PNG backend draws glyphs itself. No system font is assumed: Hack Regular
//! (MIT licence with the Bitstream Vera licence, shipped by the `epaint_default_fonts` crate of
//! the egui project) is registered once per process as plotters' `sans-serif` family, before
//! the first figure is drawn.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::error::FigureError;

/// The series colours, in order (Tableau 10).
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

/// The colour of reference lines (bounds, set-points, limits).
pub const REFERENCE_GREY: RGBColor = RGBColor(110, 110, 110);

/// The image formats to write.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Formats {
    /// Scalable vector graphics.
    pub svg: bool,
    /// Portable network graphics.
    pub png: bool,
}

impl Formats {
    /// SVG and PNG.
    pub const BOTH: Formats = Formats {
        svg: true,
        png: true,
    };
}

/// A figure plotters can draw on any backend.
pub trait Draw {
    /// The file name without extension.
    fn file(&self) -> &str;
    /// The size in pixels.
    fn size(&self) -> (u32, u32);
    /// Draws the figure on `root` (not yet presented).
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>;
}

/// Writes `DIR/FILE.svg` and `DIR/FILE.png` (as `formats` says) and returns their paths.
pub fn render<F: Draw>(
    figure: &F,
    dir: &Path,
    formats: Formats,
) -> Result<Vec<PathBuf>, FigureError> {
    register_font()?;
    let mut written = Vec::new();
    if formats.svg {
        let path = dir.join(format!("{}.svg", figure.file()));
        present(
            figure,
            SVGBackend::new(&path, figure.size()).into_drawing_area(),
        )?;
        written.push(path);
    }
    if formats.png {
        let path = dir.join(format!("{}.png", figure.file()));
        present(
            figure,
            BitMapBackend::new(&path, figure.size()).into_drawing_area(),
        )?;
        written.push(path);
    }
    Ok(written)
}

/// Writes `figure` to `path` alone, as SVG or PNG by the file's extension (`.svg`, `.png`),
/// creating its directory: for a figure whose file the user names.
pub fn render_file<F: Draw>(figure: &F, path: &Path) -> Result<(), FigureError> {
    let extension = path.extension().and_then(|e| e.to_str());
    let png = match extension.map(str::to_ascii_lowercase).as_deref() {
        Some("svg") => false,
        Some("png") => true,
        _ => return Err(FigureError::Extension(path.to_path_buf())),
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(FigureError::io(dir))?;
    }
    register_font()?;
    if png {
        present(
            figure,
            BitMapBackend::new(path, figure.size()).into_drawing_area(),
        )
    } else {
        present(
            figure,
            SVGBackend::new(path, figure.size()).into_drawing_area(),
        )
    }
}

/// Draws `figure` on a white `root` and presents it (writes the file).
fn present<F: Draw, DB: DrawingBackend>(
    figure: &F,
    root: DrawingArea<DB, Shift>,
) -> Result<(), FigureError> {
    let failed = |e: DrawingAreaErrorKind<DB::ErrorType>| FigureError::Draw {
        figure: figure.file().to_owned(),
        message: e.to_string(),
    };
    root.fill(&WHITE).map_err(failed)?;
    figure.draw(&root).map_err(failed)?;
    root.present().map_err(failed)
}

/// Registers the embedded font (Hack Regular, from `epaint_default_fonts`) as plotters'
/// `sans-serif` family, once per process: plotters measures text even for SVG, and no system
/// font is assumed. [`render()`] calls it; figures drawn with plotters directly call it first.
pub fn register_font() -> Result<(), FigureError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            epaint_default_fonts::HACK_REGULAR,
        )
        .is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(FigureError::Font)
    }
}

/// How a set of points is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mark {
    /// Unconnected dots: one measurement each.
    Points,
    /// A solid line through the points in order.
    Line,
    /// A thin dashed grey line: a bound or a reference, such as ε·cond(M) or a set-point.
    Reference,
    /// A wide translucent line: a measurement, with a model's [`Mark::Line`] drawn over it.
    Band,
}

/// One axis of a chart: its range (a `Range<f64>` or a logarithmic one), its title and how its
/// ticks are labelled.
pub(crate) struct ChartAxis<'a, R> {
    /// The coordinate range.
    pub range: R,
    /// The axis title.
    pub title: &'a str,
    /// The tick label of a value.
    pub ticks: &'a dyn Fn(&f64) -> String,
}

/// Builds the chart of `x` and `y` on `builder` and draws its mesh (axis titles and tick
/// labels, no minor grid lines) and the marked sets ([`draw_marked`]) with their legend at
/// `position`: every figure's chart, whatever the kinds of its axes.
pub(crate) fn draw_chart<'b, DB, X, Y>(
    builder: &mut ChartBuilder<DB>,
    x: ChartAxis<X>,
    y: ChartAxis<Y>,
    sets: impl IntoIterator<Item = (&'b str, Mark, &'b [(f64, f64)])>,
    position: SeriesLabelPosition,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
where
    DB: DrawingBackend,
    X: AsRangedCoord<Value = f64>,
    X::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: AsRangedCoord<Value = f64>,
    Y::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let mut chart = builder.build_cartesian_2d(x.range, y.range)?;
    chart
        .configure_mesh()
        .x_desc(x.title)
        .y_desc(y.title)
        .x_label_formatter(x.ticks)
        .y_label_formatter(y.ticks)
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    draw_marked(&mut chart, sets, position)
}

/// Draws labelled point sets with their marks, in [`PALETTE`] colours in order (references
/// are grey and take no colour), and their legend at `position`; a set with an empty label
/// has no legend entry (a second line of a reference already named).
pub(crate) fn draw_marked<'a, 'b, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    sets: impl IntoIterator<Item = (&'b str, Mark, &'b [(f64, f64)])>,
    position: SeriesLabelPosition,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let mut colour = 0;
    for (label, mark, points) in sets {
        let c = PALETTE[colour % PALETTE.len()];
        if mark != Mark::Reference {
            colour += 1;
        }
        let band = c.mix(0.45).stroke_width(6);
        let drawn = match mark {
            Mark::Points => chart.draw_series(
                points
                    .iter()
                    .map(|&p| Circle::new(p, 3, c.mix(0.75).filled())),
            )?,
            Mark::Line => {
                chart.draw_series(LineSeries::new(points.iter().copied(), c.stroke_width(2)))?
            }
            Mark::Reference => chart.draw_series(DashedLineSeries::new(
                points.iter().copied(),
                6,
                4,
                REFERENCE_GREY.stroke_width(1),
            ))?,
            Mark::Band => chart.draw_series(LineSeries::new(points.iter().copied(), band))?,
        };
        let legend = match mark {
            Mark::Reference => REFERENCE_GREY.stroke_width(1),
            Mark::Band => band,
            Mark::Points | Mark::Line => c.stroke_width(2),
        };
        if !label.is_empty() {
            drawn
                .label(label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], legend));
        }
    }
    draw_legend(chart, position)
}

/// Draws the legend of a chart's labelled series at `position`, in the style of every figure.
pub fn draw_legend<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    position: SeriesLabelPosition,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    chart
        .configure_series_labels()
        .position(position)
        .label_font(("sans-serif", 14))
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(160, 160, 160))
        .draw()
}
