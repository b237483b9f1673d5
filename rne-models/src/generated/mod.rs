//! The built-in robots' kernels, generated at compile time by `derive_dynamics!` from the
//! spec files in `rne-models/robots/`: one module per robot with every kernel, the scenes the
//! thesis's chapter 6 simulates ([`scenes`]), and the variants `rne bench` measures
//! ([`variants`]).

pub mod scenes;
pub mod variants;

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
    /// (ROBOTS.md).
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

rne_codegen::derive_dynamics! {
    /// The Universal Robots UR5 of the ros-industrial description (ROBOTS.md).
    pub mod ur5 {
        robot: "robots/ur5.urdf",
    }
}

rne_codegen::derive_dynamics! {
    /// The Franka Emika Panda with its hand and two fingers: 9 joints, a tree (ROBOTS.md).
    pub mod panda {
        robot: "robots/panda.urdf",
    }
}

rne_codegen::derive_dynamics! {
    /// The Franka Emika Panda arm to its flange, without the hand: 7 joints (ROBOTS.md).
    pub mod panda_arm {
        robot: "robots/panda-arm.urdf",
    }
}
