//! Which reader a robot file goes to: the TOML spec of docs/design.md §2.1 or a URDF, told apart by
//! the file name's extension.

use std::path::Path;

use super::LoadOptions;
use crate::spec::{SpecError, SpecErrorKind};
use crate::RobotModel;

/// The format of a robot description.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum RobotFormat {
    /// The TOML spec of docs/design.md §2.1 (`.toml`), read by [`crate::spec::parse_str`].
    Toml,
    /// A URDF file (`.urdf`), read by [`crate::urdf::parse_str`].
    Urdf,
}

impl RobotFormat {
    /// The format named by `path`'s extension, `.toml` or `.urdf` (in any letter case); any
    /// other name is a [`SpecErrorKind::UnknownFormat`] error naming the file.
    pub fn from_path(path: &Path) -> Result<RobotFormat, SpecError> {
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match extension.as_deref() {
            Some("toml") => Ok(RobotFormat::Toml),
            Some("urdf") => Ok(RobotFormat::Urdf),
            Some("xml" | "mjcf") => Err(SpecError::new(
                SpecErrorKind::UnknownFormat,
                crate::urdf::MJCF_UNSUPPORTED,
            )
            .locate(&path.display().to_string(), "")),
            other => {
                let hint = if other == Some("xacro") {
                    " (expand a .xacro file with xacro into a .urdf first)"
                } else {
                    ""
                };
                Err(SpecError::new(
                    SpecErrorKind::UnknownFormat,
                    format!(
                        "cannot tell the robot format from the file name: expected a .toml or \
                         .urdf extension{hint}"
                    ),
                )
                .locate(&path.display().to_string(), ""))
            }
        }
    }
}

/// Reads the robot file at `path`, a TOML spec or a URDF as its extension says
/// ([`RobotFormat::from_path`]); errors name the file as `path` displays.
pub fn load_robot(path: &Path, options: &LoadOptions) -> Result<RobotModel, SpecError> {
    let format = RobotFormat::from_path(path)?;
    let origin = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| {
        SpecError::new(
            SpecErrorKind::Io,
            format!("cannot read the robot file: {e}"),
        )
        .locate(&origin, "")
    })?;
    parse_robot(&text, &origin, format, options)
}

/// Reads a robot description in `format` from `text`; `origin` names the file in error
/// messages.
pub fn parse_robot(
    text: &str,
    origin: &str,
    format: RobotFormat,
    options: &LoadOptions,
) -> Result<RobotModel, SpecError> {
    match format {
        RobotFormat::Toml => crate::spec::parse_str(text, origin, options),
        RobotFormat::Urdf => crate::urdf::parse_str(text, origin, options),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_follow_the_extension() {
        let format = |name: &str| RobotFormat::from_path(Path::new(name));
        assert_eq!(format("robots/arm.toml"), Ok(RobotFormat::Toml));
        assert_eq!(format("robots/arm.urdf"), Ok(RobotFormat::Urdf));
        assert_eq!(format("ARM.URDF"), Ok(RobotFormat::Urdf));
        let error = format("robots/arm.stl").unwrap_err();
        assert_eq!(error.kind(), SpecErrorKind::UnknownFormat);
        assert_eq!(
            error.to_string(),
            "robots/arm.stl: cannot tell the robot format from the file name: expected a .toml \
             or .urdf extension"
        );
        let mjcf = format("robots/arm.xml").unwrap_err();
        assert_eq!(mjcf.kind(), SpecErrorKind::UnknownFormat);
        assert!(mjcf.to_string().contains("MJCF"), "{mjcf}");
        assert!(format("arm.urdf.xacro")
            .unwrap_err()
            .message()
            .ends_with("(expand a .xacro file with xacro into a .urdf first)"));
        assert!(format("robots/arm").is_err());
    }
}
