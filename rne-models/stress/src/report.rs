//! The stress report: one section per case (what was run, tables, figures, and where `f64`
//! accuracy is lost and why), written as markdown with its figures.

use std::path::{Path, PathBuf};

use super::error::StressError;
use super::Effort;
use rne_figures::log_plot::LogPlot;
use rne_figures::{render, FigureError, Formats, Table};

/// The outcome of one stress case.
#[derive(Clone, Debug, PartialEq)]
pub struct CaseReport {
    /// Short name, used in file names: `mass-ratio`, `conditioning`, …
    pub slug: &'static str,
    /// Section title.
    pub title: String,
    /// What was run: robots, states, sample sizes (markdown).
    pub setup: String,
    /// The measurements.
    pub tables: Vec<Table>,
    /// The figures, rendered next to the report.
    pub plots: Vec<LogPlot>,
    /// Where `f64` accuracy is lost and why, with the measured figures (markdown).
    pub findings: String,
}

impl CaseReport {
    /// The section in markdown, figures linked by file name.
    pub fn markdown(&self) -> String {
        let mut text = format!("## {}\n\n{}\n\n", self.title, self.setup.trim_end());
        for table in &self.tables {
            text.push_str(&table.markdown());
            text.push('\n');
        }
        for plot in &self.plots {
            text.push_str(&format!("![{}]({}.svg)\n\n", plot.title, plot.file));
        }
        text.push_str(self.findings.trim_end());
        text.push('\n');
        text
    }
}

/// Every case of one `rne stress` run.
#[derive(Clone, Debug, PartialEq)]
pub struct StressReport {
    /// How thorough the run was.
    pub effort: Effort,
    /// The cases, in order.
    pub cases: Vec<CaseReport>,
}

impl StressReport {
    /// The whole report in markdown.
    pub fn markdown(&self) -> String {
        let mut text = String::from("# rne stress: numerical stability of the f64 kernels\n\n");
        text.push_str(super::METHOD);
        text.push_str(&format!(
            "\n\nThis run: {} (`rne stress{}`).\n\n",
            match self.effort {
                Effort::Quick => "quick, small samples for a fast check",
                Effort::Full => "full",
            },
            match self.effort {
                Effort::Quick => " --quick",
                Effort::Full => "",
            }
        ));
        for case in &self.cases {
            text.push_str(&case.markdown());
            text.push('\n');
        }
        text
    }

    /// Writes `DIR/report.md` and every figure as SVG and PNG into `dir` (created if
    /// missing); returns the paths written.
    pub fn write(&self, dir: &Path) -> Result<Vec<PathBuf>, StressError> {
        std::fs::create_dir_all(dir).map_err(FigureError::io(dir))?;
        let report = dir.join("report.md");
        std::fs::write(&report, self.markdown()).map_err(FigureError::io(&report))?;
        let mut written = vec![report];
        for plot in self.cases.iter().flat_map(|c| &c.plots) {
            written.extend(render(plot, dir, Formats::BOTH)?);
        }
        Ok(written)
    }
}
