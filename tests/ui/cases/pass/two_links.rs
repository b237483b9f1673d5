rne_codegen::derive_dynamics! {
    /// Doc comments and attributes are kept on the module.
    #[allow(dead_code)]
    pub mod arm {
        robot: "specs/two_links.toml",
        outputs: [inverse_dynamics, forward_dynamics],
        gravity: [0.0, 0.0, -9.81],
        lock: { q2: 0.5 },
        parameters: constant,
        scalar: f64,
        fma: true,
    }
}

fn main() {
    assert_eq!(arm::NDOF, 1);
    let tau = arm::inverse_dynamics(&[0.1], &[0.2], &[0.3]);
    let qdd = arm::forward_dynamics(&[0.1], &[0.2], &tau);
    assert!((qdd[0] - 0.3).abs() < 1e-12);
}
