//! A robot file with a warning compiles by default (the warning is listed in the module's
//! docs) and with `validation: warn`.
#![deny(missing_docs)]

rne_codegen::derive_dynamics! {
    /// A link whose inertia breaks the triangle inequality.
    pub mod arm {
        robot: "specs/triangle.toml",
        outputs: [gravity_torques],
        validation: warn,
    }
}

fn main() {
    assert_eq!(arm::NDOF, 1);
    assert_eq!(arm::gravity_torques(&[0.3]), [0.0]);
}
