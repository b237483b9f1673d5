//! The built-in robots' kernels, generated at compile time by `derive_dynamics!` from the
//! spec files in `rne-models/robots/`.

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
