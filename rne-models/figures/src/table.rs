//! Markdown tables of the reports.

/// A markdown table with a caption.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Table {
    /// One sentence above the table saying what the rows are.
    pub caption: String,
    /// Column headings.
    pub header: Vec<String>,
    /// Cells, one vector per row, as long as the header.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// An empty table.
    pub fn new(caption: impl Into<String>, header: &[&str]) -> Table {
        Table {
            caption: caption.into(),
            header: header.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row.
    pub fn push(&mut self, row: Vec<String>) {
        self.rows.push(row);
    }

    /// The caption, a blank line and the table in GitHub markdown; numeric columns are
    /// right-aligned (every column but the first).
    pub fn markdown(&self) -> String {
        // A `|` inside a cell (as in |q|) would end it: escape it.
        let line = |cells: &[String]| {
            let cells: Vec<String> = cells.iter().map(|c| c.replace('|', "\\|")).collect();
            format!("| {} |\n", cells.join(" | "))
        };
        let rule: Vec<String> = (0..self.header.len())
            .map(|i| if i == 0 { "---" } else { "---:" }.to_string())
            .collect();
        let mut text = format!("{}\n\n", self.caption);
        text.push_str(&line(&self.header));
        text.push_str(&line(&rule));
        for row in &self.rows {
            text.push_str(&line(row));
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::sci;

    /// Tables render as GitHub markdown with right-aligned numbers.
    #[test]
    fn markdown_table() {
        let mut t = Table::new("Errors.", &["case", "max"]);
        t.push(vec!["a".into(), sci(1.234e-16)]);
        assert_eq!(
            t.markdown(),
            "Errors.\n\n| case | max |\n| --- | ---: |\n| a | 1.2e-16 |\n"
        );
        let mut t = Table::new("Norms.", &["|x|"]);
        t.push(vec!["‖x‖".into()]);
        assert!(t.markdown().contains("| \\|x\\| |"));
    }
}
