//! The error of spec reading: what went wrong, and where (file, line, link, field).

use std::ops::Range;

use super::location::Location;

/// What kind of mistake a [`SpecError`] reports.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SpecErrorKind {
    /// The file could not be read.
    Io,
    /// The text is not valid TOML.
    Syntax,
    /// The TOML is valid but does not follow the spec format: an unknown or missing key, a
    /// value of the wrong type, zero or two frame conventions on a link.
    Format,
    /// A malformed expression, an unknown symbol, a bad power, a parameter cycle.
    Expression,
    /// A joint variable that does not enter its frame convention as the joint's motion: missing
    /// from a revolute `rotation`, not of the form ±q + c, a zero or non-unit axis.
    Kinematics,
    /// The link tree: unknown parent, duplicate link or joint names, cycles, no links; a mimic
    /// joint that follows a missing joint or, through other mimic joints, itself.
    Tree,
    /// Physically invalid numbers: negative mass, negative friction or armature, an inertia
    /// that is not symmetric or has a clearly negative principal moment, a value that is not
    /// finite.
    Physics,
    /// A URDF file that cannot be read (malformed XML, a missing or malformed element or
    /// attribute the dynamics reads) or that uses what a rigid-body tree with one-variable
    /// joints cannot model: floating, planar or spherical joints.
    Urdf,
    /// A warning ([`SpecWarning`](super::SpecWarning)) turned into an error by strict
    /// validation ([`LoadOptions::strict`](super::LoadOptions::strict)).
    Strict,
    /// A file name whose extension names no robot format (`.toml` or `.urdf`).
    UnknownFormat,
}

/// An error found while reading a robot spec (DESIGN §2), naming the file, the joint or link and
/// the field.
///
/// Displays as `robots/arm.toml:12: link 'link2', field 'mass': mass must be >= 0, got -3`; the
/// line number appears when the reader knows where the offending text is, the joint, link and
/// field when the error belongs to one. A URDF error names the joint for what its `<joint>`
/// element says and the link for what its `<link>` element says:
/// `robots/arm.urdf:7: joint 'elbow', field 'axis': axis must not be zero`.
///
/// A struct with a [`SpecErrorKind`] rather than an enum with one variant per mistake: every
/// error carries the same location, callers that react to errors match on the kind, and the
/// message says exactly what is wrong. It is boxed so that the `Result`s of the reader stay one
/// pointer wide.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}", self.0.at.render(&self.0.message))]
pub struct SpecError(Box<Details>);

#[derive(Clone, Debug, PartialEq, Eq)]
struct Details {
    kind: SpecErrorKind,
    message: String,
    at: Location,
}

impl SpecError {
    /// An error of this kind with no location yet; the reader adds the file, link and field as
    /// the error travels outwards.
    pub(crate) fn new(kind: SpecErrorKind, message: impl Into<String>) -> SpecError {
        SpecError(Box::new(Details {
            kind,
            message: message.into(),
            at: Location::default(),
        }))
    }

    /// An error of this kind at `at`.
    pub(crate) fn at(kind: SpecErrorKind, message: String, at: Location) -> SpecError {
        SpecError(Box::new(Details { kind, message, at }))
    }

    /// Sets the field if none is set yet (inner functions know more precise fields).
    pub(crate) fn at_field(mut self, field: impl Into<String>) -> SpecError {
        self.0.at.at_field(field);
        self
    }

    /// Sets the joint if none is set yet (a URDF `<joint>` element).
    pub(crate) fn in_joint(mut self, joint: &str) -> SpecError {
        self.0.at.in_joint(joint);
        self
    }

    /// Sets the link if none is set yet.
    pub(crate) fn in_link(mut self, link: &str) -> SpecError {
        self.0.at.in_link(link);
        self
    }

    /// Sets the byte range of the offending text if none is set yet.
    pub(crate) fn at_span(mut self, span: Option<Range<usize>>) -> SpecError {
        self.0.at.at_span(span);
        self
    }

    /// Sets the file name and turns the byte range into a line number of `text`.
    pub(crate) fn locate(mut self, file: &str, text: &str) -> SpecError {
        self.0.at.locate(file, text);
        self
    }

    /// Where the error belongs, for a reader that completes it.
    pub(crate) fn location_mut(&mut self) -> &mut Location {
        &mut self.0.at
    }

    /// What kind of mistake this is.
    pub fn kind(&self) -> SpecErrorKind {
        self.0.kind
    }

    /// The file (the `origin` given to [`parse_str`](super::parse_str), or the path given to
    /// [`load_file`](super::load_file)).
    pub fn file(&self) -> &str {
        &self.0.at.file
    }

    /// The 1-based line of the offending text, when known.
    pub fn line(&self) -> Option<usize> {
        self.0.at.line
    }

    /// The URDF joint the error belongs to, if any.
    pub fn joint(&self) -> Option<&str> {
        self.0.at.joint.as_deref()
    }

    /// The link the error belongs to, if any.
    pub fn link(&self) -> Option<&str> {
        self.0.at.link.as_deref()
    }

    /// The field the error belongs to, if any (`mass`, `inertia.xy`, `dh.theta`, `com[1]`,
    /// `parameters.w`; in a URDF `axis`, `origin.rpy`, `inertial.mass`, ...).
    pub fn field(&self) -> Option<&str> {
        self.0.at.field.as_deref()
    }

    /// The description of the problem, without its location.
    pub fn message(&self) -> &str {
        &self.0.message
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn displays_file_line_link_and_field() {
        let text = "a\nb\nmass = -3\n";
        let error = SpecError::new(SpecErrorKind::Physics, "mass must be >= 0, got -3")
            .at_field("mass")
            .in_link("link2")
            .at_span(Some(11..13))
            .locate("robots/arm.toml", text);
        assert_eq!(
            error.to_string(),
            "robots/arm.toml:3: link 'link2', field 'mass': mass must be >= 0, got -3"
        );
        assert_eq!(error.line(), Some(3));
    }

    #[test]
    fn displays_the_joint_of_a_urdf() {
        let error = SpecError::new(SpecErrorKind::Kinematics, "axis must not be zero")
            .at_field("axis")
            .in_joint("elbow")
            .at_span(Some(30..40))
            .locate(
                "robots/arm.urdf",
                "<robot>\n<link/>\n<link/>\n<joint name=\"elbow\">",
            );
        assert_eq!(
            error.to_string(),
            "robots/arm.urdf:4: joint 'elbow', field 'axis': axis must not be zero"
        );
        assert_eq!(error.joint(), Some("elbow"));
        assert_eq!(error.link(), None);
    }

    #[test]
    fn omits_what_is_unknown() {
        let error =
            SpecError::new(SpecErrorKind::Tree, "the spec has no [[link]]").locate("x.toml", "");
        assert_eq!(error.to_string(), "x.toml: the spec has no [[link]]");
    }

    #[test]
    fn inner_locations_win() {
        let error = SpecError::new(SpecErrorKind::Format, "m")
            .at_field("inertia.xy")
            .at_field("inertia");
        assert_eq!(error.field(), Some("inertia.xy"));
    }
}
