//! The expanded equations within a size limit: every entry brought into canonical form under
//! a term budget, then printed in order while the output stays within the limit, all of it
//! under one work budget proportional to the limit (so a robot whose equations run to
//! gigabytes costs seconds, not hours); what does not fit is listed with its size, what was
//! not expanded or printed by name.

use std::io::Write;

use rne_symbolic::canonical::{mathml, Polynomial, Printer, WorkBudget};
use rne_symbolic::ExprGraph;

use super::entries::{EntryKey, Section};
use super::sections::{label, mathml_label};
use super::Format;
use crate::progress::Progress;
use crate::CliError;

/// The bytes a printed term of a robot's equations takes, which turns a size limit into a term
/// budget: a sign, a coefficient of six significant digits and a product of factors
/// (` - 0.00134386 c23 s4 Dq1 Dq2`, about 24 bytes with single-digit joint labels; a robot's
/// joint names make terms far longer, the Panda's about 400 bytes). An entry of more terms
/// than the budget is not expanded further, so a robot whose equations run to megabytes costs
/// seconds; an entry of short terms refused at the limit is printed by raising it.
const MIN_TERM_BYTES: usize = 24;

/// The same in MathML, whose elements take about twice the bytes of the text
/// (`<mo>+</mo><mn>0.5</mn><msub><mi>c</mi><mn>1</mn></msub>`).
const MIN_TERM_BYTES_MATHML: usize = 48;

/// Bytes left below which the remaining sections are not expanded at all.
const MIN_LINE_BYTES: usize = 64;

/// The work (term operations: [`WorkBudget`]) allowed per byte of the size limit, for the
/// expansion and the printing together. Printing a byte takes a few operations when the
/// entries are short; an entry of a floating-base humanoid takes thousands per byte it would
/// print, and is then refused as soon as the budget is spent, so the time of `rne show` grows
/// with `--max-size` and not with the robot.
pub const WORK_PER_BYTE: usize = 12;

/// An entry left out, and why.
#[derive(Clone, Debug)]
pub struct Omitted {
    /// The entry.
    pub key: EntryKey,
    /// Its printed size in bytes, or `None` when it was not expanded or not printed: its
    /// expansion passed the term budget, or its work passed what was left of the work budget.
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
    /// The work spent and the work allowed.
    pub work: (usize, usize),
    /// Whether some expansion or printing was refused for want of work.
    pub work_exhausted: bool,
}

/// How the entries are printed.
pub struct Style<'a> {
    /// The polynomial printer (text, LaTeX or MathML, digits).
    pub printer: Printer<'a>,
    /// The labels, line ends and section titles around the printed polynomials.
    pub format: Format,
    /// The most bytes to write.
    pub max_size: usize,
}

/// Expands and prints `sections` within `style.max_size` bytes (the header excluded), one
/// section at a time, each under the term budget the bytes left allow, all under
/// [`WORK_PER_BYTE`] times the limit of work; once the limit is reached, the remaining sections
/// are not expanded at all.
pub fn print(
    graph: &ExprGraph,
    sections: &[Section],
    style: &Style<'_>,
    what: &str,
    out: &mut dyn Write,
) -> Result<Printed, CliError> {
    let mut printed = Printed::default();
    let limit = style.max_size.saturating_mul(WORK_PER_BYTE);
    let mut work = WorkBudget::new(limit);
    for (k, section) in sections.iter().enumerate() {
        let left = style.max_size.saturating_sub(printed.bytes);
        if left < MIN_LINE_BYTES {
            let rest = section.entries.iter().map(|(key, _)| Omitted {
                key: key.clone(),
                bytes: None,
            });
            printed.omitted.extend(rest);
            continue;
        }
        let term_bytes = match style.format {
            Format::Html => MIN_TERM_BYTES_MATHML,
            Format::Text | Format::Latex => MIN_TERM_BYTES,
        };
        let context = Context {
            graph,
            style,
            max_terms: left / term_bytes + 1,
            what,
        };
        let mut share = WorkBudget::new(work.left() / (sections.len() - k));
        print_section(&context, section, &mut share, out, &mut printed)?;
        work.spend(share.spent());
        printed.work_exhausted |= share.exhausted();
    }
    printed.work = (work.spent(), limit);
    Ok(printed)
}

/// What a section is printed with.
struct Context<'a> {
    graph: &'a ExprGraph,
    style: &'a Style<'a>,
    /// The most terms an entry's expansion may have.
    max_terms: usize,
    /// The progress line's subject.
    what: &'a str,
}

/// Expands one section's entries under `context.max_terms` and `work`, and prints those that
/// fit.
fn print_section(
    context: &Context<'_>,
    section: &Section,
    work: &mut WorkBudget,
    out: &mut dyn Write,
    printed: &mut Printed,
) -> Result<(), CliError> {
    let roots: Vec<_> = section.entries.iter().map(|(_, id)| *id).collect();
    let _progress = Progress::start(&format!("expanding {}: {}", context.what, section.title));
    // At most half the section's work expands, so what was expanded (the cheapest entries
    // first) can still be printed.
    let mut expansion = WorkBudget::new(work.left() / 2);
    let forms =
        Polynomial::from_exprs_within(context.graph, &roots, context.max_terms, &mut expansion)
            .map_err(|e| {
                CliError::Argument(format!("cannot expand the dynamics for printing: {e}"))
            })?;
    work.absorb(&expansion);
    let style = context.style;
    let (mut title, close) = frame(style.format, &section.title);
    for ((key, _), form) in section.entries.iter().zip(forms) {
        let full = style.max_size.saturating_sub(printed.bytes) < MIN_LINE_BYTES;
        let form = form.filter(|_| !full);
        let text = form.and_then(|form| style.printer.print_within(&form, work));
        let Some(text) = text else {
            printed.omitted.push(Omitted {
                key: key.clone(),
                bytes: None,
            });
            continue;
        };
        let line = entry(style.format, key, &text);
        let title_bytes = title.as_ref().map_or(0, |t| t.len() + close.len());
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
    if title.is_none() {
        out.write_all(close.as_bytes())?;
    }
    Ok(())
}

/// What comes before a section's first printed entry (its title) and after its last.
fn frame(format: Format, title: &str) -> (Option<String>, &'static str) {
    match format {
        Format::Text => (Some(format!("\n# {title}\n")), ""),
        Format::Latex => (Some(format!("\n% {title}\n")), ""),
        Format::Html => (
            Some(format!("<section>\n<h2>{}</h2>\n", mathml::escape(title))),
            "</section>\n",
        ),
    }
}

/// One entry's line: `M[1,2] = …`, `M_{12} &= … \\`, or a collapsible block of MathML.
fn entry(format: Format, key: &EntryKey, printed: &str) -> String {
    match format {
        Format::Text => format!("{} = {printed}\n", label(key, false)),
        Format::Latex => format!("{} &= {printed} \\\\\n", label(key, true)),
        Format::Html => format!(
            "<details open><summary>{}</summary>{}</details>\n",
            mathml::escape(&key.text()),
            mathml::math(&format!(
                "{}{}{printed}",
                mathml_label(key),
                mathml::mo("=")
            ))
        ),
    }
}

/// `12.3 KB`, `4.5 MB`, `812 bytes`.
pub fn human_size(bytes: usize) -> String {
    match bytes {
        b if b >= 1_000_000 => format!("{:.1} MB", b as f64 / 1e6),
        b if b >= 1_000 => format!("{:.1} KB", b as f64 / 1e3),
        b => format!("{b} bytes"),
    }
}
