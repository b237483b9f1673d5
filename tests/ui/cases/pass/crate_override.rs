//! Generated code finds the runtime through a re-export named by `crate:`, and a joint is
//! locked by a string key.

mod reexport {
    pub use ::rne_codegen;
}

rne_codegen::derive_dynamics! {
    mod arm {
        robot: "specs/two_links.toml",
        outputs: [inverse_dynamics, gravity_torques],
        lock: { "q1": 0.0 },
        scalar: generic,
        crate: crate::reexport::rne_codegen,
    }
}

use rne_codegen::Dynamics;

fn main() {
    let model = arm::Model::<f64>::new();
    assert_eq!(arm::NQ, 1);
    assert!(model.gravity_torques(&[0.3]).is_some());
    assert!(model.mass_matrix(&[0.3]).is_none());
}
