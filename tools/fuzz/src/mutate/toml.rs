//! TOML-spec-aware mutations, on the lines of the text: `[[link]]` tables removed, duplicated
//! (with their name or a fresh one) and moved; parents relinked (to another link, to the link
//! itself, to a later link, to a missing or reserved name: cycles and orphans); joint kinds
//! changed; values, or one number or string inside them, replaced by odd values; keys removed,
//! duplicated, renamed or added (mimic, friction, axis, conventions); parameters made to
//! refer to each other in cycles; values nested deep; top-level keys broken.

use std::ops::Range;

use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::{pick, Applied};
use crate::odd;

/// A table of the spec: the lines from its header (or the file's start) to the next header.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Table {
    /// The header line (`[[link]]`, `[parameters]`), `None` for the top level.
    header: Option<String>,
    /// Line indices, header included.
    lines: Range<usize>,
}

/// A `key = value` line.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Entry {
    line: usize,
    key: String,
    /// The byte range of the value within the line.
    value: Range<usize>,
}

/// The text as lines (each with its line end) and its tables.
struct Spec {
    lines: Vec<String>,
    tables: Vec<Table>,
}

impl Spec {
    fn parse(text: &str) -> Spec {
        let lines: Vec<String> = text.split_inclusive('\n').map(str::to_owned).collect();
        let mut tables = vec![Table {
            header: None,
            lines: 0..0,
        }];
        for (i, line) in lines.iter().enumerate() {
            if line.trim_start().starts_with('[') {
                tables.push(Table {
                    header: Some(line.trim().to_owned()),
                    lines: i..i,
                });
            }
            if let Some(last) = tables.last_mut() {
                last.lines.end = i + 1;
            }
        }
        Spec { lines, tables }
    }

    fn text(&self) -> String {
        self.lines.concat()
    }

    fn links(&self) -> Vec<&Table> {
        self.tables
            .iter()
            .filter(|t| t.header.as_deref() == Some("[[link]]"))
            .collect()
    }

    fn entries(&self, table: &Table) -> Vec<Entry> {
        table
            .lines
            .clone()
            .filter_map(|i| {
                entry(&self.lines[i]).map(|(key, value)| Entry {
                    line: i,
                    key,
                    value,
                })
            })
            .collect()
    }

    fn all_entries(&self) -> Vec<Entry> {
        self.tables.iter().flat_map(|t| self.entries(t)).collect()
    }

    /// The `name` of a link table.
    fn name(&self, table: &Table) -> Option<String> {
        self.entries(table)
            .into_iter()
            .find(|e| e.key == "name")
            .map(|e| unquote(&self.lines[e.line][e.value]))
    }

    fn names(&self) -> Vec<String> {
        self.links().iter().filter_map(|t| self.name(t)).collect()
    }

    /// The table holding line `line`.
    fn table_of(&self, line: usize) -> Option<&Table> {
        self.tables.iter().find(|t| t.lines.contains(&line))
    }

    /// The name of the link whose table holds line `line`, if it is a link's.
    fn link_of(&self, line: usize) -> Option<String> {
        self.table_of(line)
            .filter(|t| t.header.as_deref() == Some("[[link]]"))
            .and_then(|t| self.name(t))
    }

    /// Sets `key = value` in `table`, replacing its line or adding one after the header.
    fn set(&mut self, table: &Table, key: &str, value: &str) {
        let line = format!("{key} = {value}\n");
        match self.entries(table).into_iter().find(|e| e.key == key) {
            Some(e) => self.lines[e.line] = line,
            None => self.lines.insert(table.lines.start + 1, line),
        }
    }
}

/// The key and the value's byte range of a `key = value` line.
fn entry(line: &str) -> Option<(String, Range<usize>)> {
    let trimmed = line.trim_start();
    if trimmed.starts_with('#') || trimmed.starts_with('[') {
        return None;
    }
    let equals = line.find('=')?;
    let key = line[..equals].trim();
    if key.is_empty()
        || !key
            .chars()
            .all(|c| c.is_alphanumeric() || "_-.\"".contains(c))
    {
        return None;
    }
    let start = equals + 1 + (line[equals + 1..].len() - line[equals + 1..].trim_start().len());
    let end = line.find(" #").unwrap_or(line.trim_end().len()).max(start);
    Some((key.to_owned(), start..end))
}

