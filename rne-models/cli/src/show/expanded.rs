//! The expanded equations within a size limit: every entry brought into canonical form under
//! a term budget (so a robot whose equations run to megabytes costs seconds, not minutes), then
//! printed in order while the output stays within the limit; what does not fit is listed with
//! its size.

use std::io::Write;

use rne_symbolic::canonical::{Polynomial, Printer};
use rne_symbolic::ExprGraph;

use super::entries::{EntryKey, Section};
use super::sections::label;
use crate::progress::Progress;
use crate::CliError;

/// The fewest bytes a printed term takes (` + x`), which turns a size limit into a term
/// budget that never refuses an entry that would fit.
const MIN_TERM_BYTES: usize = 4;

/// An entry left out, and why.
#[derive(Clone, Debug)]
pub struct Omitted {
    /// The entry.
    pub key: EntryKey,
    /// Its printed size in bytes, or `None` when its expansion passed the budget.
    pub bytes: Option<usize>,
}

/// What was printed.
#[derive(Clone, Debug, Default)]
pub struct Printed {
    /// Bytes written.
    pub bytes: usize,
    /// Entries written.
    pub entries: usize,
    /// Entries left out.
    pub omitted: Vec<Omitted>,
    /// The term budget each entry had.
    pub max_terms: usize,
}

/// How the entries are printed.
pub struct Style<'a> {
    /// The polynomial printer (text or LaTeX, digits).
    pub printer: Printer<'a>,
    /// LaTeX labels and line ends.
    pub latex: bool,
    /// The most bytes to write.
    pub max_size: usize,
}

/// Expands and prints `sections` within `style.max_size` bytes (the header excluded).
pub fn print(
    graph: &ExprGraph,
    sections: &[Section],
    style: &Style<'_>,
    what: &str,
    out: &mut dyn Write,
) -> Result<Printed, CliError> {
    let roots: Vec<_> = sections
        .iter()
        .flat_map(|s| s.entries.iter().map(|(_, id)| *id))
        .collect();
    let max_terms = style.max_size / MIN_TERM_BYTES + 1;
    let forms = {
        let _progress = Progress::start(&format!("expanding {what} ({} entries)", roots.len()));
        Polynomial::from_exprs_within(graph, &roots, max_terms).map_err(|e| {
            CliError::Argument(format!("cannot expand the dynamics for printing: {e}"))
        })?
    };
    let (comment, equals, end) = match style.latex {
        true => ("%", " &= ", " \\\\"),
        false => ("#", " = ", ""),
    };
    let mut printed = Printed {
        max_terms,
        ..Printed::default()
    };
    let mut forms = forms.into_iter();
    for section in sections {
        let mut title = Some(format!("\n{comment} {}\n", section.title));
        for (key, _) in &section.entries {
            let Some(form) = forms.next().flatten() else {
                printed.omitted.push(Omitted {
                    key: key.clone(),
                    bytes: None,
                });
                continue;
            };
            let line = format!(
                "{}{equals}{}{end}\n",
                label(key, style.latex),
                style.printer.print(&form)
            );
            let title_bytes = title.as_ref().map_or(0, String::len);
            if printed.bytes + title_bytes + line.len() > style.max_size {
                printed.omitted.push(Omitted {
                    key: key.clone(),
                    bytes: Some(line.len()),
                });
                continue;
            }
            if let Some(t) = title.take() {
                out.write_all(t.as_bytes())?;
                printed.bytes += t.len();
            }
            out.write_all(line.as_bytes())?;
            printed.bytes += line.len();
            printed.entries += 1;
        }
    }
    Ok(printed)
}

/// `12.3 KB`, `4.5 MB`, `812 bytes`.
pub fn human_size(bytes: usize) -> String {
    match bytes {
        b if b >= 1_000_000 => format!("{:.1} MB", b as f64 / 1e6),
        b if b >= 1_000 => format!("{:.1} KB", b as f64 / 1e3),
        b => format!("{b} bytes"),
    }
}
