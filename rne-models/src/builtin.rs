//! The built-in robots: their spec files (embedded in the binary) and generated kernels.

use std::path::Path;

use rne_symbolic::spec::{load_file, parse_str, LoadOptions, SpecError};
use rne_symbolic::RobotModel;

use crate::generated;
use crate::impl_kernels;
use crate::kernels::Kernels;

impl_kernels!(PlanarElbow, generated::planar_elbow);
impl_kernels!(Irb140ThreeDof, generated::irb140_3dof);

/// A robot that ships with rne.
pub struct BuiltinRobot {
    /// The name used on the command line.
    pub name: &'static str,
    /// The spec file, relative to `rne-models/`.
    pub file: &'static str,
    /// The spec file's text.
    pub source: &'static str,
    /// One line about it.
    pub description: &'static str,
    /// Its generated kernels.
    pub kernels: &'static (dyn Kernels + Sync),
}

/// Every built-in robot.
pub static BUILTIN_ROBOTS: &[BuiltinRobot] = &[
    BuiltinRobot {
        name: "planar-elbow",
        file: "robots/planar-elbow.toml",
        source: include_str!("../robots/planar-elbow.toml"),
        description: "planar elbow manipulator, thesis chapter 4 and table 6.1",
        kernels: &PlanarElbow,
    },
    BuiltinRobot {
        name: "irb140-3dof",
        file: "robots/irb140-3dof.toml",
        source: include_str!("../robots/irb140-3dof.toml"),
        description: "ABB IRB 140, first three joints, thesis chapter 5 and table 6.2",
        kernels: &Irb140ThreeDof,
    },
];

/// The built-in robot called `name`.
pub fn builtin(name: &str) -> Option<&'static BuiltinRobot> {
    BUILTIN_ROBOTS.iter().find(|r| r.name == name)
}

/// A robot named on the command line: a built-in name, or a path to a spec file.
pub enum RobotSource {
    /// A built-in robot.
    Builtin(&'static BuiltinRobot),
    /// A file.
    File(std::path::PathBuf),
}

impl RobotSource {
    /// Resolves `model`: a built-in name first, then a path.
    pub fn resolve(model: &str) -> RobotSource {
        match builtin(model) {
            Some(robot) => RobotSource::Builtin(robot),
            None => RobotSource::File(Path::new(model).to_path_buf()),
        }
    }

    /// Reads the robot.
    pub fn load(&self, options: &LoadOptions) -> Result<RobotModel, SpecError> {
        match self {
            RobotSource::Builtin(robot) => parse_str(robot.source, robot.file, options),
            RobotSource::File(path) => load_file(path, options),
        }
    }

    /// The name to print.
    pub fn display_name(&self) -> String {
        match self {
            RobotSource::Builtin(robot) => robot.name.to_owned(),
            RobotSource::File(path) => path.display().to_string(),
        }
    }
}
