//! `parameters: base` on a spec whose masses, lengths and inertias are named parameters
//! compiles: the macro reads the spec at its parameters' values (the base parameters'
//! combinations depend on the geometry), `Params` holds the base parameters rather than the
//! spec's names, and at `Params::default()` the kernels are the constant-parameter ones.

rne_codegen::derive_dynamics! {
    mod constant {
        robot: "specs/parameterised.toml",
        outputs: [inverse_dynamics, mass_matrix],
    }
}

rne_codegen::derive_dynamics! {
    mod base {
        robot: "specs/parameterised.toml",
        outputs: [inverse_dynamics, mass_matrix],
        parameters: base,
    }
}

fn main() {
    assert_eq!(
        base::BASE_PARAMETERS,
        [
            "upper.mcxR",
            "upper.mcy",
            "upper.IzzR",
            "lower.mcx",
            "lower.mcy",
            "lower.Izz"
        ]
    );
    let p = base::Params::default();
    let m2 = 2.0;
    assert!((p.upper_mcxR - (3.0 * 0.25 + m2 * 0.5)).abs() < 1e-12);
    assert!((p.lower_mcx - m2 * 0.2).abs() < 1e-12);
    let close = |a: &[f64], b: &[f64]| {
        let scale = b.iter().fold(1.0f64, |s, v| s.max(v.abs()));
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-13 * scale)
    };
    for k in 0..20 {
        let t = k as f64;
        let (q, qd, qdd) = (
            [0.3 * t - 2.0, 1.1 - 0.2 * t],
            [0.5 * t.sin(), t.cos()],
            [1.0 - 0.1 * t, 0.4 * t - 3.0],
        );
        assert!(close(
            &base::inverse_dynamics(&p, &q, &qd, &qdd),
            &constant::inverse_dynamics(&q, &qd, &qdd),
        ));
        assert!(close(
            base::mass_matrix(&p, &q).as_flattened(),
            constant::mass_matrix(&q).as_flattened(),
        ));
    }
}
