//! What `rne show` says after a size-limited print: the entries left out, each with its size,
//! and the commands that print one of them or the compact form — as comment lines, or as
//! paragraphs of the web page.

use std::io::Write;

use clap::ValueEnum;
use rne_symbolic::canonical::mathml::escape;

use super::compact::CompactPrinted;
use super::expanded::{human_size, Omitted, Printed};
use super::{Format, ShowArgs};
use crate::CliError;

/// At most this many left-out entries are listed one by one (the largest first).
const LISTED: usize = 12;

/// The note after expanded equations, when entries were left out.
pub fn expanded(args: &ShowArgs, printed: &Printed, out: &mut dyn Write) -> Result<(), CliError> {
    if printed.omitted.is_empty() {
        return Ok(());
    }
    let total = printed.entries + printed.omitted.len();
    let mut lines = vec![format!(
        "{} of {total} entries printed ({} of at most {}, --max-size); not printed:",
        printed.entries,
        human_size(printed.bytes),
        human_size(args.max_size)
    )];
    let mut omitted: Vec<&Omitted> = printed.omitted.iter().collect();
    omitted.sort_by_key(|o| std::cmp::Reverse(o.bytes.unwrap_or(usize::MAX)));
    for o in omitted.iter().take(LISTED) {
        let size = match o.bytes {
            Some(bytes) => human_size(bytes),
            None => "not expanded: past the limit (or its expansion alone passes it)".to_owned(),
        };
        lines.push(format!("  {:<14} {size}", o.key.text()));
    }
    if omitted.len() > LISTED {
        lines.push(format!("  … and {} more", omitted.len() - LISTED));
    }
    let example = &omitted[0].key.text();
    lines.push(format!(
        "one entry: {} --entry \"{example}\" (with --max-size to raise the limit); \
         all of them as a program with named intermediate quantities: {} --compact",
        command(args),
        command(args)
    ));
    write_note(args.format, &lines, out)
}

/// The note's lines as comments after a blank line, or as one preformatted block of the page.
fn write_note(format: Format, lines: &[String], out: &mut dyn Write) -> Result<(), CliError> {
    let comment = match format {
        Format::Text => "#",
        Format::Latex => "%",
        Format::Html => {
            writeln!(
                out,
                "<pre class=\"note\">{}</pre>",
                escape(&lines.join("\n"))
            )?;
            return Ok(());
        }
    };
    writeln!(out)?;
    for line in lines {
        writeln!(out, "{comment} {line}")?;
    }
    Ok(())
}

/// The note after a program cut short by the size limit.
pub fn compact(
    args: &ShowArgs,
    printed: CompactPrinted,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    if printed.lines < printed.total {
        let line = format!(
            "{} of {} lines printed (at most {}, --max-size); the rest: {} --compact --max-size {}",
            printed.lines,
            printed.total,
            human_size(args.max_size),
            command(args),
            suggest_size(args.max_size, printed)
        );
        write_note(args.format, &[line], out)?;
    }
    Ok(())
}

/// A limit that would take the whole program, from the average line printed so far.
fn suggest_size(max_size: usize, printed: CompactPrinted) -> String {
    let per_line = max_size / printed.lines.max(1) + 1;
    let needed = per_line.saturating_mul(printed.total);
    format!("{}K", needed.div_ceil(1000) + 1)
}

/// `rne show MODEL --what PART` as the reader typed it (model options included).
fn command(args: &ShowArgs) -> String {
    let mut command = format!("rne show {}", args.model);
    if let Some(what) = args.what.to_possible_value() {
        command += &format!(" --what {}", what.get_name());
    }
    if args.options.floating_base {
        command += " --floating-base";
    }
    if let Some(dir) = &args.out {
        command += &format!(" --format html --out {}", dir.display());
    }
    command
}
