//! The figure of measured against predicted torques: one panel per joint over time, the
//! measurement as a wide translucent band and the prediction as a line inside it, written by
//! rne-figures (SVG, or PNG for a `.png` path).

use std::path::Path;

use rne_figures::time_series::{Curve, Figure, Panel};
use rne_figures::{render_file, Mark};

use crate::data::Measurements;
use crate::identification::fit;
use crate::IdentifyError;

/// Draws `data`'s torques and `predicted` (one vector per sample) into `path`, titled `title`.
pub fn torque_figure(
    path: &Path,
    title: &str,
    data: &Measurements,
    predicted: &[Vec<f64>],
) -> Result<(), IdentifyError> {
    let figure = torque_panels(path, title, data, predicted);
    render_file(&figure, path).map_err(|e| IdentifyError::Figure {
        file: path.to_path_buf(),
        message: e.to_string(),
    })
}

/// What generalised force `j` of `data` is: on a floating base (one more position than rates,
/// the quaternion's) the first six are the wrench on the base in its own frame (docs/design.md
/// §4.5) and the joints are numbered after it.
fn force_label(data: &Measurements, j: usize) -> String {
    const AXES: [&str; 3] = ["x", "y", "z"];
    if data.positions > data.joints {
        match j {
            0..3 => format!("base force {} (N)", AXES[j]),
            3..6 => format!("base moment {} (N·m)", AXES[j - 3]),
            _ => format!("joint {} torque (N·m)", j - 5),
        }
    } else {
        format!("joint {} torque (N·m)", j + 1)
    }
}

/// The figure: per joint, the measured band and the identified model's line, with the
/// joint's RMS error in the legend.
fn torque_panels(path: &Path, title: &str, data: &Measurements, predicted: &[Vec<f64>]) -> Figure {
    let time: Vec<f64> = data
        .samples
        .iter()
        .enumerate()
        .map(|(k, s)| s.t.unwrap_or(k as f64))
        .collect();
    let errors = fit(predicted, data);
    let panels = (0..data.joints)
        .map(|j| {
            let measured = Curve {
                style: Mark::Band,
                ..Curve::new("measured", &time, data.samples.iter().map(|s| s.tau[j]))
            };
            let model = Curve::new(
                format!(
                    "identified model: RMS error {:.2} % of RMS torque",
                    100.0 * errors.joints[j]
                ),
                &time,
                predicted.iter().map(|p| p[j]),
            );
            Panel::new(force_label(data, j), vec![measured, model])
        })
        .collect();
    Figure {
        file: path.file_stem().map_or_else(
            || "torques".to_owned(),
            |s| s.to_string_lossy().into_owned(),
        ),
        title: title.to_owned(),
        panels,
    }
}
