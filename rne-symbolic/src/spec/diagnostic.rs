//! A located message of spec reading, shared by errors ([`SpecError`](super::SpecError)) and
//! warnings ([`SpecWarning`](super::SpecWarning)): what kind, what is wrong, and where (file,
//! line, joint or link, field).

use std::fmt;
use std::ops::Range;

use super::location::{Lines, Location};

/// A message of kind `K` about a robot file, naming the file, the joint or link and the field.
///
/// Displays as `robots/arm.toml:12: link 'link2', field 'mass': mass must be >= 0, got -3`; the
/// line number appears when the reader knows where the offending text is, the joint, link and
/// field when the message belongs to one. A URDF message names the joint for what its
/// `<joint>` element says and the link for what its `<link>` element says:
/// `robots/arm.urdf:7: joint 'elbow', field 'axis': axis must not be zero`.
///
/// A struct with a kind rather than an enum with one variant per mistake: every message
/// carries the same location, callers that react to one match on the kind, and the message
/// says exactly what is wrong. It is boxed so that the `Result`s of the reader stay one pointer
/// wide.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic<K>(Box<Details<K>>);

#[derive(Clone, Debug, PartialEq, Eq)]
struct Details<K> {
    kind: K,
    message: String,
    at: Location,
}

impl<K: Copy> Diagnostic<K> {
    /// A message of this kind with no location yet; the reader adds the file, link and field
    /// as it travels outwards.
    pub(crate) fn new(kind: K, message: impl Into<String>) -> Self {
        Self::at(kind, message.into(), Location::default())
    }

    /// A message of this kind at `at`.
    pub(crate) fn at(kind: K, message: String, at: Location) -> Self {
        Diagnostic(Box::new(Details { kind, message, at }))
    }

    /// Sets the field if none is set yet (inner functions know more precise fields).
    pub(crate) fn at_field(mut self, field: impl Into<String>) -> Self {
        self.0.at.at_field(field);
        self
    }

    /// Sets the joint if none is set yet (a URDF `<joint>` element).
    pub(crate) fn in_joint(mut self, joint: &str) -> Self {
        self.0.at.in_joint(joint);
        self
    }

    /// Sets the link if none is set yet.
    pub(crate) fn in_link(mut self, link: &str) -> Self {
        self.0.at.in_link(link);
        self
    }

    /// Sets the byte range of the text concerned if none is set yet.
    pub(crate) fn at_span(mut self, span: Option<Range<usize>>) -> Self {
        self.0.at.at_span(span);
        self
    }

    /// Sets the file name and turns the byte range into a line number of `text`.
    pub(crate) fn locate(mut self, file: &str, text: &str) -> Self {
        self.0.at.locate(file, text);
        self
    }

    /// Sets the file name and turns the byte range into a line number by `lines` (for the
    /// many messages of one file).
    pub(crate) fn locate_in(mut self, file: &str, lines: &Lines<'_>) -> Self {
        self.0.at.locate_in(file, lines);
        self
    }

    /// Where the message belongs, for a reader that completes it.
    pub(crate) fn location_mut(&mut self) -> &mut Location {
        &mut self.0.at
    }

    /// The message's message and location, taken apart.
    pub(crate) fn into_parts(self) -> (String, Location) {
        let Details { message, at, .. } = *self.0;
        (message, at)
    }

    /// What kind of mistake or oddity this is.
    pub fn kind(&self) -> K {
        self.0.kind
    }

    /// The file (the `origin` given to `parse_str`, or the path given to
    /// `load_file`).
    pub fn file(&self) -> &str {
        &self.0.at.file
    }

    /// The 1-based line of the text concerned, when known.
    pub fn line(&self) -> Option<usize> {
        self.0.at.line
    }

    /// The URDF joint the message belongs to, if any.
    pub fn joint(&self) -> Option<&str> {
        self.0.at.joint.as_deref()
    }

    /// The link the message belongs to, if any.
    pub fn link(&self) -> Option<&str> {
        self.0.at.link.as_deref()
    }

    /// The field the message belongs to, if any (`mass`, `inertia.xy`, `dh.theta`, `com[1]`,
    /// `parameters.w`; in a URDF `axis`, `origin.rpy`, `inertial.mass`, ...).
    pub fn field(&self) -> Option<&str> {
        self.0.at.field.as_deref()
    }

    /// The description of the problem, without its location.
    pub fn message(&self) -> &str {
        &self.0.message
    }
}

impl<K> fmt::Display for Diagnostic<K> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0.at.render(&self.0.message))
    }
}
