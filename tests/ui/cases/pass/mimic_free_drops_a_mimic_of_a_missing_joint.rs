//! With `mimic: free` the same file compiles: the dangling mimic is dropped with a warning
//! (listed in the module's docs) and the follower is a joint of its own.
#![deny(missing_docs)]

rne_codegen::derive_dynamics! {
    /// A finger whose mimic names a joint the robot does not have.
    pub mod hand {
        robot: "specs/dangling_mimic.urdf",
        outputs: [mass_matrix],
        mimic: free,
    }
}

fn main() {
    assert_eq!(hand::NDOF, 1);
    assert_eq!(hand::JOINTS, ["finger_q2"]);
    let m = hand::mass_matrix(&[0.0]);
    assert!((m[0][0] - (0.001 + 0.1 * 0.05 * 0.05)).abs() < 1e-15, "{m:?}");
}
