//! Where an element is written in the URDF text, for the line number of an error: urdf-rs
//! keeps no positions, so the opening tag `<joint name="..">` or `<link name="..">` is found by
//! a scan of the text that skips comments.

use std::ops::Range;

use crate::spec::SpecError;

/// Gives `error` the position of the element it names (its joint, else its link), if found.
pub(crate) fn element(error: SpecError, text: &str) -> SpecError {
    let span = match (error.joint(), error.link()) {
        (Some(joint), _) => opening_tag(text, "joint", joint),
        (None, Some(link)) => opening_tag(text, "link", link),
        (None, None) => None,
    };
    error.at_span(span)
}

/// The byte range of the first opening tag `<tag ...>` outside comments whose `name`
/// attribute is `name`.
fn opening_tag(text: &str, tag: &str, name: &str) -> Option<Range<usize>> {
    let mut at = 0;
    while let Some(offset) = text.get(at..)?.find('<') {
        let start = at + offset;
        let rest = text.get(start..)?;
        if rest.starts_with("<!--") {
            at = start + rest.find("-->")? + 3;
            continue;
        }
        let end = start + rest.find('>').map_or(rest.len(), |e| e + 1);
        let element = text.get(start..end)?;
        if is_tag(element, tag) && attribute(element, "name") == Some(name) {
            return Some(start..end);
        }
        at = start + 1;
    }
    None
}

/// Whether `element` (`<...>`) opens a `tag` element.
fn is_tag(element: &str, tag: &str) -> bool {
    element
        .strip_prefix('<')
        .and_then(|e| e.strip_prefix(tag))
        .and_then(|e| e.chars().next())
        .is_some_and(|c| c.is_whitespace() || c == '/' || c == '>')
}

/// The value of the attribute `key` in an opening tag, quoted with `"` or `'`.
fn attribute<'t>(element: &'t str, key: &str) -> Option<&'t str> {
    let mut search = element;
    while let Some(found) = search.find(key) {
        let before = search[..found].chars().next_back();
        let after = search[found + key.len()..].trim_start();
        search = &search[found + key.len()..];
        if !before.is_some_and(char::is_whitespace) {
            continue;
        }
        let Some(value) = after.strip_prefix('=') else {
            continue;
        };
        let value = value.trim_start();
        let quote = value.chars().next().filter(|&c| c == '"' || c == '\'')?;
        let value = &value[1..];
        return value.find(quote).map(|end| &value[..end]);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = r#"<robot name="r">
  <!-- <joint name="j1" type="fixed"> -->
  <link name="a"/>
  <link name = 'b'>
  </link>
  <joint type="revolute" name="j1">
"#;

    #[test]
    fn finds_opening_tags_outside_comments() {
        let span = opening_tag(TEXT, "joint", "j1").unwrap();
        assert_eq!(&TEXT[span.clone()], r#"<joint type="revolute" name="j1">"#);
        assert_eq!(TEXT[..span.start].matches('\n').count() + 1, 6);
        assert_eq!(
            &TEXT[opening_tag(TEXT, "link", "b").unwrap()],
            "<link name = 'b'>"
        );
        assert_eq!(opening_tag(TEXT, "link", "j1"), None);
        assert_eq!(opening_tag(TEXT, "joint", "a"), None);
        assert_eq!(opening_tag("<joint name=\"x", "joint", "x"), None);
        assert_eq!(opening_tag("<!-- unterminated", "joint", "x"), None);
    }
}
