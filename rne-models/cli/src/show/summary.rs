//! What `rne show` says after a size-limited print: the entries left out (those too long for
//! what was left by size, those not expanded by name and count), and the commands that print
//! one of them or the compact form — as comment lines, or as paragraphs of the web page.

use std::io::Write;

use clap::ValueEnum;
use rne_symbolic::canonical::mathml::escape;

use super::compact::CompactPrinted;
use super::expanded::{human_size, Omitted, Printed};
use super::{Format, ShowArgs};
use crate::CliError;

/// At most this many left-out entries are listed one by one with their size (the largest
/// first).
const LISTED: usize = 12;

/// The note after expanded equations, when entries were left out: those printed but too long
/// for what was left, by size; those not expanded or not printed, by name and count.
pub fn expanded(args: &ShowArgs, printed: &Printed, out: &mut dyn Write) -> Result<(), CliError> {
    let Some(first) = printed.omitted.first() else {
        return Ok(());
    };
    let total = printed.entries + printed.omitted.len();
    let mut lines = vec![format!(
        "{} of {total} entries printed ({} of at most {}, --max-size); not printed:",
        printed.entries,
        human_size(printed.bytes),
        human_size(args.max_size)
    )];
    lines.extend(by_size(&printed.omitted));
    lines.extend(by_name(printed));
    let example = first.key.text();
    lines.push(format!(
        "one entry: {} --entry \"{example}\" (with --max-size to raise the limit); \
         all of them as a program with named intermediate quantities: {} --compact",
        command(args),
        command(args)
    ));
    write_note(args.format, &lines, out)
}

/// The entries printed in full but longer than what was left, the largest first.
fn by_size(omitted: &[Omitted]) -> Vec<String> {
    let mut sized: Vec<(&Omitted, usize)> =
        omitted.iter().filter_map(|o| Some((o, o.bytes?))).collect();
    if sized.is_empty() {
        return Vec::new();
    }
    sized.sort_by_key(|&(_, bytes)| std::cmp::Reverse(bytes));
    let mut lines = vec!["longer than what was left, by printed size:".to_owned()];
    for (o, bytes) in sized.iter().take(LISTED) {
        lines.push(format!("  {:<14} {}", o.key.text(), human_size(*bytes)));
    }
    if sized.len() > LISTED {
        lines.push(format!("  … and {} more", sized.len() - LISTED));
    }
    lines
}

/// The entries not expanded or not printed, by name and count only (their size is not
/// estimated): one line per matrix or vector, in print order.
fn by_name(printed: &Printed) -> Vec<String> {
    // (name, count, first, last) of each matrix or vector.
    let mut groups: Vec<(&str, usize, String, String)> = Vec::new();
    for o in printed.omitted.iter().filter(|o| o.bytes.is_none()) {
        let text = o.key.text();
        match groups.iter_mut().find(|(name, ..)| *name == o.key.name) {
            Some((_, count, _, last)) => {
                *count += 1;
                *last = text;
            }
            None => groups.push((&o.key.name, 1, text.clone(), text)),
        }
    }
    if groups.is_empty() {
        return Vec::new();
    }
    let (spent, allowed) = printed.work;
    let why = if printed.work_exhausted {
        format!(
            "past the output limit, or the work it allows ({} of {} term operations spent)",
            count(spent),
            count(allowed)
        )
    } else {
        "past the output limit".to_owned()
    };
    let mut lines = vec![format!(
        "not expanded or not printed ({why}), by name and count only, size not estimated:"
    )];
    for (name, count, first, last) in groups {
        lines.push(match count {
            1 => format!("  {first}"),
            n => format!("  {name}: {n} entries, {first} … {last}"),
        });
    }
    lines
}

/// `812`, `12.3 M`.
fn count(n: usize) -> String {
    match n {
        n if n >= 1_000_000 => format!("{:.1} M", n as f64 / 1e6),
        n if n >= 1_000 => format!("{:.1} K", n as f64 / 1e3),
        n => n.to_string(),
    }
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
