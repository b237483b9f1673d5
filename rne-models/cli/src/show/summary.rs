//! What `rne show` says after a size-limited print: the entries left out, each with its size,
//! and the commands that print one of them or the compact form.

use std::io::Write;

use clap::ValueEnum;

use super::compact::CompactPrinted;
use super::expanded::{human_size, Omitted, Printed};
use super::ShowArgs;
use crate::CliError;

/// At most this many left-out entries are listed one by one (the largest first).
const LISTED: usize = 12;

/// The note after expanded equations, when entries were left out.
pub fn expanded(
    args: &ShowArgs,
    comment: &str,
    printed: &Printed,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    if printed.omitted.is_empty() {
        return Ok(());
    }
    let total = printed.entries + printed.omitted.len();
    writeln!(
        out,
        "\n{comment} {} of {total} entries printed ({} of at most {}, --max-size); not printed:",
        printed.entries,
        human_size(printed.bytes),
        human_size(args.max_size)
    )?;
    let mut omitted: Vec<&Omitted> = printed.omitted.iter().collect();
    omitted.sort_by_key(|o| std::cmp::Reverse(o.bytes.unwrap_or(usize::MAX)));
    for o in omitted.iter().take(LISTED) {
        let size = match o.bytes {
            Some(bytes) => human_size(bytes),
            None => "not expanded: past the limit (or its expansion alone passes it)".to_owned(),
        };
        writeln!(out, "{comment}   {:<14} {size}", o.key.text())?;
    }
    if omitted.len() > LISTED {
        writeln!(out, "{comment}   … and {} more", omitted.len() - LISTED)?;
    }
    let example = &omitted[0].key.text();
    writeln!(
        out,
        "{comment} one entry: {} --entry \"{example}\" (with --max-size to raise the limit); \
         all of them as a program with named intermediate quantities: {} --compact",
        command(args),
        command(args)
    )?;
    Ok(())
}

/// The note after a program cut short by the size limit.
pub fn compact(
    args: &ShowArgs,
    comment: &str,
    printed: CompactPrinted,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    if printed.lines < printed.total {
        writeln!(
            out,
            "\n{comment} {} of {} lines printed (at most {}, --max-size); the rest: {} --compact --max-size {}",
            printed.lines,
            printed.total,
            human_size(args.max_size),
            command(args),
            suggest_size(args.max_size, printed)
        )?;
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
    command
}
