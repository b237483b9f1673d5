//! The built-in robots' kernels, generated at compile time by `derive_dynamics!` from the
//! spec files in `rne-models/robots/`: one module per robot with every kernel, the scenes the
//! thesis's chapter 6 simulates ([`scenes`]), and the variants `rne bench` measures
//! ([`variants`]).

/// `derive_dynamics!` for a URDF robot's module that `rne bench --pinocchio` sets beside
/// Pinocchio: as written, with `fma: true` added under the crate feature `fma` and
/// `derivatives: lanes` under the crate feature `derivative-lanes`, so that a build for the
/// machine (`RUSTFLAGS="-C target-cpu=native"`) compares fused kernels, and derivatives four
/// directions per AVX instruction, with Pinocchio's CppADCodeGen code, which gcc builds with
/// `-march=native`. (In a baseline x86-64 build the lanes' vectors are pairs of SSE2
/// registers and the derivatives in lanes are slower than without: docs/performance.md.)
/// The settings end with a comma.
macro_rules! beside_pinocchio {
    ($(#[$doc:meta])* pub mod $name:ident { $($settings:tt)* }) => {
        #[cfg(not(feature = "fma"))]
        in_lanes_if_asked! { $(#[$doc])* pub mod $name { $($settings)* } }
        #[cfg(feature = "fma")]
        in_lanes_if_asked! { $(#[$doc])* pub mod $name { $($settings)* fma: true, } }
    };
}

/// `derive_dynamics!`, with `derivatives: lanes` added under the crate feature
/// `derivative-lanes` (the second half of [`beside_pinocchio`]).
macro_rules! in_lanes_if_asked {
    ($(#[$doc:meta])* pub mod $name:ident { $($settings:tt)* }) => {
        #[cfg(not(feature = "derivative-lanes"))]
        rne_codegen::derive_dynamics! { $(#[$doc])* pub mod $name { $($settings)* } }
        #[cfg(feature = "derivative-lanes")]
        rne_codegen::derive_dynamics! {
            $(#[$doc])* pub mod $name { $($settings)* derivatives: lanes, }
        }
    };
}

pub mod scenes;
pub mod variants;

/// Whether the URDF robots' default and `control` modules were generated with `fma: true`
/// (the crate feature `fma`, for `rne bench` in a native build).
pub const FUSED_MULTIPLY_ADD: bool = cfg!(feature = "fma");

/// Whether the URDF robots' default and `control` modules were generated with
/// `derivatives: lanes` (the crate feature `derivative-lanes`, for `rne bench` in a native
/// build).
pub const DERIVATIVE_LANES: bool = cfg!(feature = "derivative-lanes");

rne_codegen::derive_dynamics! {
    /// The planar elbow manipulator of the thesis's chapter 4 (table 6.1).
    pub mod planar_elbow {
        robot: "robots/planar-elbow.toml",
    }
}

rne_codegen::derive_dynamics! {
    /// The first three joints of the ABB IRB 140 (thesis chapter 5, table 6.2).
    pub mod irb140_3dof {
        robot: "robots/irb140-3dof.toml",
    }
}

rne_codegen::derive_dynamics! {
    /// The PUMA 560 in standard DH form with Corke & Armstrong-Helouvry's parameters
    /// (ICRA 1994).
    pub mod puma560 {
        robot: "robots/puma560.toml",
    }
}

rne_codegen::derive_dynamics! {
    /// The ABB IRB 140 with all six joints: the thesis's first three and ABB's wrist geometry,
    /// with estimated wrist inertials (see the spec's comments).
    pub mod irb140 {
        robot: "robots/irb140.toml",
    }
}

beside_pinocchio! {
    /// The Universal Robots UR5 of the ros-industrial description (`universal_robot`).
    pub mod ur5 {
        robot: "robots/ur5.urdf",
    }
}

beside_pinocchio! {
    /// The Franka Emika Panda with its hand and two fingers: 9 joints, a tree
    /// (`franka_description`, inertials of Gaz et al., RA-L 2019).
    pub mod panda {
        robot: "robots/panda.urdf",
    }
}

beside_pinocchio! {
    /// The Franka Emika Panda arm to its flange, without the hand: 7 joints
    /// (`franka_description`, inertials of Gaz et al., RA-L 2019).
    pub mod panda_arm {
        robot: "robots/panda-arm.urdf",
    }
}