fn unquote(value: &str) -> String {
    value.trim().trim_matches('"').to_owned()
}

/// The numbers and quoted strings inside a value.
fn tokens(value: &str) -> Vec<Range<usize>> {
    let bytes = value.as_bytes();
    let mut found = Vec::new();
    let mut at = 0;
    while at < bytes.len() {
        let start = at;
        if bytes[at] == b'"' {
            at += 1 + value[at + 1..]
                .find('"')
                .map_or(value.len() - at - 1, |e| e + 1);
            found.push(start..at.min(value.len()));
        } else if bytes[at].is_ascii_digit() || bytes[at] == b'-' {
            at += 1;
            while at < bytes.len()
                && (bytes[at].is_ascii_alphanumeric() || b"._+-".contains(&bytes[at]))
            {
                at += 1;
            }
            found.push(start..at);
        } else {
            at += 1;
        }
    }
    found
}

/// Applies one random TOML-spec mutation to `text`; chains are at most `longest` links long.
pub fn mutate(rng: &mut ChaCha8Rng, text: &mut String, longest: usize) -> Applied {
    let mut spec = Spec::parse(text);
    let applied = match rng.gen_range(0..16) {
        0 => remove_link(rng, &mut spec),
        1 => duplicate_link(rng, &mut spec),
        2 => move_link(rng, &mut spec),
        3 | 4 => relink(rng, &mut spec),
        5 => change_joint(rng, &mut spec),
        6 | 7 => odd_value(rng, &mut spec),
        8 => remove_or_double_key(rng, &mut spec),
        9 => rename_key(rng, &mut spec),
        10 => add_key(rng, &mut spec),
        11 => parameters(rng, &mut spec),
        12 => nest(rng, &mut spec),
        13 => rename_link(rng, &mut spec),
        14 => long_chain(rng, &mut spec, longest),
        _ => top_level(rng, &mut spec),
    };
    *text = spec.text();
    applied.unwrap_or_else(|| Applied::anywhere("nothing to mutate"))
}

fn pick_link(rng: &mut ChaCha8Rng, spec: &Spec) -> Option<(Table, String)> {
    let links = spec.links();
    if links.is_empty() {
        return None;
    }
    let table = (*pick(rng, &links)).clone();
    let name = spec.name(&table).unwrap_or_else(|| "?".to_owned());
    Some((table, name))
}

fn remove_link(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let (table, name) = pick_link(rng, spec)?;
    spec.lines.drain(table.lines);
    Some(Applied::at(format!("remove link '{name}'"), &name, "link"))
}

fn duplicate_link(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let (table, name) = pick_link(rng, spec)?;
    let mut copy: Vec<String> = spec.lines[table.lines.clone()].to_vec();
    let renamed = rng.gen_bool(0.5);
    if renamed {
        for line in &mut copy {
            if entry(line).is_some_and(|(key, _)| key == "name" || key == "q") {
                *line = line.replacen(&format!("\"{name}\""), "\"copy\"", 1);
                *line = line.replacen("q = \"", "q = \"copy_", 1);
            }
        }
    }
    if copy.last().is_some_and(|l| !l.ends_with('\n')) {
        copy.last_mut().unwrap().push('\n');
    }
    let at = table.lines.end;
    spec.lines.splice(at..at, copy);
    let what = if renamed { " renamed 'copy'" } else { "" };
    Some(Applied::at(
        format!("duplicate link '{name}'{what}"),
        &name,
        "name",
    ))
}

fn move_link(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let (table, name) = pick_link(rng, spec)?;
    let mut block: Vec<String> = spec.lines.drain(table.lines).collect();
    if block.last().is_some_and(|l| !l.ends_with('\n')) {
        block.last_mut().unwrap().push('\n');
    }
    let rest = Spec::parse(&spec.text());
    let starts: Vec<usize> = rest
        .links()
        .iter()
        .map(|t| t.lines.start)
        .chain([rest.lines.len()])
        .collect();
    let at = *pick(rng, &starts);
    spec.lines.splice(at..at, block);
    Some(Applied::at(format!("move link '{name}'"), &name, "parent"))
}

