//! What a command says when its MODEL is neither a built-in robot nor a file: that, and the
//! built-in names closest to what was typed (by edit distance), so `rne check pandaa` points to
//! `panda` and `rne models`.

use std::path::Path;

use crate::builtin::BUILTIN_ROBOTS;

/// The most edits (insertions, deletions, substitutions) a suggested name may be from the
/// typed one.
const MAX_EDITS: usize = 2;

/// The message for a `model` that names no built-in robot and no existing file, `None` when
/// the file exists (its reader then says what is wrong with it).
pub fn not_found(model: &str) -> Option<String> {
    if Path::new(model).exists() {
        return None;
    }
    let close = closest_builtins(model);
    let hint = match close.as_slice() {
        [] => String::new(),
        names => format!("; did you mean {}?", names.join(" or ")),
    };
    Some(format!(
        "'{model}' is not a built-in robot (see `rne models`) and no such file exists{hint}"
    ))
}

/// The built-in names within `MAX_EDITS` edits of `typed` (case-insensitive), nearest first, or
/// those that start with it.
pub fn closest_builtins(typed: &str) -> Vec<&'static str> {
    let typed = typed.to_ascii_lowercase();
    let mut close: Vec<(usize, &'static str)> = BUILTIN_ROBOTS
        .iter()
        .map(|r| (edit_distance(&typed, r.name), r.name))
        .filter(|(d, name)| *d <= MAX_EDITS || (typed.len() >= 3 && name.starts_with(&typed)))
        .collect();
    close.sort();
    close.into_iter().map(|(_, name)| name).collect()
}

/// Levenshtein distance between two strings, by characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substitution = diagonal + usize::from(ca != *cb);
            diagonal = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_typo_of_a_builtin_name_suggests_it() {
        assert_eq!(closest_builtins("pandaa")[0], "panda");
        assert_eq!(closest_builtins("ur6"), vec!["ur5"]);
        assert!(closest_builtins("irb").contains(&"irb140"));
        assert!(closest_builtins("completely-different").is_empty());
    }

    #[test]
    fn the_message_names_the_model_rne_models_and_the_suggestion() {
        let e = not_found("pandaa").unwrap();
        for part in [
            "'pandaa' is not a built-in robot",
            "rne models",
            "did you mean panda",
        ] {
            assert!(e.contains(part), "{part}: {e}");
        }
        assert!(
            not_found("Cargo.toml").is_none(),
            "an existing file is read, not refused"
        );
    }

    #[test]
    fn edit_distance_counts_insertions_deletions_and_substitutions() {
        assert_eq!(edit_distance("panda", "panda"), 0);
        assert_eq!(edit_distance("pandaa", "panda"), 1);
        assert_eq!(edit_distance("pnada", "panda"), 2);
        assert_eq!(edit_distance("", "ur5"), 3);
    }
}
