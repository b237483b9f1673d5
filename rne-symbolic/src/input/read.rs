//! The one way into the crate for a robot description: a file, or text (or bytes) in a named
//! format, read with [`LoadOptions`] by [`read_robot`]. The format readers (TOML spec, URDF)
//! are private behind it.

use std::borrow::Cow;
use std::path::Path;

use super::format::{decode, read_text, RobotFormat};
use super::LoadOptions;
use crate::spec::SpecError;
use crate::RobotModel;

/// A robot description to read: where it is, its format, and the name errors and warnings
/// give it.
#[derive(Clone, Debug)]
pub struct Description<'a> {
    /// Where the description is.
    content: Content<'a>,
    /// The file's name in messages; the path as it displays when not given.
    origin: Option<Cow<'a, str>>,
}

/// Where a description is, and in what format when it is not a file's extension that says.
#[derive(Clone, Debug)]
enum Content<'a> {
    File(&'a Path),
    Text(&'a str, RobotFormat),
    Bytes(&'a [u8], RobotFormat),
}

impl<'a> Description<'a> {
    /// The file at `path`, a TOML spec or a URDF as its extension says
    /// ([`RobotFormat::from_path`]), named in messages as `path` displays.
    pub fn file(path: &'a Path) -> Description<'a> {
        Description {
            content: Content::File(path),
            origin: None,
        }
    }

    /// `text` in `format`, named `origin` in messages.
    pub fn text(text: &'a str, format: RobotFormat, origin: &'a str) -> Description<'a> {
        Description {
            content: Content::Text(text, format),
            origin: Some(Cow::Borrowed(origin)),
        }
    }

    /// A TOML spec held in `text`, named `origin` in messages.
    pub fn toml(text: &'a str, origin: &'a str) -> Description<'a> {
        Description::text(text, RobotFormat::Toml, origin)
    }

    /// A URDF held in `text`, named `origin` in messages.
    pub fn urdf(text: &'a str, origin: &'a str) -> Description<'a> {
        Description::text(text, RobotFormat::Urdf, origin)
    }

    /// A file's contents as the caller read them, in `format`, named `origin` in messages:
    /// bytes that are not UTF-8 are an error naming the line and column of the first one.
    pub fn bytes(bytes: &'a [u8], format: RobotFormat, origin: &'a str) -> Description<'a> {
        Description {
            content: Content::Bytes(bytes, format),
            origin: Some(Cow::Borrowed(origin)),
        }
    }

    /// The same description, named `origin` in messages (a file's path as its user wrote it,
    /// a built-in robot's file relative to its crate).
    pub fn named(self, origin: &'a str) -> Description<'a> {
        Description {
            origin: Some(Cow::Borrowed(origin)),
            ..self
        }
    }

    /// The name messages give the description.
    pub fn origin(&self) -> Cow<'a, str> {
        match (&self.origin, &self.content) {
            (Some(origin), _) => origin.clone(),
            (None, Content::File(path)) => Cow::Owned(path.display().to_string()),
            (None, _) => Cow::Borrowed(""),
        }
    }
}

/// Reads a robot description (docs/design.md §2: a TOML spec or a URDF) into a
/// [`RobotModel`], as `options` say. Errors and warnings name the file, the line, the link or
/// joint and the field.
pub fn read_robot(
    description: Description<'_>,
    options: &LoadOptions,
) -> Result<RobotModel, SpecError> {
    let origin = description.origin();
    let (text, format) = match description.content {
        Content::File(path) => {
            let format = RobotFormat::from_path(path)?;
            (Cow::Owned(read_text(path, &origin)?), format)
        }
        Content::Text(text, format) => (Cow::Borrowed(text), format),
        Content::Bytes(bytes, format) => (Cow::Owned(decode(bytes.to_vec(), &origin)?), format),
    };
    match format {
        RobotFormat::Toml => crate::spec::parse_str(&text, &origin, options),
        RobotFormat::Urdf => crate::urdf::parse_str(&text, &origin, options),
    }
}
