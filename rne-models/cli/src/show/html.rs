//! `rne show MODEL --format html --out DIR`: the equations as a web page, `DIR/index.html`,
//! that needs nothing but a browser — no script, no font, no network. The mathematics is
//! MathML, which browsers render natively; each entry is a collapsible `<details>` block, one
//! section per output (τ, M, C, g, …), then the compact program. The size limit applies to
//! each of the two forms' markup, as to the printed text.

use std::io::Write;
use std::path::Path;

use rne_symbolic::canonical::mathml::escape;
use rne_symbolic::canonical::PrintFormat;
use rne_symbolic::ExprGraph;

use super::entries::Section;
use super::expanded::human_size;
use super::{compact, expanded, printer, summary, Format, Header, ShowArgs};
use crate::CliError;

/// The page's style: readable widths, long formulas scroll instead of overflowing.
const STYLE: &str = "body{font-family:sans-serif;max-width:70em;margin:1em auto;padding:0 1em}\
math[display=block]{overflow-x:auto;padding:.2em 0}\
details{border-left:3px solid #ccd;padding-left:.6em;margin:.3em 0}\
summary{font-family:monospace;cursor:pointer}\
pre.note{background:#f4f4f8;padding:.5em;white-space:pre-wrap}";

/// Writes the page to `dir/index.html` and says on `out` where it is and what it holds.
pub fn write(
    args: &ShowArgs,
    header: &Header,
    graph: &ExprGraph,
    sections: &[Section],
    dir: &Path,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let mut page = Vec::new();
    head(header, &mut page)?;
    let mut shown = String::new();
    if !args.compact {
        let style = expanded::Style {
            printer: printer(args, graph, PrintFormat::MathMl),
            format: Format::Html,
            max_size: args.max_size,
        };
        let what = format!("the equations of {}", header.name);
        writeln!(page, "<h2 id=\"equations\">The equations</h2>")?;
        let printed = expanded::print(graph, sections, &style, &what, &mut page)?;
        summary::expanded(args, &printed, &mut page)?;
        let total = printed.entries + printed.omitted.len();
        shown = format!("{} of {total} entries, ", printed.entries);
    }
    writeln!(
        page,
        "<section id=\"program\">\n<h2>The compact form: a program</h2>"
    )?;
    let program = compact::print(graph, sections, Format::Html, args.max_size, &mut page)?;
    summary::compact(args, program, &mut page)?;
    writeln!(page, "</section>\n</body>\n</html>")?;
    let path = dir.join("index.html");
    std::fs::write(&path, &page)
        .map_err(|e| CliError::Argument(format!("--out: cannot write {}: {e}", path.display())))?;
    writeln!(
        out,
        "wrote {} ({}: {shown}{} of {} program lines)",
        path.display(),
        human_size(page.len()),
        program.lines,
        program.total
    )?;
    Ok(())
}

/// The page up to its first section: title, style, the robot's name, joints and notation.
fn head(header: &Header, page: &mut Vec<u8>) -> std::io::Result<()> {
    let name = escape(&header.name);
    writeln!(
        page,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>Equations of {name}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
         <h1>Equations of {name}</h1>"
    )?;
    let joints: Vec<String> = header
        .joints
        .iter()
        .map(|j| format!("<code>{}</code>", escape(j)))
        .collect();
    let base = match header.floating {
        true => format!("; {}", escape(super::BASE_NOTATION)),
        false => String::new(),
    };
    writeln!(
        page,
        "<p>{} degrees of freedom; joints: {}{base}.</p>",
        header.dofs,
        joints.join(", ")
    )?;
    writeln!(
        page,
        "<p>Notation of <i>Dynamics of robot manipulators by the Newton–Euler formulation</i>: \
         q<sub>k</sub> the joint positions (by number, or by name), q̇<sub>k</sub> and \
         q̈<sub>k</sub> their rates and accelerations, s<sub>12</sub> = sin(q<sub>1</sub> + \
         q<sub>2</sub>), c<sub>12</sub> = cos(q<sub>1</sub> + q<sub>2</sub>); \
         M(q) q̈ + C(q, q̇) q̇ + g(q) = τ. Each entry folds.</p>"
    )
}
