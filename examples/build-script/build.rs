//! Generates the planar elbow's dynamics into `$OUT_DIR/planar_elbow.rs`, which `src/lib.rs`
//! includes: the module `derive_dynamics!` would expand to, written by a build script.

use rne_codegen::{Builder, Kernel};

fn main() {
    let outputs = [
        Kernel::InverseDynamics,
        Kernel::MassMatrix,
        Kernel::GravityTorques,
    ];
    // A relative path is read from this crate's directory; the build script is rerun when the
    // file changes.
    Builder::new("../../rne-models/robots/planar-elbow.toml")
        .outputs(&outputs)
        .write("planar_elbow.rs")
        .unwrap_or_else(|error| panic!("{error}"));
}
