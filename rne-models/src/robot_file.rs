//! Robot files as files: the `robots/` directory for programs that take a path (the `rne`
//! command, `rne corpus`, Pinocchio's scripts), and the files in it that have no generated
//! module.

use std::path::{Path, PathBuf};

use rne_symbolic::spec::{LoadOptions, RobotFormat, SpecError};
use rne_symbolic::RobotModel;
use rne_symbolic::{read_robot, Description};

/// The `robots/` directory of the source tree this crate was built from.
pub fn robots_dir() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/robots"))
}

/// A robot file of `robots/` without a generated module: a robot for the commands and tests
/// that need what the built-in robots lack.
pub struct RobotFile {
    /// The file, relative to `rne-models/` (as messages name it).
    pub file: &'static str,
    /// The file's text.
    pub source: &'static str,
    /// One line about it.
    pub description: &'static str,
}

impl RobotFile {
    /// The file's path on disk, in [`robots_dir`].
    pub fn path(&self) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join(self.file)
    }

    /// Reads the robot, a TOML spec or a URDF as its file's extension says.
    pub fn load(&self, options: &LoadOptions) -> Result<RobotModel, SpecError> {
        parse_embedded(self.source, self.file, options)
    }
}

/// A quadruped: a trunk with a fixed IMU link and four two-joint legs (continuous hips, joint
/// names that are numbers, dotted or unicode, rotated inertial frames, massless feet). Fixed
/// to the world as a URDF reads; on a free-flyer (`--floating-base`, `set_base`) NV = 6 + 8.
/// Its Pinocchio 4.1 values are in rne-corpus's test data.
pub static QUADRUPED: RobotFile = RobotFile {
    file: "robots/quadruped.urdf",
    source: include_str!("../robots/quadruped.urdf"),
    description: "a trunk and four two-joint legs, for floating-base tests and examples",
};

/// Reads an embedded robot file's text, named `file` in messages.
pub(crate) fn parse_embedded(
    source: &str,
    file: &str,
    options: &LoadOptions,
) -> Result<RobotModel, SpecError> {
    let format = RobotFormat::from_path(Path::new(file))?;
    read_robot(Description::text(source, format, file), options)
}
