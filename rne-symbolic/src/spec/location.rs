//! Where a finding of spec reading belongs: the file, the line, the joint or link and the field.
//! Errors ([`SpecError`](super::SpecError)) and warnings ([`SpecWarning`](super::SpecWarning))
//! carry the same location and display it the same way.

use std::ops::Range;

/// A location in a robot file, filled in as a finding travels outwards through the reader:
/// inner functions know the field, outer ones the link or joint, the reader the byte range and
/// the file.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Location {
    pub(crate) file: String,
    pub(crate) line: Option<usize>,
    pub(crate) joint: Option<String>,
    pub(crate) link: Option<String>,
    pub(crate) field: Option<String>,
    pub(crate) span: Option<Range<usize>>,
}

impl Location {
    /// Sets the field if none is set yet (inner functions know more precise fields).
    pub(crate) fn at_field(&mut self, field: impl Into<String>) {
        if self.field.is_none() {
            self.field = Some(field.into());
        }
    }

    /// Sets the joint if none is set yet (a URDF `<joint>` element).
    pub(crate) fn in_joint(&mut self, joint: &str) {
        if self.joint.is_none() {
            self.joint = Some(joint.to_owned());
        }
    }

    /// Sets the link if none is set yet.
    pub(crate) fn in_link(&mut self, link: &str) {
        if self.link.is_none() {
            self.link = Some(link.to_owned());
        }
    }

    /// Sets the byte range of the offending text if none is set yet.
    pub(crate) fn at_span(&mut self, span: Option<Range<usize>>) {
        if self.span.is_none() {
            self.span = span;
        }
    }

    /// Sets the file name and turns the byte range into a line number of `text`.
    pub(crate) fn locate(&mut self, file: &str, text: &str) {
        file.clone_into(&mut self.file);
        if self.line.is_none() {
            self.line = self
                .span
                .as_ref()
                .and_then(|span| text.get(..span.start))
                .map(|before| before.matches('\n').count() + 1);
        }
    }

    /// Sets the file name and turns the byte range into a line number by `lines`: what
    /// [`locate`](Self::locate) does, in logarithmic time, for the many warnings of one file.
    pub(crate) fn locate_in(&mut self, file: &str, lines: &Lines<'_>) {
        file.clone_into(&mut self.file);
        if self.line.is_none() {
            self.line = self.span.as_ref().and_then(|span| lines.line(span.start));
        }
    }

    /// `file:line: joint 'j', link 'l', field 'f': message`, leaving out what is unknown.
    pub(crate) fn render(&self, message: &str) -> String {
        let mut out = self.file.clone();
        if let Some(line) = self.line {
            out.push_str(&format!(":{line}"));
        }
        out.push_str(": ");
        let mut place = Vec::new();
        if let Some(joint) = &self.joint {
            place.push(format!("joint '{joint}'"));
        }
        if let Some(link) = &self.link {
            place.push(format!("link '{link}'"));
        }
        if let Some(field) = &self.field {
            place.push(format!("field '{field}'"));
        }
        if !place.is_empty() {
            out.push_str(&place.join(", "));
            out.push_str(": ");
        }
        out.push_str(message);
        out
    }
}

/// Where the lines of a text start, to give many byte offsets their line numbers without
/// counting the newlines before each (which made a file with thousands of warnings take a
/// time quadratic in its length).
pub(crate) struct Lines<'t> {
    text: &'t str,
    newlines: Vec<usize>,
}

impl<'t> Lines<'t> {
    /// The lines of `text`.
    pub(crate) fn new(text: &'t str) -> Lines<'t> {
        Lines {
            text,
            newlines: text.match_indices('\n').map(|(i, _)| i).collect(),
        }
    }

    /// The 1-based line of byte `offset`, as [`Location::locate`] counts it: `None` past the
    /// end or inside a character.
    pub(crate) fn line(&self, offset: usize) -> Option<usize> {
        self.text.get(..offset)?;
        Some(self.newlines.partition_point(|&n| n < offset) + 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_count_as_locate_does() {
        let text = "a\nbé\n\nc";
        let lines = Lines::new(text);
        for offset in 0..=text.len() + 1 {
            let mut counted = Location {
                span: Some(offset..offset),
                ..Location::default()
            };
            let mut indexed = counted.clone();
            counted.locate("f", text);
            indexed.locate_in("f", &lines);
            assert_eq!(counted, indexed, "offset {offset}");
        }
    }
}