fn relink(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let (table, name) = pick_link(rng, spec)?;
    let names = spec.names();
    let target = match rng.gen_range(0..4) {
        0 if !names.is_empty() => pick(rng, &names).clone(),
        0 | 1 => name.clone(),
        2 => pick(rng, odd::NAMES).to_string(),
        _ => format!("{name}-orphan"),
    };
    spec.set(&table, "parent", &format!("\"{target}\""));
    Some(Applied::at(
        format!("parent of '{name}' to '{target}'"),
        &name,
        "parent",
    ))
}

fn change_joint(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let (table, name) = pick_link(rng, spec)?;
    let kind = *pick(rng, odd::TOML_JOINT_TYPES);
    spec.set(&table, "joint", kind);
    Some(Applied::at(
        format!("joint of '{name}' to {kind}"),
        &name,
        "joint",
    ))
}

/// Replaces a whole value, or one number or string inside it, by an odd value.
fn odd_value(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let entries = spec.all_entries();
    let entry = pick_some(rng, &entries)?;
    let line = spec.lines[entry.line].clone();
    let value = &line[entry.value.clone()];
    let inner = tokens(value);
    let (range, new) = if !inner.is_empty() && rng.gen_bool(0.7) {
        let token = pick(rng, &inner).clone();
        let new = if value[token.clone()].starts_with('"') || rng.gen_bool(0.3) {
            format!("\"{}\"", pick(rng, odd::NUMBERS).escape_default())
        } else {
            pick(rng, odd::TOML_VALUES).to_string()
        };
        (
            token.start + entry.value.start..token.end + entry.value.start,
            new,
        )
    } else {
        (entry.value.clone(), pick(rng, odd::TOML_VALUES).to_string())
    };
    let mut line = line;
    line.replace_range(range, &new);
    spec.lines[entry.line] = line;
    let description = format!("{} = .. {new} ..", entry.key);
    Some(located(spec, entry, description))
}

fn located(spec: &Spec, entry: &Entry, description: String) -> Applied {
    match spec.link_of(entry.line) {
        Some(link) => Applied::at(description, &link, &entry.key),
        None => Applied {
            description,
            focus: super::Focus {
                element: None,
                field: Some(entry.key.clone()),
            },
        },
    }
}

fn remove_or_double_key(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let entries = spec.all_entries();
    let entry = pick_some(rng, &entries)?.clone();
    let double = rng.gen_bool(0.5);
    let applied = located(
        spec,
        &entry,
        format!(
            "{} key {}",
            if double { "duplicate" } else { "remove" },
            entry.key
        ),
    );
    if double {
        let copy = spec.lines[entry.line].clone();
        spec.lines.insert(entry.line, copy);
    } else {
        spec.lines.remove(entry.line);
    }
    Some(applied)
}

/// Keys a spec has (and a misspelt one): renaming one key to another gives unknown keys,
/// conflicting conventions and values of the wrong shape.
const KEYS: &[&str] = &[
    "name",
    "parent",
    "joint",
    "q",
    "rotation",
    "position",
    "dh",
    "mdh",
    "origin",
    "axis",
    "mass",
    "com",
    "com_from_prev",
    "inertia",
    "mimic",
    "friction",
    "armature",
    "triangle_inequality",
    "gravity",
    "base",
    "parameters",
    "masss",
    "link",
];

fn rename_key(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let entries = spec.all_entries();
    let entry = pick_some(rng, &entries)?.clone();
    let new = *pick(rng, KEYS);
    let line = &spec.lines[entry.line];
    let equals = line.find('=')?;
    let renamed = format!("{new} {}", &line[equals..]);
    let applied = located(spec, &entry, format!("rename key {} to {new}", entry.key));
    spec.lines[entry.line] = renamed;
    Some(applied)
}

