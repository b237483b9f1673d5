//! The warnings of spec reading: what published robot data often gets slightly wrong while the
//! mathematics survives (docs/design.md §2.4), located like errors.

use super::diagnostic::Diagnostic;
use super::error::{SpecError, SpecErrorKind};

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
pub type SpecWarning = Diagnostic<SpecWarningKind>;

impl SpecWarning {
    /// The error strict validation makes of this warning: same location, kind
    /// [`SpecErrorKind::Strict`], the message marked as such.
    pub fn into_error(self) -> SpecError {
        let (message, at) = self.into_parts();
        SpecError::at(
            SpecErrorKind::Strict,
            format!("{message} (an error under strict validation)"),
            at,
        )
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
