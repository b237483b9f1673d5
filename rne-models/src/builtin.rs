//! The built-in robots: their spec files (embedded in the crate) and generated modules.

use std::path::Path;

use rne_symbolic::spec::{LoadOptions, SpecError};
use rne_symbolic::RobotModel;
use rne_symbolic::{read_robot, Description};

use rne_codegen::{Dynamics, Kernel};

use crate::generated;
use crate::robot_file::parse_embedded;
use crate::visit::Visitor;

/// Which generated module a built-in robot has.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Module {
    PlanarElbow,
    Irb140ThreeDof,
    Puma560,
    Ur5,
    Panda,
    PandaArm,
    Irb140,
}

/// A robot that ships with rne.
pub struct BuiltinRobot {
    /// The name used on the command line.
    pub name: &'static str,
    /// The spec file (`.toml` or `.urdf`), relative to `rne-models/`.
    pub file: &'static str,
    /// The spec file's text.
    pub source: &'static str,
    /// One line about it.
    pub description: &'static str,
    /// Its generated module, for [`BuiltinRobot::visit`].
    module: Module,
}

impl BuiltinRobot {
    /// Runs `visitor` on the robot's generated `Model` (every kernel, `f64`).
    pub fn visit<V: Visitor>(&self, visitor: V) -> V::Output {
        match self.module {
            Module::PlanarElbow => visitor.visit(generated::planar_elbow::Model),
            Module::Irb140ThreeDof => visitor.visit(generated::irb140_3dof::Model),
            Module::Puma560 => visitor.visit(generated::puma560::Model),
            Module::Ur5 => visitor.visit(generated::ur5::Model),
            Module::Panda => visitor.visit(generated::panda::Model),
            Module::PandaArm => visitor.visit(generated::panda_arm::Model),
            Module::Irb140 => visitor.visit(generated::irb140::Model),
        }
    }

    /// Runs `visitor` on the robot's generated module for `kernel`: for M⁻¹ and the
    /// derivatives, the `Dynamics` kernels that the default module leaves out, the URDF
    /// robots' `control` module ([`generated::variants`]); else the default one.
    pub fn visit_having<V: Visitor>(&self, kernel: Kernel, visitor: V) -> V::Output {
        use generated::variants;
        match self.module {
            Module::Ur5 if lacks(generated::ur5::Model, kernel) => {
                visitor.visit(variants::ur5::control::Model)
            }
            Module::Panda if lacks(generated::panda::Model, kernel) => {
                visitor.visit(variants::panda::control::Model)
            }
            Module::PandaArm if lacks(generated::panda_arm::Model, kernel) => {
                visitor.visit(variants::panda_arm::control::Model)
            }
            _ => self.visit(visitor),
        }
    }
}

/// Whether the module of `model` lacks `kernel`, one of the `Dynamics` kernels that the
/// URDF robots' `control` modules have (M⁻¹, ∂ID, ∂FD).
fn lacks<const N: usize, D: Dynamics<N, N>>(_model: D, kernel: Kernel) -> bool {
    let in_control = [
        Kernel::MassMatrixInverse,
        Kernel::InverseDynamicsDerivatives,
        Kernel::ForwardDynamicsDerivatives,
    ];
    in_control.contains(&kernel) && !D::KERNELS.contains(&kernel)
}

/// Every built-in robot.
pub static BUILTIN_ROBOTS: &[BuiltinRobot] = &[
    BuiltinRobot {
        name: "planar-elbow",
        file: "robots/planar-elbow.toml",
        source: include_str!("../robots/planar-elbow.toml"),
        description: "planar elbow manipulator, thesis chapter 4 and table 6.1",
        module: Module::PlanarElbow,
    },
    BuiltinRobot {
        name: "irb140-3dof",
        file: "robots/irb140-3dof.toml",
        source: include_str!("../robots/irb140-3dof.toml"),
        description: "ABB IRB 140, first three joints, thesis chapter 5 and table 6.2",
        module: Module::Irb140ThreeDof,
    },
    BuiltinRobot {
        name: "puma560",
        file: "robots/puma560.toml",
        source: include_str!("../robots/puma560.toml"),
        description: "PUMA 560, standard DH, Corke & Armstrong-Helouvry (ICRA 1994) parameters",
        module: Module::Puma560,
    },
    BuiltinRobot {
        name: "ur5",
        file: "robots/ur5.urdf",
        source: include_str!("../robots/ur5.urdf"),
        description: "Universal Robots UR5, ros-industrial description",
        module: Module::Ur5,
    },
    BuiltinRobot {
        name: "panda",
        file: "robots/panda.urdf",
        source: include_str!("../robots/panda.urdf"),
        description: "Franka Emika Panda with hand and two fingers (9 joints, a tree), Gaz et al. 2019",
        module: Module::Panda,
    },
    BuiltinRobot {
        name: "panda-arm",
        file: "robots/panda-arm.urdf",
        source: include_str!("../robots/panda-arm.urdf"),
        description: "Franka Emika Panda arm to the flange, no hand (7 joints), Gaz et al. 2019",
        module: Module::PandaArm,
    },
    BuiltinRobot {
        name: "irb140",
        file: "robots/irb140.toml",
        source: include_str!("../robots/irb140.toml"),
        description: "ABB IRB 140, six joints: thesis chapter 5 and ABB's wrist geometry (wrist inertials estimated)",
        module: Module::Irb140,
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

    /// Reads the robot, a TOML spec or a URDF as its file's extension says.
    pub fn load(&self, options: &LoadOptions) -> Result<RobotModel, SpecError> {
        match self {
            RobotSource::Builtin(robot) => parse_embedded(robot.source, robot.file, options),
            RobotSource::File(path) => read_robot(Description::file(path), options),
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
