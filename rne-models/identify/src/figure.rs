//! The figure of measured against predicted torques: one panel per joint over time, the
//! measurement as a wide translucent band and the prediction as a thin line inside it, drawn
//! with plotters as SVG (PNG for a `.png` path).
//!
//! Text is drawn with the reports' font, registered by [`rne_figures::register_font`].

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::data::Measurements;
use crate::identification::fit;
use crate::IdentifyError;

const MEASURED: RGBColor = RGBColor(31, 119, 180);
const PREDICTED: RGBColor = RGBColor(214, 39, 40);

/// Draws `data`'s torques and `predicted` (one vector per sample) into `path`, titled `title`.
pub fn torque_figure(
    path: &Path,
    title: &str,
    data: &Measurements,
    predicted: &[Vec<f64>],
) -> Result<(), IdentifyError> {
    let failed = |message: String| IdentifyError::Figure {
        file: path.to_path_buf(),
        message,
    };
    rne_figures::register_font().map_err(|e| failed(e.to_string()))?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| IdentifyError::Io {
            file: dir.to_path_buf(),
            source,
        })?;
    }
    let columns = if data.joints > 1 { 2 } else { 1 };
    let rows = data.joints.div_ceil(columns);
    let size = (1200, 80 + 260 * rows as u32);
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if png {
        draw(
            BitMapBackend::new(path, size).into_drawing_area(),
            title,
            data,
            predicted,
            columns,
        )
    } else {
        draw(
            SVGBackend::new(path, size).into_drawing_area(),
            title,
            data,
            predicted,
            columns,
        )
    }
    .map_err(failed)
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    data: &Measurements,
    predicted: &[Vec<f64>],
    columns: usize,
) -> Result<(), String> {
    let e = |error: DrawingAreaErrorKind<DB::ErrorType>| error.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = root.titled(title, ("sans-serif", 24)).map_err(e)?;
    let rows = data.joints.div_ceil(columns);
    let panels = root.split_evenly((rows, columns));
    let time: Vec<f64> = data
        .samples
        .iter()
        .enumerate()
        .map(|(k, s)| s.t.unwrap_or(k as f64))
        .collect();
    let (t0, t1) = (time[0], time[time.len() - 1].max(time[0] + 1e-9));
    let errors = fit(predicted, data);
    for (j, panel) in panels.iter().enumerate().take(data.joints) {
        let measured: Vec<(f64, f64)> = time
            .iter()
            .zip(&data.samples)
            .map(|(&t, s)| (t, s.tau[j]))
            .collect();
        let model: Vec<(f64, f64)> = time
            .iter()
            .zip(predicted)
            .map(|(&t, p)| (t, p[j]))
            .collect();
        let (lo, hi) = measured
            .iter()
            .chain(&model)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(_, y)| {
                (a.min(y), b.max(y))
            });
        let pad = 0.08 * (hi - lo).max(1e-9);
        let mut chart = ChartBuilder::on(panel)
            .caption(
                format!(
                    "joint {}: RMS error {:.2} % of RMS torque",
                    j + 1,
                    100.0 * errors.joints[j]
                ),
                ("sans-serif", 16),
            )
            .margin(8)
            .x_label_area_size(34)
            .y_label_area_size(64)
            .build_cartesian_2d(t0..t1, (lo - pad)..(hi + pad))
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc("t (s)")
            .y_desc("torque (N m)")
            .light_line_style(WHITE.mix(0.0))
            .draw()
            .map_err(e)?;
        chart
            .draw_series(LineSeries::new(
                measured,
                MEASURED.mix(0.45).stroke_width(6),
            ))
            .map_err(e)?
            .label("measured")
            .legend(|(x, y)| {
                PathElement::new(
                    vec![(x, y), (x + 20, y)],
                    MEASURED.mix(0.45).stroke_width(6),
                )
            });
        chart
            .draw_series(LineSeries::new(model, PREDICTED.stroke_width(1)))
            .map_err(e)?
            .label("identified model")
            .legend(|(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], PREDICTED.stroke_width(1))
            });
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font(("sans-serif", 12))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .draw()
            .map_err(e)?;
    }
    root.present().map_err(e)
}
