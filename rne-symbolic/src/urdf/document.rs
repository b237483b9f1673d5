//! The URDF XML parsed by urdf-rs into its `Robot` (links and joints in file order).

use quick_xml::events::Event;
use quick_xml::Reader;
use urdf_rs::Robot;

use crate::spec::{SpecError, SpecErrorKind};

/// The deepest element nesting read. URDF elements nest five deep at most (`robot`, `link`,
/// `visual`, `geometry`, `mesh`); the readers behind urdf-rs recurse once per level, and some
/// ten thousand levels overflow the stack, which aborts the process.
const MAX_NESTING: usize = 64;

/// Parses `text`; the error carries urdf-rs's description of what is malformed (without the
/// `custom: ` its deserialiser puts before some).
pub(crate) fn read(text: &str) -> Result<Robot, SpecError> {
    check_nesting(text)?;
    urdf_rs::read_from_string(text).map_err(|e| {
        let description = e.to_string();
        let description = description.strip_prefix("custom: ").unwrap_or(&description);
        SpecError::new(
            SpecErrorKind::Urdf,
            format!("cannot read the URDF: {description}"),
        )
    })
}

/// Refuses elements nested deeper than [`MAX_NESTING`], naming the line, before urdf-rs reads
/// them. Malformed XML is left to urdf-rs, which describes it.
fn check_nesting(text: &str) -> Result<(), SpecError> {
    let mut reader = Reader::from_str(text);
    let mut depth = 0usize;
    loop {
        match reader.read_event() {
            Ok(Event::Start(_)) => {
                depth += 1;
                if depth > MAX_NESTING {
                    let offset = usize::try_from(reader.buffer_position()).unwrap_or(usize::MAX);
                    let line = text
                        .get(..offset)
                        .map_or(0, |before| before.matches('\n').count())
                        + 1;
                    return Err(SpecError::new(
                        SpecErrorKind::Urdf,
                        format!(
                            "cannot read the URDF: elements nest more than {MAX_NESTING} deep \
                             (line {line})"
                        ),
                    ));
                }
            }
            Ok(Event::End(_)) => depth = depth.saturating_sub(1),
            Ok(Event::Eof) | Err(_) => return Ok(()),
            Ok(_) => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nested(levels: usize) -> String {
        format!(
            "<robot name=\"r\">\n{}{}</robot>",
            "<x>".repeat(levels),
            "</x>".repeat(levels)
        )
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_stack_overflow() {
        let error = read(&nested(50_000)).unwrap_err();
        assert!(
            error.message().contains("nest more than 64 deep (line 2)"),
            "{}",
            error.message()
        );
    }

    #[test]
    fn nesting_up_to_the_limit_is_left_to_urdf_rs() {
        assert!(check_nesting(&nested(MAX_NESTING - 1)).is_ok());
        assert!(check_nesting(&nested(MAX_NESTING)).is_err());
    }
}