/// Keys a link may have, with values odd and ordinary.
fn snippet(rng: &mut ChaCha8Rng, names: &[String]) -> (&'static str, String) {
    let leader = format!("q{}", rng.gen_range(0..names.len() + 2));
    let number = *pick(rng, odd::TOML_VALUES);
    match rng.gen_range(0..10) {
        0 => (
            "mimic",
            format!("{{ joint = \"{leader}\", multiplier = {number} }}"),
        ),
        1 => ("friction", format!("{{ viscous = {number}, coulomb = 1 }}")),
        2 => ("armature", number.to_owned()),
        3 => ("axis", format!("[0, {number}, 0]")),
        4 => ("q", format!("\"{leader}\"")),
        5 => ("dh", format!("{{ a = {number}, alpha = 0 }}")),
        6 => ("mdh", "{ a = 0.1 }".to_owned()),
        7 => (
            "rotation",
            format!(
                "\"Rz({leader}) * Rx({})\"",
                pick(rng, odd::NUMBERS).escape_default()
            ),
        ),
        8 => (
            "origin",
            format!("{{ xyz = [0, 0, {number}], rpy = [0, 0, 0] }}"),
        ),
        _ => ("com_from_prev", format!("[{number}, 0, 0]")),
    }
}

fn add_key(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let (table, name) = pick_link(rng, spec)?;
    let names = spec.names();
    let (key, value) = snippet(rng, &names);
    spec.set(&table, key, &value);
    Some(Applied::at(
        format!("{key} = {value} in '{name}'"),
        &name,
        key,
    ))
}

/// Parameter tables with cycles, self-references, names of joints and built-ins, and odd
/// values.
fn parameters(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let a = *pick(rng, &["a", "l1", "g", "q1", "pi", "base", "D_q1"]);
    let body = match rng.gen_range(0..5) {
        0 => format!("{a} = \"{a} + 1\"\n"),
        // Each parameter twice its predecessor: an evaluation that does not share would take
        // 2^n steps.
        4 => (1..2000).fold(format!("{a} = \"p1 + p1\"\np0 = 1\n"), |body, k| {
            body + &format!("p{k} = \"p{} * p{} + 1\"\n", k - 1, k - 1)
        }),
        1 => format!("{a} = \"b\"\nb = \"{a} * 2\"\n"),
        2 => format!("{a} = {}\n", pick(rng, odd::TOML_VALUES)),
        _ => format!("{a} = \"{}\"\n", pick(rng, odd::NUMBERS).escape_default()),
    };
    let at = spec
        .tables
        .get(1)
        .map_or(spec.lines.len(), |t| t.lines.start);
    if spec.lines.last().is_some_and(|l| !l.ends_with('\n')) {
        spec.lines.last_mut().unwrap().push('\n');
    }
    let section = format!("[parameters]\n{body}");
    spec.lines.insert(at, section.clone());
    Some(Applied {
        description: section,
        focus: super::Focus {
            element: None,
            field: Some(a.to_owned()),
        },
    })
}

fn nest(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let entries = spec.all_entries();
    let entry = pick_some(rng, &entries)?.clone();
    let depth = *pick(rng, &[10, 64, 65, 127, 128, 129, 1000, 100_000]);
    let value = match rng.gen_range(0..3) {
        0 => format!("{}{}", "[".repeat(depth), "]".repeat(depth)),
        1 => format!("\"{}1{}\"", "(".repeat(depth), ")".repeat(depth)),
        _ => format!("{}1{}", "{ a = ".repeat(depth), " }".repeat(depth)),
    };
    let mut line = spec.lines[entry.line].clone();
    line.replace_range(entry.value.clone(), &value);
    spec.lines[entry.line] = line;
    Some(located(
        spec,
        &entry,
        format!("{} nested {depth} deep", entry.key),
    ))
}

