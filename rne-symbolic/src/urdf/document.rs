//! The URDF XML parsed by urdf-rs into its `Robot` (links and joints in file order).

use urdf_rs::Robot;

use crate::spec::{SpecError, SpecErrorKind};

/// Parses `text`; the error carries urdf-rs's description of what is malformed (without the
/// `custom: ` its deserialiser puts before some).
pub(crate) fn read(text: &str) -> Result<Robot, SpecError> {
    urdf_rs::read_from_string(text).map_err(|e| {
        let description = e.to_string();
        let description = description.strip_prefix("custom: ").unwrap_or(&description);
        SpecError::new(
            SpecErrorKind::Urdf,
            format!("cannot read the URDF: {description}"),
        )
    })
}
