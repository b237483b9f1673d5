//! The error of spec reading: what went wrong, and where (file, line, link, field).

use super::diagnostic::Diagnostic;

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

/// An error found while reading a robot spec (docs/design.md §2.3), naming the file, the joint or
/// link and the field: `robots/arm.toml:12: link 'link2', field 'mass': mass must be >= 0, got -3`
/// (see [`Diagnostic`] for its parts).
pub type SpecError = Diagnostic<SpecErrorKind>;

impl std::error::Error for SpecError {}

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
