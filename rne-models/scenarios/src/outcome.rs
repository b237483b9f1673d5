//! What a scenario produces: CSV tables of its runs, figures, and its measurements set beside
//! what the thesis reports.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::error::ScenarioError;
use rne_figures::time_series::Figure;
use rne_figures::{render, FigureError, Formats};
use rne_sim::Record;

/// One run as CSV text: `t, q, q̇, u, kinetic, potential, total[, lyapunov]` (the columns of
/// [`Record::csv_header`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// The file name, with its `.csv` extension.
    pub file: String,
    /// The CSV text.
    pub csv: String,
}

impl Table {
    /// The CSV of `record`, to be written as `file`.
    pub fn of<const N: usize>(file: impl Into<String>, record: &Record<N>) -> Self {
        let mut bytes = Vec::new();
        // Writing into memory cannot fail.
        let written = record.write_csv(&mut bytes);
        debug_assert!(written.is_ok());
        Self {
            file: file.into(),
            csv: String::from_utf8_lossy(&bytes).into_owned(),
        }
    }
}

/// One measured quantity beside what the thesis reports for it.
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    /// What is measured, with its definition where it needs one.
    pub quantity: String,
    /// What rne measured.
    pub rne: String,
    /// What the thesis reports ("—" where it reports nothing).
    pub thesis: String,
}

impl Finding {
    /// A finding.
    pub fn new(
        quantity: impl Into<String>,
        rne: impl Into<String>,
        thesis: impl Into<String>,
    ) -> Self {
        Self {
            quantity: quantity.into(),
            rne: rne.into(),
            thesis: thesis.into(),
        }
    }
}

/// A kind of file [`Outcome::write`] produces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// The CSV table of every run.
    Csv,
    /// Every figure as SVG.
    Svg,
    /// Every figure as PNG.
    Png,
    /// The findings as a Markdown table, `SCENARIO-findings.md`.
    Md,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 4] = [Format::Csv, Format::Svg, Format::Png, Format::Md];
}

/// Everything one scenario produced.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// The scenario's name.
    pub scenario: String,
    /// One CSV per run.
    pub tables: Vec<Table>,
    /// The figures.
    pub figures: Vec<Figure>,
    /// The measurements.
    pub findings: Vec<Finding>,
}

impl Outcome {
    /// Writes the tables, figures and findings in `formats` into `dir`, creating it, and returns
    /// the paths written.
    pub fn write(&self, dir: &Path, formats: &[Format]) -> Result<Vec<PathBuf>, ScenarioError> {
        std::fs::create_dir_all(dir).map_err(FigureError::io(dir))?;
        let mut written = Vec::new();
        if formats.contains(&Format::Csv) {
            for table in &self.tables {
                let path = dir.join(&table.file);
                std::fs::write(&path, &table.csv).map_err(FigureError::io(&path))?;
                written.push(path);
            }
        }
        let images = Formats {
            svg: formats.contains(&Format::Svg),
            png: formats.contains(&Format::Png),
        };
        for figure in &self.figures {
            written.extend(render(figure, dir, images)?);
        }
        if formats.contains(&Format::Md) {
            let path = dir.join(format!("{}-findings.md", self.scenario));
            std::fs::write(&path, self.findings_table()).map_err(FigureError::io(&path))?;
            written.push(path);
        }
        Ok(written)
    }

    /// The findings as a Markdown table: quantity | rne | thesis (`|` inside a cell escaped).
    pub fn findings_table(&self) -> String {
        let mut text = String::from("| quantity | rne | thesis |\n|---|---|---|\n");
        for f in &self.findings {
            // Writing into a String cannot fail.
            let cell = |s: &str| s.replace('|', "\\|");
            let _ = writeln!(
                text,
                "| {} | {} | {} |",
                cell(&f.quantity),
                cell(&f.rne),
                cell(&f.thesis)
            );
        }
        text
    }
}
