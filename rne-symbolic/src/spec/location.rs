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
