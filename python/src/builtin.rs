//! The robots that ship with rne, by the names `rne models` lists, and `quadruped` (rne-models'
//! floating-base example robot file): their files embedded in the extension, so that
//! `rne.load("ur5")` needs no file on disk.
//!
//! The table names the same files as rne-models' `BUILTIN_ROBOTS` and `QUADRUPED` (whose crate
//! also compiles every built-in robot's kernels ahead of time, which the JIT makes unnecessary
//! here); the tests check that every name loads.

/// A built-in robot: its name, its file (relative to `rne-models/`, as messages name it) and
/// the file's text.
pub(crate) struct Builtin {
    /// The name `rne models` lists.
    pub name: &'static str,
    /// The file, relative to `rne-models/`.
    pub file: &'static str,
    /// The file's text.
    pub source: &'static str,
}

/// Every built-in robot.
pub(crate) static BUILTINS: &[Builtin] = &[
    Builtin {
        name: "planar-elbow",
        file: "robots/planar-elbow.toml",
        source: include_str!("../../rne-models/robots/planar-elbow.toml"),
    },
    Builtin {
        name: "irb140-3dof",
        file: "robots/irb140-3dof.toml",
        source: include_str!("../../rne-models/robots/irb140-3dof.toml"),
    },
    Builtin {
        name: "puma560",
        file: "robots/puma560.toml",
        source: include_str!("../../rne-models/robots/puma560.toml"),
    },
    Builtin {
        name: "ur5",
        file: "robots/ur5.urdf",
        source: include_str!("../../rne-models/robots/ur5.urdf"),
    },
    Builtin {
        name: "panda",
        file: "robots/panda.urdf",
        source: include_str!("../../rne-models/robots/panda.urdf"),
    },
    Builtin {
        name: "panda-arm",
        file: "robots/panda-arm.urdf",
        source: include_str!("../../rne-models/robots/panda-arm.urdf"),
    },
    Builtin {
        name: "irb140",
        file: "robots/irb140.toml",
        source: include_str!("../../rne-models/robots/irb140.toml"),
    },
    Builtin {
        name: "quadruped",
        file: "robots/quadruped.urdf",
        source: include_str!("../../rne-models/robots/quadruped.urdf"),
    },
];

/// The built-in robot called `name`.
pub(crate) fn builtin(name: &str) -> Option<&'static Builtin> {
    BUILTINS.iter().find(|b| b.name == name)
}
