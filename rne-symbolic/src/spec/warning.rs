//! The warnings of spec reading: what published robot data often gets slightly wrong while the
//! mathematics survives (DESIGN §2), located like errors.

use std::fmt;
use std::ops::Range;

use super::error::{SpecError, SpecErrorKind};
use super::location::Location;

/// What a [`SpecWarning`] reports.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SpecWarningKind {
    /// The principal moments of a link with mass break the triangle inequality
    /// I1 + I2 ≥ I3: no rigid body has that inertia, but M(q) stays positive definite.
    TriangleInequality,
    /// A rotational inertia with a negative principal moment that is negligible against the
    /// robot's inertia scale (rounding in the published numbers); see
    /// [`NEGLIGIBLE_INERTIA`](crate::input::NEGLIGIBLE_INERTIA).
    NegligibleNegativeInertia,
    /// A moving joint whose link and every link beyond it have no mass and no inertia: the
    /// joint is kept for kinematics, but M(q) is singular and forward dynamics undefined.
    MasslessSubtree,
    /// A mimic joint whose leader is not a moving joint of the robot, read with mimic joints
    /// free ([`LoadOptions::free_mimic`](crate::spec::LoadOptions::free_mimic)): the mimic
    /// is dropped and the joint is a joint of its own.
    MimicLeaderMissing,
}

/// A warning found while reading a robot file, naming the file, the joint or link and the field
/// as a [`SpecError`] does, and displayed the same way:
/// `robots/arm.urdf:10: link 'upper', field 'inertial.inertia': inertia breaks the triangle
/// inequality: ...`. [`RobotModel::warnings`](crate::RobotModel::warnings) lists them;
/// [`LoadOptions::strict`](super::LoadOptions::strict) turns the first into an error.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpecWarning(Box<Details>);

#[derive(Clone, Debug, PartialEq, Eq)]
struct Details {
    kind: SpecWarningKind,
    message: String,
    at: Location,
}

impl SpecWarning {
    /// A warning of this kind with no location yet.
    pub(crate) fn new(kind: SpecWarningKind, message: impl Into<String>) -> SpecWarning {
        SpecWarning(Box::new(Details {
            kind,
            message: message.into(),
            at: Location::default(),
        }))
    }

    /// Sets the field if none is set yet.
    pub(crate) fn at_field(mut self, field: impl Into<String>) -> SpecWarning {
        self.0.at.at_field(field);
        self
    }

    /// Sets the joint if none is set yet.
    pub(crate) fn in_joint(mut self, joint: &str) -> SpecWarning {
        self.0.at.in_joint(joint);
        self
    }

    /// Sets the link if none is set yet.
    pub(crate) fn in_link(mut self, link: &str) -> SpecWarning {
        self.0.at.in_link(link);
        self
    }

    /// Sets the byte range of the text warned about if none is set yet.
    pub(crate) fn at_span(mut self, span: Option<Range<usize>>) -> SpecWarning {
        self.0.at.at_span(span);
        self
    }

    /// Sets the file name and turns the byte range into a line number of `text`.
    pub(crate) fn locate(mut self, file: &str, text: &str) -> SpecWarning {
        self.0.at.locate(file, text);
        self
    }

    /// The error strict validation makes of this warning: same location, kind
    /// [`SpecErrorKind::Strict`], the message marked as such.
    pub fn into_error(self) -> SpecError {
        let Details { message, at, .. } = *self.0;
        SpecError::at(
            SpecErrorKind::Strict,
            format!("{message} (an error under strict validation)"),
            at,
        )
    }

    /// What the warning is about.
    pub fn kind(&self) -> SpecWarningKind {
        self.0.kind
    }

    /// The file.
    pub fn file(&self) -> &str {
        &self.0.at.file
    }

    /// The 1-based line of the text warned about, when known.
    pub fn line(&self) -> Option<usize> {
        self.0.at.line
    }

    /// The URDF joint the warning belongs to, if any.
    pub fn joint(&self) -> Option<&str> {
        self.0.at.joint.as_deref()
    }

    /// The link the warning belongs to, if any.
    pub fn link(&self) -> Option<&str> {
        self.0.at.link.as_deref()
    }

    /// The field the warning belongs to, if any.
    pub fn field(&self) -> Option<&str> {
        self.0.at.field.as_deref()
    }

    /// The description, without the location.
    pub fn message(&self) -> &str {
        &self.0.message
    }
}

impl fmt::Display for SpecWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0.at.render(&self.0.message))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn displays_like_an_error_and_becomes_one_under_strict_validation() {
        let text = "<robot>\n<link name=\"a\">";
        let warning = SpecWarning::new(SpecWarningKind::TriangleInequality, "inertia breaks it")
            .at_field("inertial.inertia")
            .in_link("a")
            .at_span(Some(8..20))
            .locate("arm.urdf", text);
        assert_eq!(
            warning.to_string(),
            "arm.urdf:2: link 'a', field 'inertial.inertia': inertia breaks it"
        );
        let error = warning.into_error();
        assert_eq!(error.kind(), SpecErrorKind::Strict);
        assert_eq!(
            error.to_string(),
            "arm.urdf:2: link 'a', field 'inertial.inertia': inertia breaks it (an error under \
             strict validation)"
        );
    }
}