/// A link copied many times, each copy the child of the previous one (the default parent) and
/// with its own joint variable: a long chain for the reader's scaling.
fn long_chain(rng: &mut ChaCha8Rng, spec: &mut Spec, longest: usize) -> Option<Applied> {
    let (table, name) = pick_link(rng, spec)?;
    let block: Vec<String> = spec.lines[table.lines.clone()]
        .iter()
        .filter(|l| {
            !entry(l)
                .is_some_and(|(key, _)| matches!(key.as_str(), "name" | "q" | "parent" | "mimic"))
        })
        .cloned()
        .collect();
    let fixed = block.iter().any(|l| l.contains("\"fixed\""));
    let copies = super::chain_length(rng, longest);
    let mut chain = Vec::new();
    for k in 0..copies {
        chain.extend(block.iter().cloned());
        if chain.last().is_some_and(|l| !l.ends_with('\n')) {
            chain.last_mut().unwrap().push('\n');
        }
        let at = chain.len() - block.len() + 1;
        let q = if fixed {
            String::new()
        } else {
            format!("q = \"qchain{k}\"\n")
        };
        chain.insert(at.min(chain.len()), format!("name = \"chain{k}\"\n{q}"));
    }
    spec.lines.extend(chain);
    Some(Applied::at(
        format!("{copies} copies of link '{name}' in a chain"),
        &name,
        "name",
    ))
}

fn rename_link(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let (table, name) = pick_link(rng, spec)?;
    let names = spec.names();
    let new = if rng.gen_bool(0.5) && !names.is_empty() {
        pick(rng, &names).clone()
    } else {
        pick(rng, odd::NAMES).escape_default().to_string()
    };
    spec.set(&table, "name", &format!("\"{new}\""));
    Some(Applied::at(
        format!("rename link '{name}' to '{new}'"),
        &new,
        "name",
    ))
}

fn top_level(rng: &mut ChaCha8Rng, spec: &mut Spec) -> Option<Applied> {
    let top = spec.tables.first()?.clone();
    let (key, value) = match rng.gen_range(0..4) {
        0 => (
            "base",
            pick(rng, &["\"floating\"", "\"fixed\"", "\"\"", "\"free\"", "1"]).to_string(),
        ),
        1 => (
            "gravity",
            format!("[0, 0, {}]", pick(rng, odd::TOML_VALUES)),
        ),
        2 => ("name", pick(rng, odd::TOML_VALUES).to_string()),
        _ => ("link", "[]".to_owned()),
    };
    let line = format!("{key} = {value}\n");
    match spec.entries(&top).into_iter().find(|e| e.key == key) {
        Some(e) => spec.lines[e.line] = line,
        None => spec.lines.insert(0, line),
    }
    Some(Applied {
        description: format!("{key} = {value}"),
        focus: super::Focus {
            element: None,
            field: Some(key.to_owned()),
        },
    })
}

fn pick_some<'a, T>(rng: &mut ChaCha8Rng, items: &'a [T]) -> Option<&'a T> {
    (!items.is_empty()).then(|| pick(rng, items))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    const SPEC: &str = "name = \"r\"\ngravity = [0, 0, -9.81]\n\n[[link]]\nname = \"a\"\njoint = \"revolute\"\nmass = 1 # kg\ncom = [0, \"x\", 0.5]\ninertia = { xx = 1, yy = 1, zz = 1 }\n\n[[link]]\nname = \"b\"\njoint = \"prismatic\"\nmass = 2\ninertia = { xx = 1, yy = 1, zz = 1 }\n";

    #[test]
    fn reads_tables_entries_and_tokens() {
        let spec = Spec::parse(SPEC);
        assert_eq!(spec.text(), SPEC);
        assert_eq!(spec.names(), ["a", "b"]);
        let mass = spec
            .all_entries()
            .into_iter()
            .find(|e| e.key == "mass")
            .unwrap();
        assert_eq!(&spec.lines[mass.line][mass.value.clone()], "1");
        assert_eq!(spec.link_of(mass.line).as_deref(), Some("a"));
        let value = "[0, \"x\", -0.5e-3]";
        let found: Vec<&str> = tokens(value).into_iter().map(|r| &value[r]).collect();
        assert_eq!(found, ["0", "\"x\"", "-0.5e-3"]);
    }

    #[test]
    fn mutations_change_the_text_and_replay() {
        let mut changed = 0;
        for seed in 0..400 {
            let run = || {
                let mut text = SPEC.to_owned();
                let applied = mutate(&mut ChaCha8Rng::seed_from_u64(seed), &mut text, 3000);
                (text, applied)
            };
            assert_eq!(run(), run());
            changed += usize::from(run().0 != SPEC);
        }
        assert!(changed > 340, "{changed}");
    }
}
