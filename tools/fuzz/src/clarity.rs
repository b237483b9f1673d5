//! Whether a reader's error is clear: its message names the file (required), and the element
//! and field a mutation aimed at (counted, best effort: an error may rightly be about
//! something else the mutation broke).

use crate::mutate::Focus;

/// What an error message names.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct Naming {
    /// It names the file.
    pub file: bool,
    /// The mutations aimed at an element, and it names one of them (`None`: none aimed).
    pub element: Option<bool>,
    /// The mutations aimed at a field, and it names one of them (`None`: none aimed).
    pub field: Option<bool>,
}

/// What `message` names of `file` and of what `focus` aimed at.
pub fn naming(message: &str, file: &str, focus: &[Focus]) -> Naming {
    let elements: Vec<&str> = focus.iter().filter_map(|f| f.element.as_deref()).collect();
    let fields: Vec<&str> = focus.iter().filter_map(|f| f.field.as_deref()).collect();
    let names = |items: &[&str]| {
        (!items.is_empty()).then(|| items.iter().any(|item| message.contains(item)))
    };
    Naming {
        file: message.starts_with(file),
        element: names(&elements),
        field: names(&fields),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_file_element_and_field() {
        let focus = [Focus {
            element: Some("elbow".into()),
            field: Some("axis".into()),
        }];
        let message = "arm.urdf:7: joint 'elbow', field 'axis': axis must not be zero";
        assert_eq!(
            naming(message, "arm.urdf", &focus),
            Naming {
                file: true,
                element: Some(true),
                field: Some(true)
            }
        );
        let vague = naming("cannot read: invalid number", "arm.urdf", &focus);
        assert_eq!(
            (vague.file, vague.element, vague.field),
            (false, Some(false), Some(false))
        );
        assert_eq!(naming(message, "arm.urdf", &[]).element, None);
    }
}
