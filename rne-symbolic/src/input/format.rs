//! Which reader a robot file goes to: the TOML spec of docs/design.md §2.1 or a URDF, told apart by
//! the file name's extension.

use std::path::Path;

use crate::spec::{SpecError, SpecErrorKind};

/// The format of a robot description.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum RobotFormat {
    /// The TOML spec of docs/design.md §2.1 (`.toml`), read by the spec reader ([`crate::spec`]).
    Toml,
    /// A URDF file (`.urdf`), read by the URDF reader.
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

/// The text of the robot file at `path`, named `origin` in errors: an error when it cannot be
/// read, and one naming the line and column of the first byte that is not UTF-8 when it is
/// not UTF-8 text.
pub(crate) fn read_text(path: &Path, origin: &str) -> Result<String, SpecError> {
    let bytes = std::fs::read(path).map_err(|e| {
        SpecError::new(
            SpecErrorKind::Io,
            format!("cannot read the robot file: {e}"),
        )
        .locate(origin, "")
    })?;
    decode(bytes, origin)
}

/// `bytes` as UTF-8 text, or an error naming `origin` and the line and column of the first
/// byte that is not UTF-8.
pub(crate) fn decode(bytes: Vec<u8>, origin: &str) -> Result<String, SpecError> {
    String::from_utf8(bytes).map_err(|e| {
        let error = e.utf8_error();
        let bytes = e.as_bytes();
        let valid = error.valid_up_to();
        // Valid up to `valid` by the error's own account.
        let before = std::str::from_utf8(&bytes[..valid]).unwrap_or_default();
        let column = before.len() - before.rfind('\n').map_or(0, |n| n + 1) + 1;
        let message = match error.error_len() {
            Some(_) => format!(
                "the file is not UTF-8 text: byte {:#04x} at column {column} is not valid \
                 UTF-8 (robot files are UTF-8)",
                bytes[valid]
            ),
            None => format!(
                "the file is not UTF-8 text: it ends inside a UTF-8 character at column \
                 {column} (robot files are UTF-8)"
            ),
        };
        SpecError::new(SpecErrorKind::Io, message)
            .at_span(Some(valid..valid))
            .locate(origin, before)
    })
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
        let error = format("robots/arm.obj").unwrap_err();
        assert_eq!(error.kind(), SpecErrorKind::UnknownFormat);
        assert_eq!(
            error.to_string(),
            "robots/arm.obj: cannot tell the robot format from the file name: expected a .toml \
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

    /// Bytes that are not UTF-8 (a fuzzed file: stray bytes, truncation inside a character)
    /// are an error naming the file, the line and the column of the first one.
    #[test]
    fn bytes_that_are_not_utf8_are_located() {
        let error = decode(b"<robot>\n  <li\xffnk/>".to_vec(), "arm.urdf").unwrap_err();
        assert_eq!(error.kind(), SpecErrorKind::Io);
        assert_eq!(
            error.to_string(),
            "arm.urdf:2: the file is not UTF-8 text: byte 0xff at column 6 is not valid UTF-8 \
             (robot files are UTF-8)"
        );
        let error = decode("name = \"é".as_bytes()[..9].to_vec(), "arm.toml").unwrap_err();
        assert_eq!(
            error.to_string(),
            "arm.toml:1: the file is not UTF-8 text: it ends inside a UTF-8 character at \
             column 9 (robot files are UTF-8)"
        );
        assert_eq!(decode(b"ok".to_vec(), "x.toml").unwrap(), "ok");
    }
}
