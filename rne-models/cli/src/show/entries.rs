//! What `rne show` can print, as named entries: `tau[1]`, `M[2,3]`, `g[1]`, `T`, and how a
//! reader picks one (`--entry "M[2,3]"`).

use crate::CliError;
use rne_symbolic::Id;

/// The name of one printed quantity: a matrix or vector and its 1-based indices.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EntryKey {
    /// `tau`, `M`, `C`, `g`, `T`, `V`, `dtau_dq`, `dtau_dqd`, `f_<link>.x`, ...
    pub name: String,
    /// Row (and column), from 1; empty for a scalar.
    pub index: Vec<usize>,
}

impl EntryKey {
    /// An entry of a vector (`g[1]`), a matrix (`M[1,2]`) or a scalar (`T`).
    pub fn new(name: &str, index: &[usize]) -> EntryKey {
        EntryKey {
            name: name.to_owned(),
            index: index.to_vec(),
        }
    }

    /// `M[2,3]`, `g[1]`, `T`: the form `--entry` takes.
    pub fn text(&self) -> String {
        match self.index.as_slice() {
            [] => self.name.clone(),
            index => {
                let index: Vec<String> = index.iter().map(usize::to_string).collect();
                format!("{}[{}]", self.name, index.join(","))
            }
        }
    }

    /// Parses `--entry`: `NAME`, `NAME[i]` or `NAME[i,j]` (spaces allowed).
    pub fn parse(text: &str) -> Result<EntryKey, CliError> {
        let bad = || {
            CliError::Argument(format!(
                "--entry '{text}': expected NAME, NAME[i] or NAME[i,j] with indices from 1, \
                 as in --entry \"M[2,3]\" or --entry \"g[1]\""
            ))
        };
        let text = text.trim();
        let Some((name, rest)) = text.split_once('[') else {
            return Ok(EntryKey::new(text, &[]));
        };
        let inner = rest.strip_suffix(']').ok_or_else(bad)?;
        let index = inner
            .split(',')
            .map(|i| i.trim().parse::<usize>().ok().filter(|&i| i > 0))
            .collect::<Option<Vec<usize>>>()
            .ok_or_else(bad)?;
        if name.trim().is_empty() || index.len() > 2 {
            return Err(bad());
        }
        Ok(EntryKey::new(name.trim(), &index))
    }
}

/// One titled group of entries (the mass matrix, the gravity torques, ...).
#[derive(Clone, Debug)]
pub struct Section {
    /// The comment line above the entries.
    pub title: String,
    /// The entries and their expressions.
    pub entries: Vec<(EntryKey, Id)>,
}

/// Keeps only the entry `wanted` names; an error listing what there is when none matches.
pub fn select(sections: Vec<Section>, wanted: &EntryKey) -> Result<Vec<Section>, CliError> {
    let available: Vec<String> = sections
        .iter()
        .flat_map(|s| s.entries.iter().map(|(k, _)| k.text()))
        .collect();
    let kept: Vec<Section> = sections
        .into_iter()
        .filter_map(|mut s| {
            s.entries.retain(|(k, _)| k == wanted);
            (!s.entries.is_empty()).then_some(s)
        })
        .collect();
    if kept.is_empty() {
        let first = available.first().map_or("", String::as_str);
        let last = available.last().map_or("", String::as_str);
        return Err(CliError::Argument(format!(
            "--entry {}: no such entry among the {} printed with this --what ({first} … {last})",
            wanted.text(),
            available.len()
        )));
    }
    Ok(kept)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entry_names_round_trip_through_their_text() {
        for text in ["M[2,3]", "g[1]", "T", "dtau_dq[10,12]", "f_link.x"] {
            assert_eq!(EntryKey::parse(text).unwrap().text(), text);
        }
        assert_eq!(EntryKey::parse(" M[ 2 , 3 ] ").unwrap().text(), "M[2,3]");
    }

    #[test]
    fn malformed_entries_are_refused_with_the_expected_form() {
        for text in ["M[0,1]", "M[2,", "M[a]", "[1]", "M[1,2,3]"] {
            let e = EntryKey::parse(text).unwrap_err().to_string();
            assert!(e.contains("NAME[i,j]"), "{text}: {e}");
        }
    }
}
